// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The discrepancy workflow (`fit3dof diagnose`): fit the model as
// configured, decide whether the residuals are measurement noise, and if
// not find the missing effect, add it, refit, and repeat (the report's
// Section 5.3 done systematically).
//
// Noise or model? The residuals are at the noise level when the probable
// error (Eq. 26, residuals in units of the configured sigma) is below
// `noise_limit` (1.1), no channel's residual has a lag-1 autocorrelation
// above `whiteness_limit` (0.3), and the periodogram of theta + i psi has
// no line above `spectral_limit` (4 ln N) times its mean, nor above what
// noise reaches with chance 1e-3 against the mean of the line's own
// neighbourhood (a line out of a colored spectrum; that mean taken as at
// least half the periodogram's, as the fit empties the bins near the
// modes it fits): measurement noise
// is white with a flat spectrum, a missing effect leaves slow, structured
// residuals with lines near the motion's frequencies. On short records the
// first two limits rise to what noise reaches with chance 1e-3:
// E^2 <= 1 + 3.09 sqrt(2 / dof) and lag-1 <= 3.09 / sqrt(n) (one-sided: a fit
// lowers the lag-1 autocorrelation of noise, a missing effect raises it).
//
// sigma: auto (the noise unknown). Each fit would weigh by its own RMS
// residual, every probable error would be 1 and the BICs would not
// compare. So the noise is held for the whole search (noise_held): each
// auto channel's the lesser of the nominal fit's RMS residual and the
// data's model-free level (noise_relaxation.h DataNoiseDeg), pooled over
// the segments; held again, and searched once more (twice at most), at a
// fit of the search's level when that leaves a channel 1.3 times or more
// below it (structure near the Nyquist frequency passes for noise
// model-free), or, where the search found the record at the noise level
// (with effects named or not), when every fit leaves a channel 1.3 times
// or more above it, white (a noise draw short of high frequencies, or
// reading errors whose slow part the differences miss, hold it low
// model-free, and the probable error it inflates blurs the other channels'
// evidence or puts a false effect past the BIC margin).
// The level limit widens by that estimate's own spread,
// E^2 <= 1 + 3.09 sqrt(2 / dof + 7.3 / n) (1.51 on 47 samples, 1.14 on 800),
// and the search goes on past the noise level while an effect earns its
// place (a round there refits only when some candidate's score, less
// ln(n) per parameter, reaches min_bic_drop). The rerun config keeps
// sigma: auto.
//
// With sigma given the search stops at the noise level, save for a round
// for the nominal fit's near twins; an explained or ambiguous answer whose
// model some contender beside it lowers BIC by more than `min_bic_drop` is
// searched
// again with one round past the noise for those effects
// (DiagnoseOptions::past_noise), each earning its place as in any round
// (docs/diagnose.md, "Sigma and the noise").
//
// Which effect? Every catalog effect not yet in the model is scored at the
// current solution by a score (Lagrange-multiplier) test: with g = J_c^T r
// the gradient of the cost along the candidate's parameters (at zero) and
// S_c = I_cc - I_cf I_ff^-1 I_fc the candidate's information after the
// parameters already free have taken what they can (the Schur complement,
// which handles correlation with them, e.g. Cm_alpha, t1, t3 of Eq. 43),
//   LM = g^T S_c^+ g / E^2
// is the predicted drop of the weighted residual sum of squares in units of
// the residual variance. The score is a local (linear) prediction and
// underrates large effects (a product of inertia that moves roll by degrees
// ranked fourth in a test), so the best `refit` (5) candidates are refitted
// in full (and any scored within 5% of the fifth: the ranking there is
// within the linearization's error);
// the one with the lowest Bayesian information criterion,
//   BIC = n ln(RSS / n) + k ln(n)   (n residuals, k free parameters),
// is a contender if it lowers BIC by more than `min_bic_drop` (10: very
// strong evidence).
//
// Never a confident wrong answer. A contender is added only when it earns
// its place (effect_validation.cc):
//   - plausible: its values within the bounds of its effect (reading
//     errors up to 0.2 deg, a calibration error up to 0.2 deg or 3% of the
//     channel's largest angle (a determined one up to 3% or three noise
//     sigmas where 0.2 deg is more), |I_zx| up to 5% of I_y, a trim angle
//     up to 2 deg, a tunnel stiffness up to half and a tunnel damping up
//     to twice the record's stiffness or damping, nonlinear terms that
//     change the linear ones (or these plus Eq. 39's tunnel term on their
//     axis, where larger) by at most 4 times their size over the record;
//     EffectCatalog lists each), and so are, in its fit, the
//     effects added before it (a newcomer that pushes one of them past
//     its bound makes a model no more plausible than that);
//   - not dragging the coefficients: unless it explains the record down
//     to the noise, no coefficient free before it moves by more than
//     `max_drag` (5) of its own standard error times the factor by which
//     the effect lowers the probable error. (A missing effect's bias hides
//     in the fit: the part of it the coefficients absorb leaves no
//     residual, so no error bar of the fit without it covers the move; an
//     effect that explains everything may move them as far as it must,
//     one that explains a little must not move them far);
//   - not carried by one reading: a reading whose weighted square residual
//     falls by more than half the whole drop, the rest of the record
//     lowering BIC by less than `min_bic_drop` without it, refuses the
//     effect (a lag filter starting at rest left the first pitch reading
//     12 robust sigmas off; a nonlinear damping bent the motion there and
//     lowered BIC by 19.8, every other reading fitting worse), nor by
//     readings in counts at their rounding, nor, where the model with it
//     reaches the noise level, by reading errors that are not white: its
//     drop weighed again with the residuals whitened as the AR(1) errors
//     that model leaves (their pooled lag-1 autocorrelation, when
//     positive) must still reach `min_bic_drop` (correlated errors hold
//     more power at the motion's low frequencies than their level says);
//     Effects that only together explain the record may each drag alone
//     (each moves the coefficients that the others biased): when a
//     contender is refused for its drag and none with a lower BIC earned
//     its place (the best may be refused otherwise), the first such is
//     fitted with one or two of three others (a joint set), drawn in the
//     order of BIC: the contenders ranked above it that failed alone only
//     to predict the held-out part, those below it, then the round's
//     refits that lowered BIC by less than `min_bic_drop`, each only in a
//     pair with the lead (a tunnel stiffness lowering BIC by 3 beside a
//     nonlinear damping that dragged Cn_r, alone among the contenders,
//     made the record with both),
//     and the lowest-BIC pair that reaches the noise level, keeps every
//     effect in the model within its bounds and predicts the held-out
//     part better (as below, per parameter it adds) is adopted, or when
//     no pair does, the lowest-BIC triple that does (a third effect that
//     belongs is left to the next round), its
//     effects as steps in turn (DiagnosisStep::note); a step adopted alone
//     has rivals, so does each of them (a roll-locked one its twins too);
//   - out of sample: each segment cut into `held_out_blocks` (8) runs of
//     samples, every other one held out (the first, where the initial
//     conditions hold, kept); fitted to the kept samples with and without
//     it, the model predicts the held-out ones better with it
//     (log-likelihood gain n_held ln(RSS_without / RSS_with) above 2 per
//     parameter it adds, AIC's price). A positive gain short of that
//     gets a second chance: the other half held out in turn (the first
//     reading still kept), whose gain must clear the bar. Held-out runs
//     spread over the record test an effect at every amplitude and spin
//     rate the record has: a calibration error that lives at the large
//     early angles would go untested in a held-out final third.
// When other contenders come within `ambiguity_bic` (10) of the BIC of
// the best that earned its place (whether or not they earned theirs: the
// effects still missing may be what refused them), the search follows the
// best and remembers the others; once the record is explained, a rival
// swapped in
// for the effect it tied with that still keeps BIC within `ambiguity_bic`
// (and its values within bounds) makes the verdict `ambiguous` and none of
// them is added: their fits are reported with what would separate them
// (another spin rate, amplitude or dynamic pressure). A rival that loses
// by more once the other effects are in is no longer one; two roll-locked
// effects stay rivals unless a record spins above half the pitch
// frequency (nothing slower separates them). The final swap also tries
// the contenders within `rival_bic` (30) of a step's best, tied or not:
// while effects are missing, a round's BIC gaps hold their signatures too
// (a roll torque adopted 21 below a tunnel stiffness that, with the
// others in, explained the record 3 better), and for a roll moment Eq.
// 39's tunnel stiffness whatever the gap (its roll part is the moment's
// signature; one 48.6 behind came within 3 once the others were in). Ties
// at later steps are judged alike and reported beside the first
// (Diagnosis::later_ties). A tie that leaves the residuals
// structured is only part of the story: the search goes on with the
// best of them in the model, and if the record then reaches the noise
// the verdict is `ambiguous`, else `not_explained`. The effects found
// after the tie, up to a second tie, are adopted when the record needs them
// whichever of the tied effects is in it: with the followed one swapped
// for each rival they still lower BIC by more than `min_bic_drop`, and
// without any they do so against the model before the tie, all within
// their bounds, and (unless every complete model reaches the noise) not
// dragging the coefficients (a Magnus moment beside a roll-synchronous
// reading error that ties with a trim moment). The final model is then
// the one before the tie with them added (Diagnosis::alternatives holds
// the complete model with each tied effect, a later tie's followed effect
// in). A step out of its bounds without the tied effect that a rival in
// its place does not need goes with the tied effect (partial): a roll
// damping taken after a roll torque that ties with a tunnel stiffness.
// When they need one of the tied effects (without any, they leave their
// bounds: a calibration error beside a bearing moment, with a roll
// damping and a roll torque tied), every complete model reaches the noise
// and each of them is needed in each, it is the complete model with the
// first tied effect standing in for the tie (Diagnosis::stand_in);
// otherwise it is the one before the tie, the tied effect and those after
// it reported as partial. When the branch
// followed ends `not_explained`, the search is run again without the
// effect it followed, and its answer is taken when it explains the
// record, with or without a tie of its own (the effect left is named
// among the rejected). So is a first step taken alone whose next
// contender came within `near_tie_bic` (40) of it, or led by more while
// an effect not excluded still lowers BIC beside the answer, when the
// answer is `ambiguous`, claims that step's effect, and without it the
// search explains the record with a BIC lower by more than
// `ambiguity_bic`; and
// the effect a tie followed when the complete model with another of its
// effects is lower than the one with it by more than `ambiguity_bic` (a
// swap that lowers BIC keeps a tie open): the search without it is taken
// when it explains the record as well as that other side. And a search
// that took steps, no tie among them, and adopted none (each left the
// residuals structured; no probe outdid them) is run again without its
// first step's effect, whose answer is taken when it explains the record:
// a body yaw asymmetry that led the first round of a 3-s run by 26 of BIC
// had left every true effect failing alone to predict the held-out part.
// An `ambiguous` answer's step that none of its complete models needs
// (without it each stays at the noise level, BIC rising by less than
// `min_bic_drop`) is searched without too, and that answer is taken when
// it explains the record with no effect the first did not add or tie and
// a complete model no more than `min_bic_drop` above. A step that the
// complete model with the followed tied effect needs and a rival's does
// not (by the same rule) goes with that effect: reported after it among
// the partial steps, not added.
// A roll-locked effect (Effect::roll_locked) on records that span less
// than a revolution of roll ties with a drift in time (`drift_in_time`,
// outside the catalog): the record is then `ambiguous` at best, and a
// record spanning a revolution, or a second run at another spin rate,
// separates them.
// Each round also scores ten probes outside the catalog: a drift of the
// pitch and yaw readings in time (theta_drift, psi_drift), a dynamic
// pressure drifting during the run (q_drift), a lag of the readings (a
// filter's: theta_lag, psi_lag), a pitch reading's gain off the yaw
// reading's (theta_gain), a flow whose stiffness differs between the
// tunnel's pitch and yaw planes without Eq. 39's roll torque (Cn_beta_flow)
// and dry friction, in the bearing against the pitch-yaw rate
// (Cm_friction), about each axis alone (Cm_axis_friction) or about the pitch
// or the yaw axis alone (Cm_pitch_friction, Cn_yaw_friction), and a
// reading error at the second harmonic of roll (theta_cos_2phi, ...;
// docs/parameters.md; a probe declared absent is not scored), and refits
// the two with the largest scores. The best of
// those (lowest BIC) whose lag or friction has its physical sign (a lead,
// or a friction that drives the motion, beyond two errors is no fault of
// those kinds: a negative axis friction had tied with a 3-s run's tunnel
// damping) is compared, when no catalog effect, refused or not, explains
// more; it is never adopted. When it lowers BIC by more than
// `ambiguity_bic` below the best catalog effect that earned its place
// (that effect charged only for the parameters the record determines: a
// bearing moment's angle whose standard error exceeds it is not) (or by
// `min_bic_drop` when none did, and it predicts the held-out part of the
// record as a newcomer must: else it is listed among the rejected and the
// round ends as if no probe had been fitted; a pressure drift past the noise
// level a roll reading error held had ended a 3-s run `not_explained`),
// nothing is added and the verdict is
// `not_explained`, naming it and its values (Diagnosis::outside_catalog): on
// two runs a roll-synchronous reading error and a zero offset had been adopted
// for a drifting pitch reading. When the best is roll-locked and the records
// sweep less than a revolution of roll (it is then a drift in time itself), a
// drift probe with fewer parameters than it needs only `drift_bic` (2): better
// by that, the verdict is `not_explained` (a pitch reading drift on one 3-s run
// had ended `ambiguous` with a roll reading error of twice its parameters);
// closer, the two tie (a trim moment had been left unexplained for a drift
// better by 0.4). With as many (a trim moment's two against the readings'
// drift's two) the margin is `ambiguity_bic`, as for any probe. Otherwise,
// within `ambiguity_bic` of the best, it ties with it (`ambiguous`): on one 3-s
// run a bearing moment (a stiffness that grows as the amplitude decays) and a
// drifting dynamic pressure do; a drifting pressure had been named a bearing
// moment. Behind the best by less than `probe_behind_bic` (2), the best is
// taken and the probe named beside its step (DiagnosisStep::outside_alike). A
// probe is weighed against one catalog effect at a time: when it wins (at the
// noise level too, where its chi-square leaves room for a catalog model to beat
// it by the margin), the diagnosis without probes is run too; when that
// explains the record (or ties with every branch explained) with a BIC lower
// than the probe's model's by more than `ambiguity_bic`, it is the answer (a
// reading lag had beaten a Magnus moment at the first step of a record a Magnus
// moment, a nonlinear damping and a calibration error explain). Unless the
// probe, given the same search (the catalog's effects beside it), explains the
// record with a BIC lower than that answer's by more than `ambiguity_bic`, a
// lag or a friction of its physical sign (positive): then the verdict stays
// `not_explained`, naming the effects that would complete the probe
// (outside_catalog_beside). A dry friction on the pitch axis alone had got a
// nonlinear damping and a body yaw asymmetry (Cm_q 15 of its errors off the
// nominal fit's); the ball's friction with a tunnel damping beside it explains
// that 3-s run better. Within `ambiguity_bic` of that answer the answer stands,
// and its verdict names the probe's model as one that explains the record
// alike, with what would separate them (outside_catalog_alike). Every effect
// that was a contender at some round of the search (it lowered BIC by more than
// `min_bic_drop` there, however far behind the round's best) and is neither in
// the model nor in a tie is also tried beside the complete model (added, not
// swapped). One the record cannot exclude there (BIC less than `ambiguity_bic`
// higher, the model's effects within their bounds, its own within two of its
// standard errors of them: on a ridge the point fit lands anywhere the record
// allows) is not added, but the final error bars cover its model's
// values, weighted by its Akaike weight against the model without it
// (Diagnosis::not_excluded). A Magnus moment
// beside a tunnel damping that had absorbed it on one coning run moved
// Cm_q by 138 of its errors. A tie whose final model falls short of the
// noise (the model before the tie) has each tried beside it and beside the
// search's model (the tied effect it followed in), listed beside the
// latter first; beside the final one an effect may explain part of what the
// tied ones do (a body asymmetry lowered BIC by 77.6 there; it had been
// called "not needed"), and its values widen the final error bars all the
// same.
// When the record is explained by several effects, each is checked again
// with the others in (backward elimination): one whose removal keeps the
// residuals at the noise level and costs less than `min_bic_drop` of BIC,
// the others within their bounds without it, is dropped
// (Diagnosis::pruned). Segments diagnosed together (runs
// at different spin rates) separate what one run cannot. When the
// residuals stay structured and nothing earns its place the verdict is
// `not_explained`, with a description of what the residuals show (lines
// against the modal and spin frequencies, a trend in time, a dependence
// on the angle or on roll). Every added effect is reported with the final
// model's values.

#ifndef FIT3DOF_DIAGNOSE_H_
#define FIT3DOF_DIAGNOSE_H_

#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "fit3dof/case.h"
#include "fit3dof/fit.h"

namespace fit3dof {

struct Effect {
  std::string id;
  std::string description;
  std::vector<std::string> symmetric;   // parameters in the symmetric model
  std::vector<std::string> asymmetric;  // and in the asymmetric one
  bool to_asymmetric = false;           // needs the asymmetric program
  // Values the effect's terms need when the case has none (the bearing
  // moment's bearing_angle), freed with its parameters.
  std::vector<std::pair<std::string, double>> companions;
  // What a second run would change to tell it from an effect of the same
  // signature ("spin rate", "amplitude", "dynamic pressure").
  std::string separated_by;
  // Its plausibility bounds, in words (effect_validation.cc checks them).
  std::string bounds;
  // Its signature is a first harmonic of roll (a body-fixed trim, a
  // roll-synchronous reading error): over less than a revolution of roll
  // it is a slow change in time, which a drift of the readings or of the
  // flow (outside the catalog) makes as well. On such records it is never
  // adopted alone (diagnose.h).
  bool roll_locked = false;
  // A probe that is a drift in time (of the readings, of the dynamic
  // pressure): over less than a revolution of roll a roll-locked effect is
  // one too, and such a probe beats it by any evidence at all (ProbeMargin,
  // DiagnoseOptions::drift_bic).
  bool drifts_in_time = false;
  // Its terms lie on a ridge with the body's own coefficients: only a
  // combination is determined, and a point fit lands anywhere along it the
  // record allows. Eq. 43's tunnel terms (Cm_alpha + t1, Cm_q + t2: a
  // tunnel stiffness's t1 = t3 = -0.134 +- 0.048 on a coning run, truth
  // 1.8e-4, where the true model's own fit lands too); a nonlinear damping
  // on a 3-s run (Cm_q + 0.0049 Cm_q_delta2, the two 99.96% correlated:
  // a true 4.0 times |Cm_q| over the record fitted at 4.02, past the bound
  // of 4); a bearing moment whose angle is small against the record's
  // (Cm_alpha + Cm_bearing, 99.9994% correlated on a pair of runs: a true
  // 0.5 deg fitted at 9.0 +- 12.8, past the record's 8.0). A second search
  // judges its bounds within two of its errors
  // (DiagnoseOptions::bounds_within_errors).
  bool on_ridge = false;
  // Probes (Probes()) or other forms (OpenForms()) whose terms the
  // effect's form leaves open: a calibration nonlinearity written as a
  // cube takes none of the linear part a real one has, which the report's
  // linear calibration fit took an unknown share of (as much as its range
  // made it); what is left is a gain error, the reading_gain probe's. Nor
  // does a cube grow as a signed square does (calibration_square). Not
  // fitted with the effect; each freed beside each complete model that
  // holds it, and where the record cannot exclude it, the final error
  // bars cover that fit (Diagnosis::open_terms).
  std::vector<std::string> leaves_open = {};
  // Another form of the effect (OpenForms()) that a round of the search
  // tries in its place, taken where the refits put it 10 lower in BIC
  // than the effect's own (and sent back where later steps no longer
  // do): a calibration error growing as the angle's signed square, less
  // the straight line a linear calibration over the readings' range took
  // of it (theta_cal2, psi_cal2; cal_range held where the config gives it, else
  // at the largest angle). On
  // a coning run, the cube in its place left a difference of the two
  // readings' gains: an elliptical look that a tunnel stiffness, a flow
  // stiffer in one plane or a body asymmetry gives a circular cone, and
  // one was named beside it (4 draws of 14). Named by the effect's own
  // id; its terms are the form's.
  std::string other_form = {};

  // Its parameters in the program `model` (symmetric or asymmetric).
  const std::vector<std::string>& Terms(ModelKind model) const {
    return model == ModelKind::kSymmetric ? symmetric : asymmetric;
  }
};

const std::vector<Effect>& EffectCatalog();
// The entry called `id`, or nullptr.
const Effect* FindEffect(const std::string& id);
// Whether `id`, as a diagnosis names it (a step, a contender, a tie), is an
// explanation outside the catalog: a probe, or `drift_in_time`.
bool OutsideCatalog(const std::string& id);

struct DiagnoseOptions {
  double noise_limit = 1.1;
  double whiteness_limit = 0.3;
  double spectral_factor = 4.0;  // spectral_limit = factor * ln(N)
  int refit = 5;
  double min_bic_drop = 10.0;
  double ambiguity_bic = 10.0;
  double rival_bic = 30.0;
  // When the answer is `ambiguous` and claims the effect of a first step
  // taken alone with its next contender (not refused) within near_tie_bic
  // of it, the record is searched again without that effect; that search's
  // answer is taken when it explains the record with a complete model lower in
  // BIC by more than ambiguity_bic (the greedy search's wrong turn), and
  // stands in a tie with the step within ambiguity_bic. Led by more, the
  // step is searched without only where an effect not excluded still
  // lowers BIC beside the answer, and that search is taken only when
  // better by more than ambiguity_bic (a lead of 42 on draw 37). At
  // the first step every effect is still missing and the leads mislead
  // most: a false body asymmetry has led a 3-s run's true first effect by
  // 14.6, 17.4, 26 and 33.6 on four noise draws.
  double near_tie_bic = 40.0;
  // How much lower a drift probe's BIC must be than a roll-locked effect's
  // with more parameters on records that sweep less than a revolution of
  // roll, for the record to be not explained: a difference under 2 is no
  // evidence either way (Kass and Raftery's scale), and the two tie.
  double drift_bic = 2.0;
  // How far behind the effect a step takes a probe may come and still be
  // named beside it (DiagnosisStep::outside_alike): by less than 2 the
  // record holds no evidence for the catalog's effect over the
  // explanation outside it (a tunnel damping named `explained`, a
  // pitch-axis friction probe 0.5 behind it, on a record that friction
  // made, had said nothing of it). A probe ahead ties within
  // ambiguity_bic.
  double probe_behind_bic = 2.0;
  // How much lower in complete BIC the search without a step whose joint
  // partner tied (WithoutTiedPartner) must come than the first answer to
  // replace it: by less than 2 the record holds no evidence either way.
  // On draw 124's 3-s run with a tunnel damping, a Magnus moment and a
  // flow angularity (sigma: auto) the first answer named the damping and
  // the Magnus moment, the angularity tied; the search without the damping
  // named a body asymmetry and a false nonlinear damping, 1.6 lower, and
  // had been taken. A partner tied only with rivals that move the
  // complete model's BIC by less than this in its place (its twins) does
  // not call for that search: the step stands with either.
  double partner_search_bic = 2.0;
  double max_drag = 5.0;
  int held_out_blocks = 8;
  double gain_per_parameter = 2.0;
  // Where a model's gain on the odd runs held out is positive but short
  // of gain_per_parameter per term, the even runs are held out in turn
  // and that gain may clear the bar (OutOfSample::GainOfBothHalves);
  // false judges by the odd runs alone, as diagnose did before the 69th
  // session (the tests that pin a rule found on such a record).
  bool held_out_both_halves = true;
  int max_steps = 5;
  // The case's sigma is the noise the record itself gave, held for the
  // search (Diagnose sets it for sigma: auto): the level is a blunter test
  // (its limit widens by the estimate's spread, CheckResiduals), so the
  // search goes on past it while an effect earns its place, and residuals
  // below it are no sign of a sigma set too large.
  bool noise_held = false;
  // Integrate the search's fits at the coarsest step the record allows
  // (SolverOptions::search_step, integration_step.h): every fit within
  // 0.1 of its errors of the fit at the config's step, or fitted again at
  // a finer step, at the config's last. On draw 0's 3-s pair of runs with a
  // bearing moment, a calibration error and a roll torque (step 2 ms) the step
  // was 8 ms and the diagnosis 3.2 times faster, its answer the same. False:
  // every fit at the config's step (fit3dof diagnose --exact_step).
  bool coarse_search = true;
  std::vector<std::string> effects;  // restrict the catalog (empty: all)
  // Catalog effects the engineer knows absent (a tunnel without flow
  // gradients, a bearing calibrated for the run): never tried, so never
  // tied, never a near twin and never in the final error bars, which are
  // then the final model's own where only those effects widened them.
  // Probes may be named too (a ball bearing without gimbal pivots has no
  // pitch_friction or yaw_friction): never fitted.
  std::vector<std::string> absent;
  bool probes = true;  // fit the probes outside the catalog
  // Try an effect's other form in its place (Effect::other_form).
  bool other_forms = true;
  // Fit a contender refused for its drag with the next ones (a joint set).
  bool joint_sets = true;
  // Let a contender refused for leaving its bounds lead a joint set too.
  // Diagnose sets it itself for a second search when the first ends
  // `not_explained` with such a contender ahead of every one that earned
  // its place.
  bool joint_sets_from_bounds = false;
  // Effects a round at the noise level may still add (sigma given), each
  // earning its place as in any round. Diagnose names them itself for a
  // second search when an explained answer leaves one that lowers BIC
  // beside its model by more than min_bic_drop (not_excluded).
  std::vector<std::string> past_noise;
  // Judge the bounds of a contender on a ridge (Effect::on_ridge)
  // within two of its standard errors (moved that far toward zero), as
  // the effects not excluded are judged, rather than at the point fit.
  // Set with joint_sets_from_bounds for the second search.
  bool bounds_within_errors = false;
  // With bounds_within_errors, judge every contender's bounds so, on a
  // ridge or not: the third search, where the second leaves the record
  // unexplained too.
  bool every_bound_within_errors = false;
  // Catalog effects a second search leaves out (its effects hold them no
  // more): the side of a tie or the step another answer outdid. Not
  // contenders there, but tried beside its complete model like every
  // contender (not_excluded): on a coning run sweeping 68 deg of roll, a
  // flow angularity is a sum of the roll interaction's terms, and the
  // answer found without it cannot exclude it.
  std::vector<std::string> searched_without;
  // Set by diagnose for the search that weighs a probe outside the catalog
  // with the catalog's effects beside it (its model the probe's): that
  // search's second thoughts do not search again without a step (whose
  // joint set's partner tied, that blocked a round's best, taken first, or
  // outdone in a swap): the catalog's own search had them.
  bool beside_probe = false;
  // Set by diagnose for the diagnosis without an effect that, taken early,
  // alone refused a later round's best contender (BlockerBranch): that
  // diagnosis does not search without another such.
  bool without_blocker = false;
  // Set by diagnose for the diagnosis without the first step of a search
  // that adopted nothing and tied at a later step (DeadEndBranch): that
  // diagnosis does not search without its own first step so.
  bool without_dead_end = false;
  // Set by diagnose for a second thought's search whose answer is taken
  // only when it explains the record with a complete model below this BIC:
  // where a probe outside the catalog outdid that search, the catalog's
  // answer above it is not weighed against the probe beside its effects
  // (it could not be taken, whoever won). One search's: the diagnoses
  // nested in it do without.
  double explain_below = std::numeric_limits<double>::infinity();
};

struct ResidualCheck {
  double probable_error = 0.0;
  ChannelValues rms_deg;
  ChannelValues lag1;  // autocorrelation at lag 1
  // Periodogram of the complex residual theta + i psi (first segment): the
  // largest power over the mean power, and where it sits. White noise
  // gives about ln(N); a missing effect a sharp line near the motion's
  // frequencies.
  double peak_ratio = 0.0;
  double peak_frequency_hz = 0.0;
  // The same peak over the mean of its neighbours: a line standing out of
  // a colored spectrum (residual_check.cc).
  double line_ratio = 0.0;
  bool at_noise_level = false;
  // Apart from their size: no channel's lag-1 autocorrelation and no line
  // beyond the limits. White residuals larger than sigma are noise larger
  // than configured as much as a missing effect; white residuals smaller
  // than noise reaches with chance 1e-3 (below_sigma) mean sigma is larger
  // than the noise, and an effect that raises them to `noise_limit` passes
  // unseen.
  bool white = false;
  bool below_sigma = false;
  double noise_limit = 0.0;  // the largest probable error noise reaches
  // Whether the residuals depend on nothing the model knows: no trend in
  // time, no dependence on the pitch or yaw angle or on roll stands out
  // (ResidualsDepend). The search goes by at_noise_level; a model explains
  // the record only with this too (Explains).
  bool independent = true;
  // The largest lag-1 autocorrelation of a channel's residual noise
  // reaches (`white` holds every channel's below it).
  double whiteness_limit = 0.0;
};

struct CandidateScore {
  std::string effect;
  double score = 0.0;  // LM statistic
  int dof = 0;         // directions not already spanned
  // The least part of the information in any direction of the effect's
  // terms that the free parameters do not already carry: 1 - R^2 of a
  // one-term effect on them. Near 0, the effect is a near twin of
  // parameters already free: a refit moves them, not the residual, so its
  // score stays low however much it drags them.
  double novelty = 1.0;
};

// How a term of a near twin of the free parameters would move one of them
// (diagnose_internal.h TwinShifts): fitted without the term, the
// parameter stands for itself plus per_unit times the term.
struct TwinShift {
  std::string term;
  std::string parameter;
  double per_unit = 0.0;
};

// A catalog effect the record cannot tell from the fitted coefficients
// (Diagnosis::coefficient_twins): its score there, and what it would move.
struct CoefficientTwin {
  CandidateScore score;
  std::vector<TwinShift> shifts;
  // Whether the shifts are the final model's (they are the first complete
  // model's: the search's last, when a tie's final model is short of the
  // noise).
  bool in_final_model = false;
};

// A contender refitted in full, and whether it earned its place.
struct CandidateFit {
  std::string effect;
  std::vector<ParameterEstimate> parameters;  // its own, as fitted
  double bic_drop = 0.0;
  // Out of sample: n_test ln(RSS_without / RSS_with) over the held-out
  // part (NaN when not checked).
  double prediction_gain = 0.0;
  std::string rejected;  // why it did not earn its place; empty if it did
};

struct DiagnosisStep {
  std::string effect;
  std::string description;
  // The effect's parameters in the final model, and as this step fitted
  // them.
  std::vector<ParameterEstimate> parameters;
  std::vector<ParameterEstimate> step_parameters;
  double score = 0.0;
  double bic_drop = 0.0;
  double prediction_gain = 0.0;
  std::vector<CandidateScore> ranking;
  std::vector<CandidateFit> contenders;  // every refit of the step
  ResidualCheck after;
  // Why a pruned step was dropped, or that the step was adopted together
  // with others (a joint set).
  std::string note;
  bool joint_set = false;  // adopted together with others
  // A joint set's other members (ids), which this step was adopted with.
  std::vector<std::string> adopted_with;
  // Diagnosis::fits of the model before and after the step (for a pruned
  // step: with and without it; `fit3dof diagnose` writes them to stepN/).
  int fit_before = -1;
  int fit_after = -1;
  // A probe outside the catalog that explained the record alike at this
  // step: behind the step's effect by less than
  // DiagnoseOptions::probe_behind_bic (no evidence either way; `effect`
  // empty when none). The effect is named, as the catalog comes first; the
  // verdict names the probe beside it, with what would separate them.
  CandidateFit outside_alike;
  double outside_alike_bic = 0.0;  // its BIC above the step's effect's
  // Every parameter of the model with the probe in the effect's place: the
  // final error bars cover it when the step is the final model's last
  // (WidenForOutsideAlike).
  std::vector<ParameterEstimate> outside_alike_model;
};

// A complete model of an ambiguous diagnosis: the effects adopted and one
// of the tied pair. Its error bars cover the effects the record cannot
// exclude (Diagnosis::not_excluded), as the final model's do.
struct AlternativeModel {
  std::string effect;  // the tied effect in it
  ResidualCheck check;
  std::vector<ParameterEstimate> parameters;  // every parameter
  int fit = -1;                               // its Diagnosis::fits
  Case model;                                 // its config, as fitted
};

enum class Verdict {
  kNoiseLevel,    // the first fit's residuals are measurement noise
  kExplained,     // effects were added and the residuals are noise
  kAmbiguous,     // two effects explain the residual alike
  kNotExplained,  // structured residuals no catalog effect explains
};
// "noise_level" | "explained" | "ambiguous" | "not_explained".
const char* VerdictToString(Verdict verdict);

struct Diagnosis {
  ResidualCheck initial;
  ResidualCheck final;
  std::vector<DiagnosisStep> steps;  // the effects in the final model
  // When the residuals stay structured: the effects that earned a step but
  // left the record unexplained. They are not adopted (the final model is
  // the one before them): an effect that explains only part of an unknown
  // structure may be absorbing it (a drift fitted as a roll-synchronous
  // error), and moves the coefficients by an amount no error bar covers.
  std::vector<DiagnosisStep> partial;
  // Effects that earned a step but are redundant in the final model: with
  // the later effects in, removing one keeps the residuals at the noise
  // level and raises BIC by less than min_bic_drop (a tunnel damping taken
  // first for what a Magnus moment and a nonlinear damping explain
  // together). Forward selection is greedy; this is its backward check.
  // An ambiguous answer's steps are pruned so when every complete model
  // (alternatives) stays at the noise level without one, BIC rising by
  // less than min_bic_drop in each.
  std::vector<DiagnosisStep> pruned;
  Verdict verdict = Verdict::kNoiseLevel;
  std::string verdict_text;  // the sentence for people
  // sigma: auto: the noise the record gave was held for the search
  // (DiagnoseOptions::noise_held); the fits' weights are it.
  bool noise_held = false;
  // The step the search integrated at (DiagnoseOptions::coarse_search;
  // s): the config's solver.step, or a coarser one where the first fit's
  // motion at it stayed within kStepChiSquare / 16 of the config's step's.
  double search_step = 0.0;
  // The effects the engineer declared absent (DiagnoseOptions::absent).
  std::vector<std::string> absent;
  // When ambiguous: the effects, their fits, and what would separate them.
  std::vector<CandidateFit> ambiguous;
  std::string separated_by;
  // Ties at later steps of the search that the record leaves open as well
  // (each: the effect followed, then its rivals); none of them is added.
  std::vector<std::vector<CandidateFit>> later_ties;
  // What would separate each of later_ties, as separated_by says it of
  // the first (set with the verdict; empty before).
  std::vector<std::string> later_separated_by;
  // When effects were adopted after the tie (they are needed whichever of
  // the tied effects is in the model): the complete model with each of
  // them, the tied effect in `effect`, the first as the search followed
  // it.
  std::vector<AlternativeModel> alternatives;
  // When the effects adopted after the tie need one of the tied effects
  // (without any, they leave their bounds or explain nothing) and every
  // alternative reaches the noise: the tied effect the final model holds in
  // the tie's place (the first, as the search followed it), else empty.
  // It is not among the steps (not claimed); its terms are in the final
  // model, whose error bars cover every alternative's values.
  std::string stand_in;
  // Steps of the final model that effects the record cannot exclude
  // (not_excluded) replace together: one effect against several, which
  // `ambiguous` (one of each group) cannot hold. Each step is taken out of
  // `steps` (not claimed) into `stood_in`, its effect joins a tie
  // (ambiguous, or later_ties) with those effects, and the final model
  // keeps its terms, its error bars covering the replacing model's values
  // (diagnose_error_bars.cc, FindSetReplacements). A body's own yaw damping
  // added on a 3-s run stood in for a tunnel damping and a Magnus moment
  // together. One effect not excluded may replace a step so too
  // (FindSingleReplacement).
  std::vector<DiagnosisStep> stood_in;
  std::vector<std::vector<std::string>> stood_in_for;  // the replacing sets
  // When the residuals stay structured: what they show, and the contenders
  // of the last round, each with why it did not earn its place.
  std::string residual_description;
  std::vector<CandidateFit> rejected;
  // When a probe outside the catalog (a drift of the readings or of the
  // dynamic pressure in time, a lag or gain error of the readings, a flow
  // stiffer in one plane, dry friction in the bearing) explains the
  // residual better than any catalog effect that earned its place, by
  // ambiguity_bic or more: its fit (effect empty otherwise), and whether
  // that fit reaches the noise level (diagnosis.json:
  // outside_catalog_at_noise_level). It is never adopted: the verdict is
  // not_explained, and it names what the residual looks like.
  CandidateFit outside_catalog;
  bool outside_at_noise_level = false;
  // When the catalog's effects together outdid that probe alone but, beside
  // it, catalog effects explain the record with a BIC lower than theirs by
  // more than ambiguity_bic, the probe's terms of their physical sign (the
  // probe weighed with the search the catalog gets): those effects (ids; a
  // tie's both). Not added.
  std::vector<std::string> outside_catalog_beside;
  // When the catalog's answer is taken (`explained` or `ambiguous`) but a
  // probe that outdid every catalog effect alone, with catalog effects
  // beside it, explains the record within ambiguity_bic of that answer:
  // the probe's id, then those effects (ids; a tie's both). Not added; the
  // verdict says so and what would separate them. Empty otherwise.
  std::vector<std::string> outside_catalog_alike;
  // When the verdict is `not_explained` for a probe outside the catalog
  // that outdid the catalog's effects, but a search of the catalog alone
  // (CatalogAlone) or without a step taken by a near tie
  // (NearTieUnderProbe) explains the record with a complete model within
  // ambiguity_bic of the probe's model either way: its effects (ids, a
  // tie's too), and the probe's model's BIC above that model's
  // (catalog_alike_bic). The verdict names them, and the final error bars
  // cover their models' values (not enough to set the probe aside, too
  // close to say the catalog cannot explain the record: on draw 43's
  // coning run with a tunnel stiffness, a nonlinear damping and a body yaw
  // asymmetry, a bearing friction beside an asymmetry and a tunnel damping
  // came 5.7 above the three, and the nominal Cm_q, -0.45 +- 0.04, stood
  // 133 of its errors from the truth, -5.5).
  std::vector<std::string> catalog_alike;
  double catalog_alike_bic = 0.0;
  // Every parameter of the final model (its free ones with errors).
  std::vector<ParameterEstimate> final_parameters;
  Case final_case;
  // The fit before the first step, then one per step the loop took (kept,
  // partial or pruned, in the order taken), then one per pruning, then
  // after a tie those of the alternatives and of the model without it
  // (none with a stand-in: the final model is then a step's), then for
  // each step pruned within the tie the alternatives and the final model
  // without it (the alternatives alone with a stand-in).
  std::vector<FitResult> fits;
  size_t final_fit = 0;  // which of them is the final model's
  // The fit whose values the partial steps report: the last model the
  // search had them in.
  size_t partial_fit = 0;
  // Each complete model that kept a tie open (a rival swapped in for a
  // tied effect, the other effects in): the final model's error bars cover
  // its values too (diagnose_error_bars.cc, WidenForTie), unless a complete
  // model of the tie (alternatives) is lower in BIC by more than
  // ambiguity_bic: then it stopped short of where its model fits.
  // Each is reported (diagnosis.json: tie_models) with the effects it
  // holds: where a second tie is left open, the alternatives hold its
  // followed effect, and these the model with each of its rivals instead.
  struct TieModel {
    double bic = 0.0;
    std::vector<ParameterEstimate> parameters;
    std::string in_place_of;  // the tied step's effect the rival replaced
    double rise = 0.0;        // BIC against the model with that step
    std::string effect;       // the rival swapped in
    std::string held;         // a tunnel term of it held at zero, or none
    std::vector<std::string> effects;  // the model's, in the search's order
    ResidualCheck check;
    // A cross model's swap in an earlier tie (cross_tie_models), or none.
    std::string also_in_place_of;
    std::string also_effect;
  };
  std::vector<TieModel> tie_models;
  // Where two ties are left open, each complete model with a rival of
  // each in place of its followed effect (the earlier tie's swap in
  // also_in_place_of and also_effect) that explains the record as the
  // tie models do: within ambiguity_bic of the model with the followed
  // effects, every swapped effect within two of its errors of its bounds.
  // The alternatives hold both followed effects and the tie models one
  // of them: the true model may hold neither (on draw 128's 3-s tunnel
  // stiffness + nonlinear damping + body asymmetry the asymmetry tied
  // with a Magnus moment and the stiffness with a roll torque, and the
  // asymmetry's alternative, with the torque, had Cn_beta 26 of its errors
  // off). The final error bars cover them as they do tie_models; they
  // are reported with them (diagnosis.json: tie_models), not weighed in
  // the search's second thoughts.
  std::vector<TieModel> cross_tie_models;
  // The contenders of the search's rounds that the record cannot exclude
  // beside a complete model (the final one, or the last of the search when
  // steps stayed partial): added to it, BIC rises by less than
  // ambiguity_bic (bic_drop is minus the rise), the model's effects stay
  // within their bounds and its own within two of its standard errors of
  // them. Not added; the final model's error bars
  // cover their models' values too (not_excluded_models,
  // diagnose_error_bars.cc WidenForNotExcluded).
  std::vector<CandidateFit> not_excluded;
  // Those of not_excluded that no round contended: effects the complete
  // model's effects made near twins of its free parameters, tried beside
  // it for that alone (diagnose_error_bars.cc NearTwins). Their error bars
  // count; they may stand in for a step, alone (FindSingleReplacement) or
  // in a set where a set without them does not (FindSetReplacements).
  std::vector<std::string> near_twins;
  // Catalog effects the record cannot tell from the final model's free
  // parameters on its own (near twins of them at the complete model's
  // solution, less than 1% of the information of some direction of their
  // terms left, not made so by the effects added; Eq. 43's tunnel terms,
  // twins of Cm_alpha and Cm_q on every record, left out). None is tried:
  // had one been present, the fitted coefficients carry it, and their
  // error bars do not cover it: each says which coefficients it moves, and
  // by how much per unit of its terms (the fitted value is the
  // combination). On a steady cone a Magnus moment keeps 0.014% of its
  // information apart from Cm_q (draw 42: the final Cm_q -0.24 against a
  // truth of -5.5: Cm_q + 0.0325 Cm_p_alpha). An answer with nothing added
  // lists the nominal fit's near twins so (a record at the noise says
  // nothing of them, and its coefficients carry any that is there).
  std::vector<CoefficientTwin> coefficient_twins;
  // The effects tried beside the complete model that were only lesser
  // refits (each round that refitted them, they lowered BIC by less than
  // min_bic_drop), because its score test called for it: when not
  // excluded, their BIC and error bars count, but like the near twins
  // they do not stand in for a step (a bearing moment whose angle the
  // record leaves open had tied with a body asymmetry, together with a
  // Magnus moment, on a 3-s run whose asymmetry was named before).
  std::vector<std::string> lesser_refits;
  // The catalog effects that earned their place at the round a probe
  // outdid them (`not_explained`): the final error bars cover their
  // models too, each with its Akaike weight against the probe's model,
  // and the probe's own model, with its weight against the final one
  // (among not_excluded_models).
  std::vector<std::string> outdone_by_probe;
  // The catalog effects refused for their drag at the round the search
  // ended without adding any: the final error bars cover their models
  // too, each with its Akaike weight against the final model (among
  // not_excluded_models).
  std::vector<std::string> refused_for_drag;
  std::vector<std::vector<ParameterEstimate>> not_excluded_models;
  std::vector<double> not_excluded_weights;  // each model's Akaike weight
  // The least BIC of a complete model with one of not_excluded or
  // open_terms beside it (infinity if none): what the record says of the
  // answer counts it too (diagnose_second_thoughts.cc, CompleteBic).
  double least_beside_bic = std::numeric_limits<double>::infinity();
  // The probes an added effect leaves open (Effect::leaves_open) that the
  // record cannot exclude beside the final model: each fitted there, the
  // rise in BIC as minus bic_drop; the final error bars cover those fits
  // too (among not_excluded_models).
  std::vector<CandidateFit> open_terms;
  // The final model's own standard errors of the estimates a tie or an
  // effect not excluded widened (within that model, before widening), by
  // name.
  std::map<std::string, double> model_standard_errors;

  // The final model's fit.
  const FitResult& FinalFit() const { return fits[final_fit]; }
  // The tie models, the single swaps (tie_models) and then the cross
  // models (cross_tie_models): what the final error bars cover and
  // diagnosis.json's tie_models report.
  std::vector<const TieModel*> AllTieModels() const {
    std::vector<const TieModel*> all;
    for (const TieModel& m : tie_models) all.push_back(&m);
    for (const TieModel& m : cross_tie_models) all.push_back(&m);
    return all;
  }
};

// Each channel's residual lag-1 autocorrelation in `fit`, pooled over its
// segments (each series about its own mean): ResidualCheck::lag1, and
// DescribeResiduals' serial correlation.
ChannelValues ResidualLag1(const FitResult& fit);

ResidualCheck CheckResiduals(const FitResult& fit,
                             const DiagnoseOptions& options);

// Whether the model `check` was made of explains the record: at the noise
// level, and residuals that depend on no angle, roll or time
// (ResidualCheck::independent). A missing effect in one channel's readings
// alone is diluted in the pooled probable error by the two others: on draw
// 152's 3-s coning run with an even calibration error of the pitch reading
// (theta_cal2 -0.031, outside the catalog) a flow angularity took its mean
// and left E 1.36 against a limit of 1.47, the pitch residual 1.7 times
// the level held, and the record was called `ambiguous` between two catalog
// effects; the pitch angle's powers took most of that residual. The pitch
// residual's own E cannot tell: held from 56 samples, the level of a
// channel may come 0.6 times the truth (draw 149's run with a flow
// angularity, whose true model's pitch residual was 1.7 times its level).
inline bool Explains(const ResidualCheck& check) {
  return check.at_noise_level && check.independent;
}

// Throws InputError for bad input (as Fit does).
Diagnosis Diagnose(const Case& c, const DiagnoseOptions& options);

// Whether a trend in time, a dependence on the pitch or yaw angle (its
// powers 1-3) or on roll (harmonics 1-3) stands out of a residual of `fit`:
// above a tenth of its variance and above what noise reaches with chance
// 1e-5 (DescribeResiduals names them from 1e-3), on the samples the
// regression is worth where what it leaves is serially correlated (errors
// correlated from one sample to the next follow slow regressors as an
// effect would).
bool ResidualsDepend(const FitResult& fit);

// What structured residuals show, for an engineer to act on: each
// channel's strongest lines (pitch's, yaw's and roll's) against the
// motion's modal frequencies and the spin's harmonics (one in the
// periodogram's first bin named a slow drift), and in pitch and yaw a
// trend in time, a dependence on the channel's angle, a dependence on the
// roll angle (residual_description.cc), each
// named only above the share of the residual's variance that noise takes
// with chance 1e-3; the readings far off the fitted motion
// (ScreenResiduals, wild_points.h), with channel and time; and the channels
// read in counts (ReadingStepDeg), with the RMS their rounding alone leaves
// beside the residual's. A broadband residual (none of these stands out)
// correlated from one sample to the next beyond what noise reaches (its
// lag-1 autocorrelation pooled over the channels, ResidualLag1) is said
// to be so, with what leaves one: reading errors that are not white,
// process noise, or an effect too weak on the record to show its shape.
std::string DescribeResiduals(const FitResult& fit);

// The noise level the diagnosis weighed the residuals by: the record's own
// estimate it held with sigma: auto (Diagnosis::noise_held), else `stated`
// (the config's sigma).
ChannelValues DiagnosedNoise(const Diagnosis& d, const ChannelValues& stated);

// diagnosis.json; `noise_reference` the case diagnosed (its sigma as
// DiagnosedNoise reads it).
std::string DiagnosisJson(const Diagnosis& d, const Case& noise_reference);
// `sigma`: the noise level quoted beside the residuals (DiagnosedNoise).
std::string FormatDiagnosis(const Diagnosis& d, const ChannelValues& sigma);

}  // namespace fit3dof

#endif  // FIT3DOF_DIAGNOSE_H_
