// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// What the files of the diagnosis search share (diagnose.h says what the
// search does): a catalog effect's candidate case and its refit in full
// (Candidate, Contender), one round of the search (diagnose_round.cc),
// its ties and the final model they leave (diagnose_ties.cc), and the
// final model's error bars (diagnose_error_bars.cc). diagnose.cc runs the
// search over them; diagnose_second_thoughts.cc weighs its answer against
// others and takes one.

#ifndef FIT3DOF_SRC_DIAGNOSE_SEARCH_H_
#define FIT3DOF_SRC_DIAGNOSE_SEARCH_H_

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "diagnose_internal.h"
#include "fit3dof/case.h"
#include "fit3dof/diagnose.h"
#include "fit3dof/fit.h"
#include "fit3dof/time_history.h"
#include "fit_memo.h"

namespace fit3dof {

// One round of the search (diagnose_round.cc).

// The Bayesian information criterion of a fit: n ln(RSS / n) + k ln(n),
// n the residuals (three per sample), k the free parameters.
double Bic(const FitResult& r);
// Akaike's: n ln(RSS / n) + 2 k.
double Aic(const FitResult& r);
// Bic's charge per free parameter of `r`, ln(n) (n at least 3).
double BicPerTerm(const FitResult& r);

// A catalog effect (or a probe) as a candidate: the current model with the
// effect's terms free at zero (their names in `added`), and its score at
// the current solution. `form`: the effect's other form (Effect::other_form)
// whose terms these are, or nullptr for the effect's own.
struct Candidate {
  const Effect* effect;
  Case c;
  std::vector<std::string> added;
  CandidateScore score;
  const Effect* form = nullptr;
};

// The entry whose terms the candidate frees: its form, or its effect.
inline const Effect& TermsOf(const Candidate& k) {
  return k.form != nullptr ? *k.form : *k.effect;
}

// A candidate refitted in full.
struct Contender {
  const Candidate* candidate = nullptr;
  FitResult fit;
  double bic = 0.0;
  CandidateFit record;
  bool dragged = false;        // refused for dragging the coefficients (Judge)
  bool out_of_bounds = false;  // refused for leaving its bounds (Judge)
  bool unpredicted = false;    // refused for predicting nothing held out
  bool minor = false;  // lowered BIC by less than min_bic_drop (Contenders)
  // The effect added before that went out of its bounds beside it, when
  // that alone refused it (Judge), else empty.
  std::string blocked_by;
};

// Candidate k refitted in full from the solution `fit` into *c (its
// record's BIC drop against `fit`); false when the fit fails.
bool Refit(const Candidate& k,
           const FitResult& fit,
           const std::vector<TimeHistory>& data,
           Contender* c);

// Whether the engineer declared the effect or probe `id` absent
// (DiagnoseOptions::absent).
bool KnownAbsent(const DiagnoseOptions& options, const std::string& id);

// Whether the options' catalog (DiagnoseOptions::effects) holds `e`, not
// declared absent.
bool Wanted(const DiagnoseOptions& options, const Effect& e);

// The case `c` at the solution `fit`, set to be refitted from there
// (RefitFromSolution).
Case FromSolution(const Case& c, const FitResult& fit);

// The current model refitted from its solution as every contender is
// (RefitFromSolution: continuation when far from the noise). A contender's
// BIC drop must come from its effect, not from the refit settling the
// model it extends further down (a roll torque of 5e-9 +- 1e-9 lowering
// BIC by 420 once did). Replaces *fit and returns true when the refit
// lowers BIC by more than 1 (less changes no decision).
bool Polish(const Case& current,
            const std::vector<TimeHistory>& data,
            FitResult* fit);

// Every applicable effect scored at the fit's solution, best first.
std::vector<Candidate> ScoredCandidates(const Case& current,
                                        const FitResult& fit,
                                        const DiagnoseOptions& options);

// Whether a round past the noise level (DiagnoseOptions::noise_held) may
// add one of `candidates`, scored at `fit`: the drop in BIC some score
// predicts (ScoreBicDrop) reaches min_bic_drop. Past the noise
// the effects left are small and the score predicts their fits well; the
// refits it spares had taken the Table 6 triples past 5 s.
bool ScoreMayEarn(const std::vector<Candidate>& candidates,
                  const FitResult& fit,
                  const DiagnoseOptions& options);

// The drop in BIC a refit of `k` beside `fit` is predicted to bring: the
// drop of the sum of squares its score predicts (the score in units of
// the residuals' variance over their degrees of freedom), on Bic's log
// scale, less ln(n) per parameter (ScoreMayEarn's measure).
double ScoreBicDrop(const Candidate& k, const FitResult& fit);

// Whether the score of `k` at `fit` leaves the record unable to exclude
// it: the drop in BIC it predicts (ScoreBicDrop) above -ambiguity_bic.
bool ScoreLeavesOpen(const Candidate& k,
                     const FitResult& fit,
                     const DiagnoseOptions& options);

// Each model (`cases`, fitted as `fits`) refitted from its solution
// without each of `steps` in turn, all in parallel: (*without)[k], for
// k = m * steps.size() + i, is model m without steps[i], and (*fitted)[k]
// whether that fit ran.
void FitWithoutEach(const std::vector<TimeHistory>& data,
                    const std::vector<const Case*>& cases,
                    const std::vector<const FitResult*>& fits,
                    const std::vector<DiagnosisStep>& steps,
                    std::vector<FitResult>* without,
                    std::vector<char>* fitted);

// The estimates of `names` in `fit`.
std::vector<ParameterEstimate> Own(const FitResult& fit,
                                   const std::vector<std::string>& names);

// A fit diagnose reports (the final model's, an alternative's), of the
// search's case `model`, taken on to the user's convergence rule and with
// the profiles the search skipped.
void Reported(const Case& model,
              const std::vector<TimeHistory>& data,
              FitResult* fit);

// Reported for each of `models` with its fit in `fits`, side by side:
// each fit is its own.
void ReportedAll(const std::vector<const Case*>& models,
                 const std::vector<TimeHistory>& data,
                 const std::vector<FitResult*>& fits);

// Whether `effect`'s other form (Effect::other_form) is in the model `at`:
// every one of its terms free.
bool FormHeld(const Case& at, const Effect& effect);

// The terms by which `effect` is in the model `at`: its other form's where
// that is held (FormHeld), its own otherwise. Judging, shrinking or holding
// a calibration added as the signed square by its cube's terms touches
// nothing of it.
const std::vector<std::string>& TermsIn(const Case& at, const Effect& effect);

// Each effect a step of `steps` added in its other form (Effect::other_form)
// back in its own form in the model `current` (fitted as *fit), where the
// record no longer favors the other form by the margin a round asked of it
// once the later steps are in (FormFavored's margin: not where the own form
// would lie outside the effect's bounds and the other lies within them):
// the round that took it saw only the effects before it. On a pair of runs
// with a Magnus moment, a nonlinear damping and a cubic calibration error
// (suite draw 52) the signed square had come 11.2 ahead of the cube with
// the Magnus moment alone beside it. Replaces *current and *fit, and the
// step's step_parameters, and returns true when it changed one.
bool BackToOwnForms(const std::vector<TimeHistory>& data,
                    Case* current,
                    FitResult* fit,
                    std::vector<DiagnosisStep>* steps);

// BackToOwnForms for each effect of `steps` that `current` holds in its
// other form, whatever the step's own parameters say (they are those of
// the model the step was last refitted in): for a final model refitted
// without an open tie's effect (OwnFormsBeforeTie, diagnose_ties.cc).
bool BackToOwnFormsInModel(const std::vector<TimeHistory>& data,
                           Case* current,
                           FitResult* fit,
                           std::vector<DiagnosisStep>* steps);

// The case `c` fitted from `from`, its solution, into *fit; false (and a
// warning naming the refit, `what`) when the fit fails.
bool FitFrom(const Case& c,
             const FitResult& from,
             const std::vector<TimeHistory>& data,
             const std::string& what,
             FitResult* fit);

// The calibration's range held at the readings' largest angle (pitch or
// yaw, over every segment): the other form's straight line is the one a
// linear calibration over the range the model flew took of the square.
// A range the config gives (cal_range > 0, held) is the bench's own
// calibration and is kept: taken at the largest angle instead, a signed
// square calibrated over +-8 deg on readings reaching 9.6 deg left the
// difference of the two lines, a gain error of the pitch reading opposite
// to the yaw reading's (0.005 deg per deg), which a tunnel stiffness and a
// bearing moment tied with after the calibration was named (suite draw
// 161's `pair`).
void HoldCalibrationRange(const std::vector<TimeHistory>& data, Case* c);

// The probable error of `union_fit` counted with the degrees of freedom of
// `fit`, the model it extends (the fewest terms): a lower bound on any
// fit of fewer of its effects that holds `fit`'s.
double LeastProbableError(const FitResult& union_fit, const FitResult& fit);

// The best `options.refit` candidates refitted on the first fit's samples:
// those that lower BIC by more than min_bic_drop, lowest BIC first; the
// others refitted, lowest BIC first, into *minor (a joint set may draw on
// them, Jointly).
std::vector<Contender> Contenders(const std::vector<Candidate>& candidates,
                                  const FitResult& fit,
                                  const std::vector<TimeHistory>& data,
                                  const DiagnoseOptions& options,
                                  std::vector<Contender>* minor);

// The log-likelihood gain out of sample (OutOfSample::Gain) a model with
// `terms` more free parameters must exceed to earn its place: a newcomer
// (Judge), a joint set (EarnedTogether), and the bar a refused rival did
// not clear (Unresolved).
inline double GainNeeded(int terms, const DiagnoseOptions& options) {
  return options.gain_per_parameter * terms;
}

// The out-of-sample check of one round: the current model fitted to the
// kept part of each segment once per half (HoldOut), each contender
// against it.
class OutOfSample {
 public:
  OutOfSample(const Case& current,
              const FitResult& fit,
              const DiagnoseOptions& options)
      : current_(FromSolution(current, fit)),
        data_(FittedData(fit)),
        both_halves_(options.held_out_both_halves) {
    for (const SegmentFit& s : fit.segments) weights_.push_back(s.sigma_deg);
    for (int half : {0, 1}) {
      Half& h = halves_[half];
      h.held_out = HoldOut(data_, options.held_out_blocks, half);
      for (const std::vector<bool>& held : h.held_out.held) {
        h.samples += 3 * std::count(held.begin(), held.end(), true);
      }
    }
  }

  // n_test ln(RSS_without / RSS_with) over the samples `half` holds out;
  // -infinity when the contender cannot be fitted or integrated there.
  double Gain(const Case& with, int half = 0) {
    CHECK(half == 0 || half == 1) << half;
    Half& h = halves_[half];
    if (h.samples == 0) return 0.0;
    if (h.rss_without < 0.0) h.rss_without = Rss(current_, h.held_out);
    return h.samples * std::log(h.rss_without / Rss(with, h.held_out));
  }

  // Gain; where it is positive but does not exceed `needed`, the gain
  // with the other half held out when that one does (both halves predict
  // better, one by the bar). One split can miss what the record shows: on
  // draw 134's 3-s coning run of another body (sigma: auto) a nonlinear
  // damping, true, lowered BIC by 92 but predicted the odd runs of samples
  // by a gain of only 0.7 (needs 2), most of its drop lying in the even
  // ones, the first among them at the largest angles; the record ended
  // `not_explained`, Cm_q 47 of its errors off. A gain at or below zero
  // gets no second chance: an effect that predicts nothing held out on
  // one half is a look-alike fitting that half's noise (taking the mean
  // of both halves named a body yaw asymmetry, false, on a tunnel damping
  // record: AnEarlyStepThatRefusedABetterOneIsSearchedWithout).
  double GainOfBothHalves(const Case& with, double needed) {
    const double first = Gain(with, 0);
    if (!SecondChance(first, needed)) return first;
    const double second = Gain(with, 1);
    return second > needed ? second : first;
  }

  // Whether a first half's gain `first` calls for the second half against
  // the bar `needed` (GainOfBothHalves): positive, short of it, and both
  // halves asked for (DiagnoseOptions::held_out_both_halves).
  bool SecondChance(double first, double needed) const {
    return both_halves_ && first > 0.0 && !(first > needed);
  }

 private:
  struct Half {
    HeldOut held_out;
    int samples = 0;            // held out, times three channels
    double rss_without = -1.0;  // the current model's; -1 before fitted
  };

  double Rss(const Case& c, const HeldOut& held_out) const {
    try {
      const FitResult trained = MemoizedFitSamples(c, held_out.train);
      return PredictionRss(c, trained, data_, held_out, weights_);
    } catch (const std::exception&) {
      return std::numeric_limits<double>::infinity();
    }
  }

  const Case current_;
  const std::vector<TimeHistory> data_;
  const bool both_halves_;
  std::vector<ChannelValues> weights_;
  Half halves_[2];
};

// How far a fit with `rival`'s effect in place of `lead`'s trails it, as
// judged for a tie against ambiguity_bic: `rise`, its BIC above the lead's,
// but for a roll-locked effect behind a flow angularity on records whose
// roll does not separate them (`roll_separates`, RollSeparates) that rise
// less the penalty of the rival's extra terms. Over part of a revolution a
// first harmonic of roll holds an offset, and the two fit alike: a `short`
// roll reading error (suite draws 47 and 65) was named a flow angularity
// 11.6 lower in BIC, of which 9.9 were the reading error's two more terms
// (2 ln 141), the fits 1.7 apart. Only a run at another spin rate, or one
// that rolls a revolution, tells them apart.
double TieGap(double rise,
              const Effect& lead,
              const FitResult& lead_fit,
              const Effect& rival,
              const FitResult& rival_fit,
              bool roll_separates);

// TieGap of the contender `rival` behind `lead`, refitted at one round.
double TieGap(const Contender& lead,
              const Contender& rival,
              bool roll_separates);

// The contenders judged in BIC order until the best that earns its place
// and every other within ambiguity_bic of it (TieGap) are known; returns
// the indices of those that earned it.
std::vector<int> Earned(const FitResult& current,
                        const std::vector<const Effect*>& added,
                        const DiagnoseOptions& options,
                        OutOfSample* out_of_sample,
                        std::vector<Contender>* contenders);

// Effects that earn their place only together (diagnose.h): the members
// (indices into the round's contenders, in their order), the model with
// the first 1, 2, ... of them and its fit, each member's terms as its
// model added them, and the set's out-of-sample gain.
struct JointSet {
  std::vector<int> members;
  std::vector<Candidate> models;
  std::vector<FitResult> fits;
  double prediction_gain = 0.0;
};

// When a contender was refused only for dragging the coefficients, and
// none better (lower BIC) earned its place, the effects missing beside it
// may be what makes the drag: each alone explains part of the record and moves
// the coefficients that the others biased (on the 48-s Table 6 record with a
// tunnel stiffness, a nonlinear damping and a body yaw asymmetry, the
// stiffness alone moved Cm_alpha by 3700 of its errors while lowering
// the probable error 1.4-fold, and asymmetric_body, whose Cn_r then took
// up the missing damping, was out of its bounds). The drag rule lets a
// model that explains the record to the noise move them; so does it a
// set: the refused contender with one or two of three others (JointPool;
// `contenders` may end with the round's lesser refits, Contender::minor),
// fitted together, earns its place together (EarnedTogether). The best
// contender may be refused otherwise and the dragged one come second: on a 3-s
// run with a tunnel damping, a Magnus moment and a flow angularity, a body yaw
// asymmetry (predicting nothing held out) came before the dragged
// damping, the Magnus moment was taken alone, and nothing after it
// earned its place. Under joint_sets_from_bounds a contender refused for
// leaving its bounds leads a set too (each may leave them taking up
// another's part). Each such contender leads its sets in turn, in the
// order of BIC, until one set earns its place: on a pair of 3-s runs with
// a tunnel damping, a Magnus moment and a flow angularity, the first to
// lead was a body yaw asymmetry (it dragged Cm_alpha), none of its sets
// earned, and the damping's set of the three did. `earned` (Earned) tells
// which contenders were judged better than every one that earned its
// place. The lowest-BIC set of the first lead whose set earns its place
// (under joint_sets_from_bounds, weighed against the sets its other
// members lead: OtherMembersLead, diagnose_round.cc) goes into *joint;
// false when none. When no lead's pools earn, each
// lead draws a last pool from the scores at its own fit (LeadPool), the
// effects of `candidates` (the round's, scored at `fit`) it names that no
// round refitted appended to *contenders, refitted alone. When none of
// those earns and no contender earned alone, the contenders refused for
// predicting nothing held out lead sets the same way: two effects each
// missing beside the other may each predict nothing alone (on a 3-s run
// of another body at 39 deg/s, a roll reading error and a Magnus moment).
bool Jointly(const Case& current,
             const FitResult& fit,
             const std::vector<TimeHistory>& data,
             const DiagnoseOptions& options,
             const std::vector<const Effect*>& added,
             OutOfSample* out_of_sample,
             const std::vector<Candidate>& candidates,
             const std::vector<int>& earned,
             std::vector<Contender>* contenders,
             JointSet* joint);

// The joint set *joint (Jointly, from `current` fitted as `fit`) with its
// members in `order` (the same indices into `contenders`), the models of
// its first 1, 2, ... members rebuilt and refitted in that order; false
// (the set unchanged) when one cannot be added or fitted.
bool InOrder(const Case& current,
             const FitResult& fit,
             const std::vector<TimeHistory>& data,
             const std::vector<Contender>& contenders,
             const std::vector<int>& order,
             JointSet* joint);

// The probes outside the catalog at one round of the search, against the
// best catalog contender that earned its place (earned[0], if any): better
// by a margin (ProbeMargin), and the probe's fit goes into
// d->outside_catalog, every contender rejected for it (nothing is adopted);
// within the margin the caller ties them; behind it by less than
// probe_behind_bic, the caller names it beside the step (TakeBest). A
// catalog effect refused here
// for dragging the coefficients that explains more than the probe keeps
// the search in the catalog; one refused for leaving its bounds does not:
// on a 3-s run with a dry friction on both axes (outside the catalog,
// suite draw 68) a calibration error refused at 3.8 times its bound
// lowered BIC by 296, the axis friction probe by 288, a tunnel damping by
// 248, and the tunnel damping was named `explained`. Where a calibration
// just past its bound has two effects missing beside it, the catalog's
// search without the probes (CatalogAlone) finds them. Returns whether a
// probe was fitted that lowers BIC enough to count (*probe, pointing into
// *probes).
bool WeighProbes(const Case& current,
                 const FitResult& fit,
                 const std::vector<TimeHistory>& data,
                 const DiagnoseOptions& options,
                 const std::vector<int>& earned,
                 OutOfSample* out_of_sample,
                 std::vector<Candidate>* probes,
                 Contender* probe,
                 std::vector<Contender>* contenders,
                 Diagnosis* d);

// Ties and the final model (diagnose_ties.cc).

// Whatever explains a round's residual as well as contenders[best]
// (diagnose.h): the other contenders within ambiguity_bic of its BIC
// (TieGap), the
// probe (when fitted) ahead of it (one behind is named beside the step:
// DiagnosisStep::outside_alike), and for a roll-locked effect on less than
// a revolution of roll a drift in time. Contenders refused at this round
// count too: with the effects still missing in, a roll reading error
// refused beside an unexplained nonlinear damping may explain the record
// as well as the trim moment adopted (the final swap decides, Unresolved).
std::vector<CandidateFit> Rivals(const std::vector<Contender>& contenders,
                                 int best,
                                 const Contender* probe,
                                 const std::vector<TimeHistory>& data,
                                 const DiagnoseOptions& options);

// The rivals the final swap (Unresolved) tries for contenders[best]:
// `rivals` (Rivals) and the other catalog contenders within rival_bic.
// While effects are still missing, the round's BIC gaps hold their
// signatures too: on one 3-s run with a tunnel stiffness, a nonlinear
// damping and a body yaw asymmetry, a roll torque was adopted 21 below
// the tunnel stiffness, and once the other two were in, the tunnel
// stiffness swapped in for it lowered BIC by 3 more.
std::vector<CandidateFit> WiderRivals(std::vector<CandidateFit> rivals,
                                      const std::vector<Contender>& contenders,
                                      int best,
                                      const DiagnoseOptions& options);

// `rivals` (WiderRivals) of contenders[best], a roll moment (IsRollMoment),
// with Eq. 39's tunnel stiffness whatever its BIC, refitted from `fit` when
// the round did not (the final swap, Unresolved, decides). Its pitch and
// yaw moments projected on the body's roll axis give a roll torque of
// (t1 - t3) theta psi times Iy / Ix, and a body yaw asymmetry (Cn_beta
// apart from -Cm_alpha) takes up its pitch and yaw parts over a short span
// of roll: until the asymmetry is in, the roll torque takes the roll part
// alone and the stiffness falls far behind it. The tunnel damping's roll
// part on a steady cone is a steady torque, the roll torque's twin, which
// comes within the round's rivals by its own BIC (refitted here it had
// tied at +9.9 on a pair of runs whose adoption it then broke). Not where
// the model's `steps` or their rivals (`earlier`, a step's each) hold a
// roll moment or a tunnel term already: the roll part is taken. On draw 159's
// 3-s run with a tunnel stiffness, a nonlinear damping and a body yaw asymmetry
// (sigma: auto) a roll torque came 48.6 ahead of the stiffness at the first
// round and a Magnus moment was added after the damping and the asymmetry; with
// them in, the stiffness in the torque's place is 3.0 above it.
std::vector<CandidateFit> RollPartRivals(
    std::vector<CandidateFit> rivals,
    const std::vector<Contender>& contenders,
    int best,
    const std::vector<Candidate>& candidates,
    const FitResult& fit,
    const std::vector<TimeHistory>& data,
    const std::vector<DiagnosisStep>& steps,
    const std::vector<std::vector<CandidateFit>>& earlier);

// The case `at` without the effect that `step` added: the terms it added
// fixed at zero (a companion keeps its value, inert without them); an
// image it had untied (an asymmetric body) tied again.
Case WithoutStep(const Case& at, const DiagnosisStep& step);

// The step's effect as the contender it was.
CandidateFit AsContender(const DiagnosisStep& step);

// Whether `steps` hold the effect `effect`.
bool HoldsEffect(const std::vector<DiagnosisStep>& steps,
                 const std::string& effect);

// Each step's parameters as the final model has them (a partial step's as
// the last partial model has them). A later step may have switched the
// model to the asymmetric program, where the effect's terms have other
// names (a Magnus moment's Cm_p_alpha is Cm_p_beta and Cn_p_alpha there):
// the effect's own list for that program finds them. Sets
// final_parameters from the final fit.
void FinalValues(Diagnosis* d);

// *d's step that claims `effect` stands in a tie with the effects that
// `other` (the search without `effect`, explaining the record about as
// well) holds as steps and *d does not: *d's final error bars cover
// `other`'s final model, and its verdict is concluded again. False (*d
// unchanged) when `other` holds no such effect.
bool StandInForSearch(const Diagnosis& other,
                      const std::string& effect,
                      Diagnosis* d);

// What a second run would change to separate the tied `ambiguous` (the
// first and its rivals), for the model fitted as `fit`.
std::string SeparatedBy(const std::vector<CandidateFit>& ambiguous,
                        const Case& c,
                        const FitResult& fit,
                        const std::vector<TimeHistory>& data);

// Diagnosis::separated_by for d->ambiguous and later_separated_by for
// each of d->later_ties (SeparatedBy, at d's final fit of `c` to `data`).
void SeparateTies(const Case& c,
                  const std::vector<TimeHistory>& data,
                  Diagnosis* d);

// The fit of the complete model of `d`'s tie (Diagnosis::alternatives) with
// the least BIC, or null when none was fitted.
const FitResult* LowestCompleteFit(const Diagnosis& d);

// Which model the search ends with (diagnose.h), given `check`, the
// residual check of its last fit, `models`, the case of each of d->fits,
// `tie`, the step of the first tie or -1, and `rivals`, each step's
// (Rivals): sets d->final_fit and
// *current (from `user` when nothing explains the record) and returns the
// final model's residual check.
ResidualCheck SettleFinalModel(
    const Case& user,
    const std::vector<TimeHistory>& data,
    const DiagnoseOptions& options,
    const std::vector<Case>& models,
    int tie,
    const std::vector<std::vector<CandidateFit>>& rivals,
    const ResidualCheck& check,
    Diagnosis* d,
    Case* current);

// The final model's error bars (diagnose_error_bars.cc).

// The standard errors an effect's terms are moved toward zero by when its
// bounds are judged within its errors (ImplausibleWithin).
constexpr double kBoundErrors = 2.0;

// Why the effect's terms `added`, as `fit` (of case `c`) has them, lie
// outside its bounds (Implausible) both at the point fit and moved `k` of
// their standard errors toward where the effect is least (Shrunk), the other
// free parameters held or moving with them by their regression on them
// (where a refit with the terms held there would put them, to first order);
// empty when any of the three is within them. Shrinking a tunnel term alone
// moves the sum that Eq. 43 leaves determined (Cm_q + t2): one within its
// bounds as fitted can leave them shrunk (a record's damping turned
// positive). Followed, the body's coefficient keeps that sum, and a
// nonlinear damping takes Cm_q along its ridge: on suite draw 104's 3-s run
// (a true 3.6 times |Cm_q| at 6 deg, fitted at 4.9) that is within its
// bound of 4 times, shrunk alone it was not; on draw 7's (a true 4.0 times,
// fitted at 4.02, Cm_q + 0.0049 Cm_q_delta2 near zero) the ridge keeps the
// ratio, and shrunk alone it is within.
std::string ImplausibleWithin(const Effect& effect,
                              const Case& c,
                              const FitResult& fit,
                              const std::vector<std::string>& added,
                              double k);

// Why `effect`'s terms `terms`, as `fit` (of case `c`) has them, lie
// outside its bounds as a round judges a newcomer: within kBoundErrors of
// their errors (ImplausibleWithin) where `options` say so
// (bounds_within_errors for an effect on a ridge, every_bound_within_errors
// for any), else at the point fit (Implausible); empty when within them.
std::string ImplausibleAsJudged(const Effect& effect,
                                const Case& c,
                                const FitResult& fit,
                                const std::vector<std::string>& terms,
                                const DiagnoseOptions& options);

// ImplausibleAsJudged for each of `effects` (added before; its terms in
// `c`'s model): the first one's id and why, or empty. An effect admitted
// within its errors stays judged so once others join it: on draw 32's
// pair of runs with a bearing moment, a calibration error and a roll
// torque, the calibration came in within its errors at the third search
// (0.349 deg at 8.2 deg, bound 0.246) and then refused the bearing moment
// beside it at its point fit (0.249).
// The effect found outside its bounds goes into *first when given.
std::string ImplausibleAmongAsJudged(const std::vector<const Effect*>& effects,
                                     const Case& c,
                                     const FitResult& fit,
                                     const DiagnoseOptions& options,
                                     const Effect** first = nullptr);

// Eq. 43's tunnel terms: effects whose pitch and yaw terms each lie on a
// ridge with a body coefficient (Cm_alpha + t1, Cm_q + t2), so that with
// one held at zero the other carries what the record sees of them.
bool OnTunnelRidge(const Effect& e);

// Whether `id` is a roll moment of the catalog (a roll torque, a roll
// damping): at a steady spin each is the other's twin, and each takes up
// the roll part of Eq. 39's tunnel moments (their pitch and yaw moments
// projected on the body's roll axis).
bool IsRollMoment(const std::string& id);

// `c` with its parameter `name` held at zero (not free); false when its
// model has no such parameter.
bool HoldAtZero(const std::string& name, Case* c);

// The final model of a record that an open tie leaves ambiguous holds
// none of the tied effects, and what one of them would change in it the
// record cannot say: a calibration error fitted without the bearing moment
// it tied over came out 0.047 +- 0.007 deg (truth 0.02). So each of its
// free estimates' error bars also covers the largest shift of its value
// in the complete models (each alternative's, or the search's last, which
// holds the first of the tied effects, or a rival swapped in for it with
// the other effects in, Diagnosis::tie_models), and the error that model
// gives it:
//
//   error' = max over the models m of sqrt(max(error, error_m)^2 +
//                                          (value_m - value)^2),
//
// Burnham and Anderson's unconditional variance with the worst model in
// place of the weighted sum (the tied models' weights are alike): where a
// tied tunnel stiffness leaves only Cm_alpha + t1 determined (Eq. 43),
// the final Cm_alpha is as uncertain as in that model.
void WidenForTie(const DiagnoseOptions& options, Diagnosis* d);

// The final error bars of `d`, left `not_explained` by a probe outside
// the catalog, widened to cover the complete models of `other`, the
// catalog's answer that explains the record alike (within ambiguity_bic
// of the probe's model; Diagnosis::catalog_alike), as a tie's are.
void WidenForCatalogAlike(const Diagnosis& other,
                          const DiagnoseOptions& options,
                          Diagnosis* d);

// The final error bars of `d` widened to cover the model with a probe
// outside the catalog in the place of its last step's effect, where the
// probe explained the record alike there (DiagnosisStep::outside_alike:
// no evidence either way), as a tie's are: the mirror of
// WidenForCatalogAlike. Only the last step's: an earlier step's probe was
// fitted without the effects added after it.
void WidenForOutsideAlike(Diagnosis* d);

// The contenders of the search's rounds (`contended`: each lowered BIC by
// more than min_bic_drop where it was tried) that the record cannot
// exclude beside a complete model (tied effects aside: WidenForTie covers
// them): added to it (not swapped in, as the final swap tries them), its
// BIC rises by less than ambiguity_bic and the effects stay within their
// bounds (ImplausibleBeside: its own within two of its errors). Their fits
// go into d->not_excluded (bic_drop against the model without) and their
// parameters into d->not_excluded_models. So do, into d->open_terms, the
// probes a complete model's effects leave open (Effect::leaves_open: the
// cube's reading gain) where the record cannot exclude them beside it.
// Beside the first complete model, the effects its effects made near twins
// of its free parameters are tried too, though never contended (their
// score stays low however far they drag; diagnose_error_bars.cc
// NearTwins): into d->near_twins as well when not excluded. So are the
// `lesser` refits (an effect that lowered BIC by less than min_bic_drop
// at its round) that are twins there or whose score may earn a place
// (Lesser): on a coning run with a tunnel stiffness, a nonlinear damping
// and a body asymmetry (draw 25) the stiffness lowered BIC by 4 beside
// the asymmetry alone and by 35 beside it and the damping; never tried
// there, the effects not excluded outdid the asymmetry and the search
// without it named a tunnel damping and a Magnus moment, 16 above the
// true model.
//
// On a 3-s coning run with a tunnel damping, a Magnus moment and a flow
// angularity, the tunnel damping and Cm_q absorbed the Magnus moment (one
// mode of motion hardly tells Cm_q from Cm_p_alpha), and the model with
// the damping and the angularity reached the noise with Cm_q at -3.84 +-
// 0.01 (truth -5.5). The Magnus moment, 24 below the damping at the first
// step, raised BIC by only 1.0 beside them, with Cm_q at -6.4 +- 1.4. On
// another noise draw it was 35 below (outside rival_bic) and, when only
// the steps' rivals were tried here, never tried: Cm_q ended 129 of its
// errors off.
//
// Into *open_ridge, Eq. 39's tunnel terms whose score at the first
// complete model says the record may not exclude them (ScoreLeavesOpen,
// as Lesser reads a lesser refit's), for FindSetReplacements.
void FindNotExcluded(const std::vector<const Effect*>& contended,
                     const std::vector<const Effect*>& lesser,
                     const std::vector<Case>& models,
                     const Case& current,
                     const std::vector<TimeHistory>& data,
                     const DiagnoseOptions& options,
                     Diagnosis* d,
                     std::vector<const Effect*>* open_ridge);

// The final error bars cover the models of the effects the record cannot
// exclude (FindNotExcluded), each with its Akaike weight against the
// model it was added to, exp(-rise / 2) / (1 + exp(-rise / 2)) for its
// rise in AIC (diagnose_error_bars.cc AkaikeWeight): neither the search
// nor the final swap added or swapped them in, but the values the record
// allows with them are part of its answer. Weighted, not the tie's worst
// case: along Eq. 43 a tunnel damping leaves only Cm_q + t2 determined,
// and one that raised BIC by 9.3 beside a roll damping (two runs) widened
// Cm_q 138-fold in the worst case, 13-fold at its BIC weight.
void WidenForNotExcluded(Diagnosis* d);

// The probe's model, with its Akaike weight against `fit` (the model the
// search stopped at, the final one), and the catalog contenders at
// `earned` (indices into `contenders`) that the probe outdid, with
// theirs against the probe's model (Diagnosis::outdone_by_probe): their
// fits' parameters among d->not_excluded_models. A probe is never
// adopted, and the final model is the one before it, whose error bars had
// covered neither what the record allows with the catalog's explanation
// nor the probe's own. On two 3-s runs (pair) a tunnel damping stronger in
// yaw lost to the yaw axis's friction by 10.3 of BIC; the two predict each
// run from the other alike, and the final Cm_q, the nominal fit's -3.39 +-
// 0.015, was 137 of its errors from the truth (-5.5) that the damping's
// model held (-5.14 +- 0.64). On draw 128's 3-s cone with a bearing
// moment a pressure drift outdid it by 17.6; the nominal Cm_alpha,
// -0.23252 +- 2.2e-5, was quoted +- 7.9e-5, while the drift's model, 96
// lower in BIC, holds -0.23196.
void KeepOutdoneByProbe(const Contender& probe,
                        const std::vector<Contender>& contenders,
                        const std::vector<int>& earned,
                        const FitResult& fit,
                        Diagnosis* d);

// The contenders refused for their drag (Contender::dragged) at the
// round the search ended without adding any (a probe outdoing the
// catalog there or not), their fits' parameters
// among d->not_excluded_models with their Akaike weights against the
// model `fit` the search stopped at (Diagnosis::refused_for_drag). The
// drag rule keeps an effect out that moves the coefficients while the
// record stays unexplained (a missing effect's bias hides in the fit),
// but then the fit without it is no surer of them: on draw 29's coning
// run with a bearing moment, a calibration error and a roll torque, the
// bearing moment lowered BIC by 72 and moved Cm_alpha by 148 of its
// errors, toward the truth, and the final Cm_alpha, the nominal fit's,
// stood 97 of its errors off.
void KeepRefusedForDrag(const std::vector<Contender>& contenders,
                        const FitResult& fit,
                        Diagnosis* d);

// Each of a tie's complete models (d->alternatives) other than the final
// one refitted with each effect the record cannot exclude beside the final
// model (d->not_excluded) added, and its error bars widened as the final
// model's are (WidenForNotExcluded: Akaike weights; the effect within its
// bounds, its own within two of its errors). An alternative reported
// without them was sure of values the record does not fix: on a 3-s
// coning run with a Magnus moment, a nonlinear damping and a calibration
// error, the nonlinear damping not excluded, the complete model with the
// Magnus moment gave Cm_p_alpha = 81 +- 6 (truth 53.5), the Magnus moment
// taking up the nonlinear damping's part.
void WidenAlternatives(const std::vector<TimeHistory>& data,
                       const DiagnoseOptions& options,
                       Diagnosis* d);

// A step of the complete model (the final one, or the search's last when
// steps stayed partial) that two or more effects not excluded replace
// together (Diagnosis::stood_in): without it and with them the model
// reaches the noise, its BIC within ambiguity_bic of the complete model's,
// its effects within their bounds, and each of them needed there (Needed).
// One effect can stand in for two: on a 3-s run at 30 deg/s (a quarter
// turn of roll) a body's own yaw damping, first at the first round by 16
// in BIC, took the place of a tunnel damping and a Magnus moment, each of
// which alone swapped for it was worse, and both of which were not
// excluded beside it. Within ambiguity_bic the step is not claimed: it
// joins a tie with them, and the final error bars cover the replacing
// model's values. Returned (nothing changed) when they do better by
// ambiguity_bic or more: the search took a wrong turn (DiagnoseFrom).
// The tunnel terms of `open_ridge` (FindNotExcluded) that no round
// refitted nor the search tried beside the model join the set last.
std::string FindSetReplacements(const std::vector<Case>& models,
                                const Case& current,
                                const std::vector<TimeHistory>& data,
                                const DiagnoseOptions& options,
                                const std::vector<const Effect*>& open_ridge,
                                Diagnosis* d);

// One effect not excluded that lowered BIC beside the complete model,
// fitted in a step's place (each step, each such effect): FindSetReplacements'
// rule for a set of one. A tunnel term out of its bounds there has run
// along Eq. 43's ridge, and each of the pair is held at zero in turn (one
// more parameter counted in BIC). On a 3-s run with a tunnel stiffness, a
// nonlinear damping and a body asymmetry (draw 23) the search named a
// roll torque for the stiffness's roll signature, the stiffness not
// excluded beside it; in the torque's place it ran to t1 = 1.55 (bound
// 0.116), and with t1 held at zero its BIC was 4.3 lower: the two tie.
// An ambiguous answer's steps are tried so too, and a near twin may stand
// in alone (not a lesser refit): on draw 27's 3-s run of that case a
// Magnus moment (-2.5 +- 0.56) was named beside the tie the stiffness was
// in, and the true body asymmetry, a near twin not excluded beside it
// (BIC -3.1), was 5 lower in its place. Better by ambiguity_bic or more, the
// step's effect is returned with *d left as it is, and *outdone_tie gets *d
// with the step in a tie with that effect (DiagnoseFrom keeps it where the
// search without the step does not explain the record better). A roll
// torque or roll damping step is tried with each tunnel term of Eq. 39 that
// no round refitted in its place too (their roll part is its signature;
// UntriedRidge): on draw 127's record of draw 23's case the stiffness was
// never a contender.
std::string FindSingleReplacement(const std::vector<Case>& models,
                                  const Case& current,
                                  const std::vector<TimeHistory>& data,
                                  const DiagnoseOptions& options,
                                  Diagnosis* d,
                                  Diagnosis* outdone_tie);

// The search and its second thoughts (diagnose.cc, diagnose_second_
// thoughts.cc).

// What a search tells its caller besides its answer: the effect it
// followed at a tie of two catalog effects (empty if none), the first
// step's effect when it was taken alone, untied, and when its next
// contender not refused came within near_tie_bic (NearTie), the step the
// effects not excluded outdid (FindSetReplacements; empty if none), and
// whether a contender refused for leaving its bounds came ahead of every
// one that earned its place at some round (a joint set's lead under
// joint_sets_from_bounds), and the model of the probe that outdid the
// catalog (Diagnosis::outside_catalog), as fitted.
struct UnfinishedSearch;

struct SearchNotes {
  // The first step's effect when it opened a tie with another that earned
  // its place, and whether that other (the search without it takes it
  // first) is its twin there: their fitted motions less than
  // kSearchBicTolerance apart in sum of weighted squares (MotionApart,
  // diagnose.cc), as a roll torque and a roll damping are at constant spin
  // (1.7e-7; the nearest pair of others on draw 131 was 0.8 apart).
  std::string tied_first;
  bool tied_first_twin = false;
  // The first step's effect when it was taken alone, untied, near tie or
  // not (NearTieBranch; a near tie when it is in led_steps too).
  std::string first_alone;
  // Each step's effect, in order, when its next catalog contender came
  // within near_tie_bic, whether or not a probe tied with it
  // (NearTieUnderProbe, NearTieBranch).
  std::vector<std::string> led_steps;
  // A step that effects not excluded beat in its place by ambiguity_bic or
  // more, and, when one effect did, the answer with the step in a tie with
  // it instead.
  std::string outdone;
  std::optional<Diagnosis> outdone_tie;
  bool bounded_lead = false;
  // An effect added before that alone refused a round's best contender,
  // which lowered BIC by min_bic_drop more than any that earned its place
  // (BlockerBranch): the first such.
  std::string blocker;
  Case probe_case;
  FitResult probe_fit;
  // The answer is the catalog's without probes (CatalogAlone), whose
  // search had its own second thoughts.
  bool catalog_alone = false;
  // What a search whose answer's error bars were left undone
  // (SearchUnfinished) needs to finish it (Finished).
  std::shared_ptr<UnfinishedSearch> unfinished;
};

// The step of `d`, an ambiguous answer, adopted in a joint set with an
// effect that then went into a tie (Diagnosis::ambiguous or later_ties)
// with other than its twins, or null: the step the search without it
// questions (WithoutTiedPartner, diagnose_second_thoughts.cc). A twin is
// a rival that, swapped in for the partner with every other effect in
// (Diagnosis::tie_models), moves the complete model's BIC by less than
// options.partner_search_bic: the step's model is then as good with it,
// with no evidence either way, and the step stands on what let it in
// whichever of them is named. At constant spin a roll damping and a roll
// torque are such twins (Cl_p p against Cl_0, BIC +0.00 swapped): on
// draw 124's Table 6 record with a bearing moment, a calibration
// nonlinearity and a roll torque, the bearing moment adopted with the
// calibration and a roll damping was searched without (1.5 of the
// diagnosis' 5.5 s alone), to end unexplained, 3281 higher in BIC.
const DiagnosisStep* PartnerTied(const Diagnosis& d,
                                 const DiagnoseOptions& options);

// Whether the catalog's effects but `id` may explain the record of `d`
// (an answer to `nominal`'s data), as far as all of them at once tell.
// Any answer of a search or diagnosis without `id` that explains the
// record (ExplainsRecord) has a model at the noise level (SettleFinalModel)
// holding a few of them in one form or the other: its sum of squares is
// no lower than theirs all together at their minimum, so its probable
// error (with at least `nominal`'s terms: LeastProbableError) is under the
// noise limit only if theirs is. The minimum is the one the fit finds
// (UnionMayEarn's argument, diagnose_round.cc): from `d`'s final model
// without `id`, the others at their values there, every other wanted
// effect and other form added at zero, the calibration's range held
// (HoldCalibrationRange). True when the union cannot be built or fitted,
// or its fit did not settle (stopped at the bearing angle's limit or its
// iteration limit, where a lower minimum may lie beyond).
// One fit of every effect at once in place of a search: on draw 131's
// Table 6 record with a tunnel damping, a Magnus moment and a flow
// angularity, the search without the angularity (WithoutTiedPartner)
// took 2.8 of the record's 4.5 s to end unexplained, 5595 above the
// first answer in BIC; the union, 0.15 s, stood at 2.5 against a noise
// limit of 1.1.
bool CatalogMayExplainWithout(const FitResult& nominal,
                              const DiagnoseOptions& options,
                              const std::string& id,
                              const Diagnosis& d);

// The forward search (diagnose.h) from `nominal`, the fit of `c`, with
// `options`' catalog; *notes gets what else it found (diagnose.cc).
Diagnosis Search(const Case& c,
                 const FitResult& nominal,
                 const DiagnoseOptions& options,
                 SearchNotes* notes);

// Search with its answer's error bars left undone (the effects the record
// cannot exclude beside the final model, the sets that would replace a
// step, the widening: most of an answer's time once its rounds are done),
// for a caller that may set the answer aside on its fits, steps and
// verdict alone (FirstHeld, diagnose.cc): those are as Search's, and
// notes->unfinished holds the rest. Finished(d, notes) is then Search's
// answer (`d` itself when nothing was left undone).
Diagnosis SearchUnfinished(const Case& c,
                           const FitResult& nominal,
                           const DiagnoseOptions& options,
                           SearchNotes* notes);
Diagnosis Finished(Diagnosis d, SearchNotes* notes);

// The search from `nominal`, the fit of `c`, without the catalog effect
// `id` (a second thought's other answer), for a caller that takes it only
// when it explains the record with a complete model below `explain_below`
// (DiagnoseOptions::explain_below; infinity takes any). A probe that
// outdoes the catalog there is weighed as in any search (diagnose.h),
// but not beside a catalog answer the caller could not take
// (diagnose_second_thoughts.cc).
Diagnosis SearchedWithout(const Case& c,
                          const FitResult& nominal,
                          const DiagnoseOptions& options,
                          const std::string& id,
                          double explain_below);

// The search from `nominal`, the fit of `c`, and its second thoughts: an
// effect past the noise, a step outdone, the other branch of a tie, a
// first step that led nowhere, joint sets led by an effect out of its
// bounds, a near or outdone tie, an effect a swap outdid in a tie the
// search left open (diagnose_second_thoughts.cc).
Diagnosis DiagnoseFrom(const Case& c,
                       const FitResult& nominal,
                       const DiagnoseOptions& options);

// DiagnoseFrom in two halves, for a caller that reads the search's answer
// before its second thoughts (WithNoiseHeld, diagnose.cc): the search
// (with the catalog searched alone where a probe outdid it), *notes
// getting what the second thoughts need, its answer's error bars left
// undone where no probe outdid the catalog (SearchUnfinished); then
// those error bars (Finished) and the second thoughts on its answer
// `first`. Rethought(FirstSearch(...)) is DiagnoseFrom.
Diagnosis FirstSearch(const Case& c,
                      const FitResult& nominal,
                      const DiagnoseOptions& options,
                      SearchNotes* notes);
Diagnosis Rethought(const Case& c,
                    const FitResult& nominal,
                    const DiagnoseOptions& options,
                    SearchNotes notes,
                    Diagnosis first);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_DIAGNOSE_SEARCH_H_
