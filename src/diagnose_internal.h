// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// What the diagnosis loop (diagnose.cc, diagnose_search.h) is built from:
// the candidate case of a catalog effect (effect_catalog.cc), its score
// test (score_test.cc) and the verdict's words (diagnosis_verdict.cc).

#ifndef FIT3DOF_SRC_DIAGNOSE_INTERNAL_H_
#define FIT3DOF_SRC_DIAGNOSE_INTERNAL_H_

#include <functional>
#include <string>
#include <vector>

#include "fit3dof/case.h"
#include "fit3dof/diagnose.h"
#include "fit3dof/fit.h"
#include "fit3dof/time_history.h"

namespace fit3dof {

// Solver settings for a fit that starts at a solution whose probable
// error is `probable_error` (a refit with one more effect, the
// out-of-sample fits): no multi-start, no rule on the residual level (the
// diagnosis judges it), and continuation only when the solution is far
// from the noise (probable error above kNearSolution): near it the
// growing windows only cost time. But a start near the noise by that
// measure takes the windows when its own probable error is above kFarStart
// (SolverOptions::far_start): a model with an effect taken out can start
// far from the solution it came from. Between the two the Gauss-Newton
// steps converge faster than windows (continuation.cc, FarStart). At 3
// times the noise the windows took 40% of the fitting time of a 48-s
// Table 6 record with a stiffness, a nonlinear damping and an asymmetry
// (its nominal fit 4.5 times the noise off); from 10, summed over nine
// draws of tools/diagnose_suite (1521 diagnoses), 0.93x the time and no
// pass or failure of the suite changed (docs/diagnose_history.md, Session
// 81).
inline constexpr double kNearSolution = 10.0;
inline constexpr double kFarStart = 30.0;
// Such a fit also stops once an iteration lowers its BIC by less than this
// (SolverOptions::bic_tolerance): the search compares fits by BIC margins
// of whole units, and fits along a flat ridge (a bearing moment's angle
// against its coefficient) had crawled 50 iterations for a few hundredths,
// more than half of a diagnosis' fitting. Where the sum of squares is
// quadratic the Gauss-Newton step lands at the minimum and a last gain
// under 0.01 leaves the fit within a tenth of an error of it; along a
// curved ridge it can stop a few tenths above (the fits diagnose reports
// are taken on to the user's rule: Reported).
inline constexpr double kSearchBicTolerance = 0.01;
void RefitFromSolution(Case* c, double probable_error);

// The probes outside the catalog (diagnose.h), and the one called `id`
// (nullptr if none).
const std::vector<Effect>& Probes();
const Effect* FindProbe(const std::string& id);

// Other forms of catalog effects that an effect's form leaves open
// (Effect::leaves_open), never tried alone, and the one called `id`
// (nullptr if none).
const std::vector<Effect>& OpenForms();
const Effect* FindOpenForm(const std::string& id);
// The effect's other form (Effect::other_form), nullptr if it has none.
const Effect* OtherForm(const Effect& effect);

// Whether `fit` holds `effect` in its other form: every one of that form's
// terms free there (FormHeld's rule, read from a fit).
bool InOtherFormIn(const Effect& effect, const FitResult& fit);

// The case `at` with the effect's parameters free at zero (converted to the
// asymmetric program when the effect needs it), their names in `added`;
// false when the effect does not apply or is already in the model.
bool CandidateCase(const Case& at,
                   const Effect& effect,
                   Case* out,
                   std::vector<std::string>* added);

// Whether `name` is one of the effect's companions (Effect::companions).
bool IsCompanion(const Effect& effect, const std::string& name);

// The Jacobian of the parameters free at a solution (the case `at`, on
// the samples its fit used), computed once for the score tests of every
// candidate there: each then integrates only its added terms' columns
// (2-4 against 20-30). A candidate whose model is not `at`'s, whose other
// free parameters are not `at`'s, or whose motion with its terms at their
// start is not the solution's (kSameMotion), is linearized whole.
struct InformationAtSolution {
  InformationAtSolution(const Case& at, const std::vector<TimeHistory>& data);
  bool ok = false;  // false: the motion cannot be integrated
  ModelKind model = ModelKind::kSymmetric;
  std::vector<std::string> names;  // of the free coordinates
  Eigen::MatrixXd jacobian;        // with respect to the values
  Eigen::VectorXd residuals;
  Eigen::MatrixXd information;  // J^T J
};

// The score (Lagrange-multiplier) statistic of the candidate's `added`
// parameters at the current solution, on the samples the fit used (one
// record per segment); see diagnose.h. `at`, if given, the solution's
// Jacobian, shared (InformationAtSolution).
CandidateScore Score(const Case& candidate,
                     const std::vector<std::string>& added,
                     const std::string& id,
                     const std::vector<TimeHistory>& data,
                     const InformationAtSolution* at = nullptr);

// Whether the candidate's score test takes the solution's Jacobian `at`
// (InformationAtSolution says when it does).
bool SharesInformation(const Case& candidate,
                       const std::vector<std::string>& added,
                       const std::vector<TimeHistory>& data,
                       const InformationAtSolution& at);

// How the candidate's `added` terms, were they present, would move the
// model's free coefficients (not a segment's initial conditions) in a fit
// without them, to first order at the current solution: each coefficient
// carrying a tenth or more of a term's signal, per unit of the term. For
// a near twin (IsNearTwin) the fitted coefficient stands for itself plus
// per_unit times the term.
std::vector<TwinShift> TwinShifts(const Case& candidate,
                                  const std::vector<std::string>& added,
                                  const std::vector<TimeHistory>& data);

// Whether a candidate so scored is a twin of the parameters free at the
// solution, near or exact (CandidateScore::novelty under 0.01): its score
// says little of what a refit with it does.
bool IsTwin(const CandidateScore& score);

// Whether it is a near twin (IsTwin), though not an exact one (under
// Score's rank drop, 1e-6).
bool IsNearTwin(const CandidateScore& score);

// Why the effect's parameters, as `fit` (of case `c`) has them, lie
// outside its bounds (diagnose.h, Effect::bounds), or empty.
std::string Implausible(const Effect& effect,
                        const Case& c,
                        const FitResult& fit);
// Why a probe's terms that have a physical sign (a filter's lag, a
// friction against the motion) lie in `fit` more than two standard errors
// on the other side, or empty (a lead, or a friction that drives the
// motion, is no fault of those kinds).
std::string WrongSign(const Effect& probe, const FitResult& fit);
// The terms WrongSign judges wrong, each (pointers into `fit`).
std::vector<const ParameterEstimate*> WrongSignTerms(const Effect& probe,
                                                     const FitResult& fit);
// The first of `effects` that `why` (an effect -> why it lies outside
// its bounds, empty when within them) finds outside: "<id> (added
// before): <why>", or empty; that effect into *first when given (else
// untouched).
std::string FirstImplausible(
    const std::vector<const Effect*>& effects,
    const std::function<std::string(const Effect&)>& why,
    const Effect** first = nullptr);
// FirstImplausible with each effect judged at `fit` (Implausible).
std::string ImplausibleAmong(const std::vector<const Effect*>& effects,
                             const Case& c,
                             const FitResult& fit);

// Why adding the effect's parameters `added` moved a coefficient free in
// `before` by more than `max_drag` of its standard error there, or empty.
std::string Drags(const FitResult& before,
                  const FitResult& after,
                  const std::vector<std::string>& added,
                  double max_drag);

// Why the BIC drop `bic_drop` from `before` to `after` (the same samples
// and weights) rests on one reading: that reading's weighted square
// residual falls by more than half the whole drop, and the record without
// it would lower BIC by less than `min_bic_drop`; or empty. A sample far
// off every model (a wild point, a filter's start-up transient) lets any
// term that bends the motion near it buy a large drop in the sum of
// squares while the rest of the record fits no better.
std::string RestsOnOneReading(const FitResult& before,
                              const FitResult& after,
                              double bic_drop,
                              double min_bic_drop);

// Why the BIC drop `bic_drop` from `before` to `after` rests on readings
// in counts (ReadingStepDeg) that `before` leaves at their rounding (a
// residual within 1.25 times the step over sqrt(12)): without those
// channels' fall in the sum of squares the record would lower BIC by less
// than `min_bic_drop`; or empty. Where the motion crosses the counts at a
// steady pace their rounding is a sawtooth, not noise, and a term that
// couples into that channel buys a fall there from no effect of the
// record's: on draw 157's 3-s run with roll read in 2-deg counts (the
// colored errors' `quantized`, no effect), a product of inertia lowered
// BIC by 11.2, 11.2 of it in roll, 6.0 in pitch and -2.0 in yaw, and was
// named.
std::string RestsOnRoundedReadings(const FitResult& before,
                                   const FitResult& after,
                                   double bic_drop,
                                   double min_bic_drop);

// Why the BIC drop `bic_drop` from `before` to `after` (the same samples
// and weights) rests on reading errors that are not white: weighed as the
// first-order autoregressive errors `after` leaves (their lag-1
// autocorrelation rho pooled over every segment and channel, when
// positive), e_i - rho e_(i-1) over sqrt(1 - rho^2), the record would
// lower BIC by less than `min_bic_drop`; or empty. Correlated errors hold
// more power at the motion's low frequencies than their level says, and a
// term whose signature is slow (a steady roll part, a growth over the
// record) buys a fall in the sum of squares from them. The rho of the model
// with the effect: an effect that is there whitens the residual it leaves,
// and keeps its drop. Read where `after` is at the noise level (Judge): a
// model still short of it leaves the missing effects' structure in rho.
std::string RestsOnSlowResiduals(const FitResult& before,
                                 const FitResult& after,
                                 double bic_drop,
                                 double min_bic_drop);

// Why the BIC drop `bic_drop` from `before` to `after` rests on the
// reading errors rather than the motion: on one reading
// (RestsOnOneReading), on readings at their rounding
// (RestsOnRoundedReadings), or, where `at_noise_level()` says `after`
// reaches the noise, on errors that are not white (RestsOnSlowResiduals);
// or empty. What a round asks of one effect (Judge) and of a joint set
// (EarnedTogether) alike.
std::string RestsOnReadingErrors(const FitResult& before,
                                 const FitResult& after,
                                 double bic_drop,
                                 double min_bic_drop,
                                 const std::function<bool()>& at_noise_level);

// Each segment cut into `blocks` runs of samples, alternately kept for
// training and held out: the held-out samples span the record's amplitudes
// and spin rates, and the motion is integrated through them. Half 0 holds
// out the odd runs; half 1 the even ones but for the first reading, which
// both keep: the initial conditions are fitted there, and the motion is
// integrated from it to every held-out sample.
struct HeldOut {
  std::vector<TimeHistory> train;
  std::vector<std::vector<bool>> held;  // per segment and sample
};
HeldOut HoldOut(const std::vector<TimeHistory>& data, int blocks, int half);

// The weighted residual sum of squares over the held-out samples of the
// case fitted to the training part (fit `trained`), the motion integrated
// from each segment's start; `weights` per segment (deg). Infinity when the
// motion cannot be integrated.
double PredictionRss(const Case& c,
                     const FitResult& trained,
                     const std::vector<TimeHistory>& data,
                     const HeldOut& held_out,
                     const std::vector<ChannelValues>& weights);

// The samples `fit` used, one record per segment.
std::vector<TimeHistory> FittedData(const FitResult& fit);

// The largest roll angle any segment sweeps (deg).
double RollSpan(const std::vector<TimeHistory>& data);

// Whether a roll-locked signature can be told from a drift in time: a
// segment sweeps a revolution of roll, or two segments roll at rates that
// differ by more than a fifth (the same roll angle at different times).
// The search's ties read it, and the verdict and diagnosis.json from the
// final fit's samples.
bool RollSeparates(const std::vector<TimeHistory>& data);

// Whether the probe `drift`, a drift in time, is what the roll-locked
// effect `roll_locked` is on `data`: records that do not separate a first
// harmonic of roll from a slow change in time (RollSeparates).
bool DriftTwin(const Effect& roll_locked,
               const Effect& drift,
               const std::vector<TimeHistory>& data);

// An offset of the tunnel's planes and the roll-locked effects (a
// body-fixed trim, a roll-synchronous reading error): over less than a
// revolution of roll a first harmonic of roll is an offset and a slow
// change, and the family's members have one signature.
bool OffsetFamily(const Effect& e);

// How a contender's refusal for the held-out part opens (PredictsHeldOut):
// the verdict reads it back (RollLockedUnconfirmed).
inline constexpr char kHeldOutRefusal[] =
    "it does not predict the held-out part of the record better";

// The id of a roll-locked effect's rival outside the catalog (diagnose.h):
// on less than a revolution of roll its signature is a drift in time.
inline constexpr char kDriftInTime[] = "drift_in_time";

// The description of a catalog effect, a probe or kDriftInTime.
std::string Describe(const std::string& id);

// The steps' descriptions, comma separated.
std::string Described(const std::vector<DiagnosisStep>& steps);

// "a, b <last> c" (last: " and ", " or ").
std::string Joined(const std::vector<std::string>& items, const char* last);

// The ties the diagnosis leaves open (d.ambiguous, then d.later_ties),
// and every effect in them in that order (diagnosis_report.cc).
std::vector<std::vector<CandidateFit>> Ties(const Diagnosis& d);
std::vector<CandidateFit> Tied(const Diagnosis& d);

// The entry of `fits` for effect `id`, or null.
const CandidateFit* FindFit(const std::vector<CandidateFit>& fits,
                            const std::string& id);

// The tie the diagnosis leaves open (d.ambiguous or one of d.later_ties)
// that holds effect `id`, or null; and whether there is one.
const std::vector<CandidateFit>* TieOf(const Diagnosis& d,
                                       const std::string& id);
bool InTie(const Diagnosis& d, const std::string& id);

// Sets d->verdict and d->verdict_text from what the search left in *d
// (its ties, steps, partial steps, probe and final residual check), and
// d->residual_description when the residuals are not explained
// (diagnosis_verdict.cc).
void Conclude(Diagnosis* d);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_DIAGNOSE_INTERNAL_H_
