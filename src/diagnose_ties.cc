// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Ties and the final model of the diagnosis search (diagnose.h): a step's
// rivals (Rivals), a tie kept open or dissolved by swapping each rival in
// once the record is explained (Unresolved, TieDissolves), effects adopted
// after a tie (AdoptAfterTie), backward elimination (Prune), and the final
// model they leave (SettleFinalModel).

#include <glog/logging.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "diagnose_search.h"
#include "fit3dof/model_conversion.h"
#include "fit3dof/parameters.h"
#include "fit3dof/thread_budget.h"
#include "format.h"

namespace fit3dof {

namespace {

// The pitch frequency of the fit (deg/s): sqrt(-Cm_alpha q S d / I_y);
// 0 when the fit is not statically stable.
double PitchFrequency(const Case& c, const FitResult& fit) {
  const ParameterEstimate* cm_alpha = SharedEstimate(fit, "Cm_alpha");
  if (cm_alpha == nullptr) return 0.0;
  const double w2 = -cm_alpha->value * c.flow.dynamic_pressure * c.body.area *
                    c.body.diameter / c.body.Iy;
  return w2 > 0.0 ? std::sqrt(w2) / kDegree : 0.0;
}

// What a second run would change to tell effects a and b apart, for a
// model fitted as `fit`.
std::string Separation(const Effect& a,
                       const Effect& b,
                       const Case& c,
                       const FitResult& fit) {
  if (a.roll_locked && b.roll_locked) {
    // Both are offsets fixed in the body (a trim angle, a reading error
    // locked to roll): well below the pitch frequency a trim moment's
    // response follows the roll without lag or growth at any spin rate,
    // so only a spin near that frequency tells them apart.
    const double pitch = PitchFrequency(c, fit);
    return "a run spinning near the pitch frequency (" +
           (pitch > 0.0 ? FormatNumber("%.0f", pitch) + " deg/s: " : "") +
           "there a trim moment's response grows and lags, a reading "
           "error's does not)";
  }
  if (a.separated_by == b.separated_by)
    return "a run at another " + a.separated_by;
  return "a run at another " + a.separated_by + " or " + b.separated_by;
}

// The rival of a roll-locked effect on a record shorter than a revolution
// of roll: outside the catalog, not fitted.
CandidateFit DriftInTime() {
  CandidateFit drift;
  drift.effect = kDriftInTime;
  drift.prediction_gain = std::numeric_limits<double>::quiet_NaN();
  return drift;
}

// The contenders other than contenders[best] with BIC below `within`.
std::vector<CandidateFit> Near(const std::vector<Contender>& contenders,
                               int best,
                               double within) {
  std::vector<CandidateFit> near;
  for (int i = 0; i < static_cast<int>(contenders.size()); ++i) {
    if (i != best && contenders[i].bic < within) {
      near.push_back(contenders[i].record);
    }
  }
  return near;
}

// The effect ids of `steps` but the one at `skip`, comma separated.
std::string Others(const std::vector<DiagnosisStep>& steps, int skip) {
  std::string text;
  for (int i = 0; i < static_cast<int>(steps.size()); ++i) {
    if (i != skip) text += (text.empty() ? "" : ", ") + steps[i].effect;
  }
  return text;
}

// The position in `model` of a term a step added: a symmetric name in the
// asymmetric program (the step came before the switch) is its first image,
// the one ToAsymmetric gave its value and free flag.
int AddedTermPosition(ModelKind model, const std::string& name) {
  const int position = FindParameter(model, name);
  if (position >= 0 || model == ModelKind::kSymmetric) return position;
  const CoefficientImage* first = FirstImage(name);
  return first == nullptr ? -1 : FindParameter(model, first->asymmetric);
}

}  // namespace

void FitWithoutEach(const std::vector<TimeHistory>& data,
                    const std::vector<const Case*>& cases,
                    const std::vector<const FitResult*>& fits,
                    const std::vector<DiagnosisStep>& steps,
                    std::vector<FitResult>* without,
                    std::vector<char>* fitted) {
  const int n = static_cast<int>(cases.size() * steps.size());
  without->assign(n, FitResult());
  fitted->assign(n, false);  // not vector<bool>: written in parallel
  ParallelFor(n, [&](int k) {
    const size_t m = k / steps.size();
    const DiagnosisStep& s = steps[k % steps.size()];
    (*fitted)[k] = FitFrom(WithoutStep(CaseAtSolution(*cases[m], *fits[m]), s),
                           *fits[m],
                           data,
                           "without " + s.effect,
                           &(*without)[k]);
  });
}

namespace {

// Whether the effects of `steps` but the `drop`th stay within their bounds
// as `options` judge them (ImplausibleAmongAsJudged) in `without`, the
// fit of `at` without that step. Prune judges those on a ridge within two
// of their errors (bounds_within_errors) in any search: there the point fit
// lands anywhere the record allows, and a step that only held it inside its
// bounds is no effect of the record's. On draw 143's pair of 3-s runs with
// a tunnel damping, a Magnus moment and a flow angularity (sigma: auto), a
// false body asymmetry stayed beside the three with Cn_beta at
// -Cm_alpha, Cn_r 0.14 from Cm_q: without it BIC fell by 3.0, but t4 came
// to 3.53 +- 0.29 with Cm_q -4.47 +- 0.33, past |t4| <= 2 |Cm_q + t4| at
// the point fit (truth 3.02 and -5.03).
bool OthersPlausibleWithout(const std::vector<DiagnosisStep>& steps,
                            int drop,
                            const Case& at,
                            const FitResult& without,
                            const DiagnoseOptions& options) {
  std::vector<const Effect*> others;
  for (int i = 0; i < static_cast<int>(steps.size()); ++i) {
    const Effect* e = FindEffect(steps[i].effect);
    if (i != drop && e != nullptr) others.push_back(e);
  }
  return ImplausibleAmongAsJudged(
             others, WithoutStep(at, steps[drop]), without, options)
      .empty();
}

// Backward elimination (diagnose.h): while the record is explained by two
// or more effects, the one whose removal costs least is dropped if the
// residuals stay at the noise level, BIC rises by less than min_bic_drop,
// and the others stay within their bounds without it (those on a ridge
// within two of their errors, OthersPlausibleWithout): on a 3-s run with a
// bearing moment, a calibration error and a roll torque (draw 107), a
// tunnel stiffness refused alone (t1 4.15 on Eq. 43's ridge, bound 0.146)
// came in with a roll damping and the bearing moment (t1 0.93 +- 1.63);
// pruned of both it was back at 4.15 +- 0.40, and named, Cm_alpha -4.4
// +- 0.4 against -0.28. `current` is the final model (d->FinalFit()'s
// case).
void Prune(const std::vector<TimeHistory>& data,
           const DiagnoseOptions& options,
           Diagnosis* d,
           Case* current) {
  DiagnoseOptions within = options;  // OthersPlausibleWithout's judgment
  within.bounds_within_errors = true;
  while (d->steps.size() >= 2) {
    const FitResult& fit = d->FinalFit();
    const Case at = CaseAtSolution(*current, fit);
    const int n = static_cast<int>(d->steps.size());
    std::vector<FitResult> without;
    std::vector<char> fitted;
    FitWithoutEach(data, {current}, {&fit}, d->steps, &without, &fitted);
    int drop = -1;
    double least = options.min_bic_drop;
    for (int i = 0; i < n; ++i) {
      if (!fitted[i] || !CheckResiduals(without[i], options).at_noise_level ||
          !OthersPlausibleWithout(d->steps, i, at, without[i], within)) {
        continue;
      }
      const double rise = Bic(without[i]) - Bic(fit);
      if (rise < least) {
        least = rise;
        drop = i;
      }
    }
    if (drop < 0) return;
    DiagnosisStep step = d->steps[drop];
    step.note = "redundant with " + Others(d->steps, drop) +
                " in the model: without it BIC changes by " +
                FormatNumber("%.1f", least) +
                " and the residuals stay at the noise level";
    step.after = CheckResiduals(without[drop], options);
    d->fits.push_back(without[drop]);
    step.fit_before = static_cast<int>(d->final_fit);
    step.fit_after = static_cast<int>(d->fits.size()) - 1;
    d->final_fit = d->fits.size() - 1;
    d->pruned.push_back(step);
    d->steps.erase(d->steps.begin() + drop);
    *current = WithoutStep(at, step);
  }
}

// The case `at` with the tied rival `id` free (CandidateCase): a catalog
// effect, a probe, or for drift_in_time the drift of the readings (what a
// roll-locked reading error is over part of a revolution), the names of
// the terms it frees in *added (when not null); false when it does not
// apply.
bool RivalCase(const Case& at,
               const std::string& id,
               Case* out,
               std::vector<std::string>* added = nullptr) {
  const Effect* e = FindEffect(id);
  if (e == nullptr) e = FindProbe(id == kDriftInTime ? "reading_drift" : id);
  std::vector<std::string> terms;
  return e != nullptr && CandidateCase(at, *e, out, added ? added : &terms);
}

// Whether two roll-locked effects can be told apart (Separation): a
// segment spins faster than half the pitch frequency of the model fitted
// as `fit`, where a trim moment's response grows and lags.
bool SpinSeparatesRollLocked(const Case& c,
                             const FitResult& fit,
                             const std::vector<TimeHistory>& data) {
  const double pitch = PitchFrequency(c, fit);
  for (const TimeHistory& h : data) {
    if (h.size() < 2 || !(h.t.back() > h.t.front())) continue;
    const double spin =
        std::abs(h.phi.back() - h.phi.front()) / (h.t.back() - h.t.front());
    if (pitch > 0.0 && spin > 0.5 * pitch) return true;
  }
  return false;
}

// A rival swapped in for a step (Unresolved).
struct Swap {
  const CandidateFit* rival = nullptr;
  const Effect* effect = nullptr;
  bool unfitted_as_good = false;
  // A roll-locked twin of a roll-locked step at spins that do not
  // separate them (Unresolved): fitted, and as good unless its model is
  // far worse.
  bool twin = false;
  // It lowered BIC within ambiguity_bic of the step where the step was
  // added (RefitFromRivalTerms).
  bool tied_at_step = false;
  Case c;
  std::vector<std::string> terms;
  bool fitted = false;
  FitResult fit;
  std::string held;  // a tunnel term held at zero, or none
};

// A model fitted as `swapped` that keeps a tie open (Diagnosis::TieModel),
// its BIC against `fit` (the model with the tied steps): what it holds in
// whose place is the caller's to fill in.
Diagnosis::TieModel FittedTieModel(const FitResult& swapped,
                                   const FitResult& fit,
                                   const DiagnoseOptions& options) {
  Diagnosis::TieModel m;
  m.bic = Bic(swapped);
  m.parameters = swapped.parameters;
  m.rise = m.bic - Bic(fit);
  m.check = CheckResiduals(swapped, options);
  return m;
}

// The swap `w` of `step` (one of `steps`, fitted as `fit`) as a model
// that keeps a tie open (Diagnosis::TieModel).
Diagnosis::TieModel AsTieModel(const DiagnosisStep& step,
                               const std::vector<DiagnosisStep>& steps,
                               const FitResult& fit,
                               const Swap& w,
                               const DiagnoseOptions& options) {
  Diagnosis::TieModel m = FittedTieModel(w.fit, fit, options);
  m.in_place_of = step.effect;
  m.effect = w.rival->effect;
  m.held = w.held;
  for (const DiagnosisStep& s : steps) {
    m.effects.push_back(s.effect == step.effect ? m.effect : s.effect);
  }
  return m;
}

// Whether the rival `effect` (null: a probe or a drift, no catalog bounds)
// swapped in as the model `c`, fitted as `fit` with its `terms` free, keeps
// within its bounds, judged within two of its errors.
bool RivalWithin(const Effect* effect,
                 const Case& c,
                 const FitResult& fit,
                 const std::vector<std::string>& terms) {
  return effect == nullptr ||
         ImplausibleWithin(*effect, c, fit, terms, kBoundErrors).empty();
}

// Whether the swap `w`, fitted, keeps its effect within its bounds
// (RivalWithin).
bool SwapWithin(const Swap& w) {
  return RivalWithin(w.effect, w.c, w.fit, w.terms);
}

// Whether the twin swap `w`, fitted (its BIC `rise` above the step's model,
// which reaches the noise) explains the record far worse: its residuals stay
// structured and BIC rises by ambiguity_bic or more. Twins are held in a
// tie whatever a close swap says (a trim moment had won one from the roll
// reading error that was there), but not against the record: on draw 41's
// two runs at 30 and 60 deg/s a trim moment in the place of a reading
// error that varies with roll in pitch and yaw apart (four terms, which a
// trim moment's two cannot follow) left the probable error at 1.20 with
// the tunnel stiffness and the angularity in, against 0.999.
bool FarWorse(const Swap& w, double rise, const DiagnoseOptions& options) {
  return rise >= options.ambiguity_bic &&
         !CheckResiduals(w.fit, options).at_noise_level;
}

// `w`'s case with every term but the rival's own (and the segments'
// initial conditions) held at the model's solution, where `w.c` has them.
Case RivalTermsOnly(const Swap& w) {
  Case held = w.c;
  const std::vector<ParameterInfo>& table = ParameterTable(held.model);
  for (size_t i = 0; i < held.parameters.size(); ++i) {
    ParameterSetting& p = held.parameters[i];
    if (p.tied() || std::find(w.terms.begin(), w.terms.end(), table[i].name) !=
                        w.terms.end()) {
      continue;
    }
    p.free = false;
  }
  held.SettleTies();
  return held;
}

// A swap of a rival that tied with the step where the step was added
// (`tied_at_step`) fitted far worse (by ambiguity_bic or more) is fitted
// again from a start where the rival's terms were fitted first with the
// model held (RivalTermsOnly), and the lower BIC of the two fits kept: the
// swap starts with the step's terms at zero, the record's response to them
// lost, and a fit from there can run off along a ridge of the model.
// On --vary-conditions draw 85's 3-s run with a gas-bearing moment, a
// calibration error and a roll torque, the roll damping and the roll
// torque lowered BIC alike at their step (35.37 and 35.36, twins at one
// spin rate), but the roll torque swapped in for the damping ran the
// bearing's angle from 5.9 to 9.7 deg and stopped 30.8 worse in BIC, and
// the roll damping was named; from its own terms first the swap is as good
// (BIC +0.00), a tie. Only such rivals: a swap costs a fit, and one that
// lost at its step by more is expected to lose.
void RefitFromRivalTerms(const FitResult& fit,
                         const std::vector<TimeHistory>& data,
                         Swap* w) {
  FitResult first;
  if (!FitFrom(RivalTermsOnly(*w),
               fit,
               data,
               "the terms of " + w->rival->effect + " alone",
               &first)) {
    return;
  }
  Case again = CaseAtSolution(w->c, first);
  FitResult staged;
  if (FitFrom(again,
              first,
              data,
              "with " + w->rival->effect + " from its terms",
              &staged) &&
      Bic(staged) < Bic(w->fit)) {
    w->fit = std::move(staged);
  }
}

// Out of its bounds on Eq. 43's ridge, a tunnel term runs along it as far
// as the record lets it: the swaps of `swaps` that did so, with each of
// the pair held at zero in turn (FindSingleReplacement's rule), unfitted.
// On draw 27's 3-s run with a tunnel stiffness, a nonlinear damping and a
// body asymmetry, the stiffness swapped in for a roll torque ran to t1 =
// 0.5 (bound 0.11, truth 8e-4) and lost; with t1 held at zero (t3
// -0.00095 +- 0.00006) it is 7 above the torque in BIC, the held term
// counted: a tie.
std::vector<Swap> HeldOnRidge(const std::vector<Swap>& swaps) {
  std::vector<Swap> held;
  for (const Swap& w : swaps) {
    if (!w.fitted || w.effect == nullptr || !OnTunnelRidge(*w.effect) ||
        SwapWithin(w)) {
      continue;
    }
    for (const std::string& name : w.terms) {
      Swap h = w;
      h.held = name;
      if (HoldAtZero(name, &h.c)) held.push_back(std::move(h));
    }
  }
  return held;
}

// Whether out of sample separates `rival` from `step`: the step, taken
// alone (not in a joint set), explained the record to the noise, and the
// rival, refitted at the same round, predicted the held-out part worse
// than the step and too little to earn its place (a finite gain at or
// below GainNeeded; NaN where not checked). Refused rivals count because
// effects still missing may hide their worth (Rivals): beside a missing
// nonlinear damping a roll reading error, a trim moment and a flow
// angularity all predicted worse, and a joint set then took the
// angularity with the damping. With nothing missing the
// refusal stands: on draw 38's coning run with a tunnel damping, a Magnus
// moment and a flow angularity, the angularity (gain 10.8, needs 4) and a
// roll reading error (7.4, needs 8) had tied 7.6 apart in BIC.
bool SeparatedOutOfSample(const CandidateFit& rival,
                          const DiagnosisStep& step,
                          const DiagnoseOptions& options) {
  if (step.joint_set || !step.after.at_noise_level ||
      !std::isfinite(rival.prediction_gain)) {
    return false;
  }
  const int terms =
      std::count_if(rival.parameters.begin(),
                    rival.parameters.end(),
                    [](const ParameterEstimate& e) { return e.free; });
  return terms > 0 && !(rival.prediction_gain > GainNeeded(terms, options)) &&
         rival.prediction_gain < step.prediction_gain;
}

// The swaps of `rivals` for `step` (of the model `at`, whose effects are
// `steps`) into the model without it, `without`, unfitted (Unresolved's
// rules): none for a rival in the model or one out of sample separates
// from the step; as good unfitted for a drift in time, or where it does
// not apply; a twin (as good unless far worse, FarWorse) for a
// roll-locked rival of a roll-locked step that tied with it at the step
// (one that lost there by more, WiderRivals, must win the swap), unless
// the spins separate them (`twins_separate`).
std::vector<Swap> SwapsFor(const std::vector<CandidateFit>& rivals,
                           const DiagnosisStep& step,
                           const std::vector<DiagnosisStep>& steps,
                           const Case& without,
                           bool twins_separate,
                           const DiagnoseOptions& options) {
  const Effect* own = FindEffect(step.effect);
  std::vector<Swap> swaps;
  for (const CandidateFit& rival : rivals) {
    if (HoldsEffect(steps, rival.effect)) continue;
    if (SeparatedOutOfSample(rival, step, options)) {
      VLOG(1) << step.effect << "'s rival " << rival.effect
              << " failed out of sample where it explained the record";
      continue;
    }
    Swap w;
    w.rival = &rival;
    w.effect = FindEffect(rival.effect);
    w.tied_at_step = step.bic_drop - rival.bic_drop < options.ambiguity_bic;
    w.twin = own != nullptr && own->roll_locked && w.effect != nullptr &&
             w.effect->roll_locked && !twins_separate && w.tied_at_step;
    w.unfitted_as_good = rival.effect == kDriftInTime ||
                         !RivalCase(without, rival.effect, &w.c, &w.terms);
    swaps.push_back(std::move(w));
  }
  return swaps;
}

// The rivals of `step` (recorded when the search added it) that still
// explain the record as well in the explained model `fit` (of case `at`,
// whose effects are `steps`): swapped in for it, BIC within ambiguity_bic
// of the model's and their values within two of their standard errors of
// their bounds (ImplausibleWithin, as beside the final model: on the Eq. 43
// ridge the point fit lands anywhere the record allows; on one 3-s run a tunnel
// stiffness swapped in for a roll torque lowered BIC by 1.1 with t1 =
// 0.138, past its bound, 0.115, and the roll torque was claimed where the
// truth was the tunnel stiffness). A drift in time
// (not fitted) always does, and so does a roll-locked rival of a
// roll-locked effect unless a segment spins fast enough to separate them
// (on two runs at 30 and 60 deg/s a trim moment had won the swap from the
// roll reading error that was there) or its swap is far worse (FarWorse);
// a rival in the model is none, nor one out of sample separates from the
// step (SeparatedOutOfSample). The
// models of the rivals that were fitted and kept the tie open go into
// *tie_models.
std::vector<CandidateFit> Unresolved(
    const std::vector<CandidateFit>& rivals,
    const DiagnosisStep& step,
    const std::vector<DiagnosisStep>& steps,
    const Case& at,
    const FitResult& fit,
    const std::vector<TimeHistory>& data,
    const DiagnoseOptions& options,
    std::vector<Diagnosis::TieModel>* tie_models) {
  const Case without = WithoutStep(at, step);
  const Effect* own = FindEffect(step.effect);
  std::vector<Swap> swaps = SwapsFor(rivals,
                                     step,
                                     steps,
                                     without,
                                     SpinSeparatesRollLocked(at, fit, data),
                                     options);
  // The swaps' fits are independent: side by side.
  auto fit_all = [&](std::vector<Swap>* all) {
    ParallelFor(static_cast<int>(all->size()), [&](int i) {
      Swap& w = (*all)[i];
      if (w.unfitted_as_good) return;
      w.fitted = FitFrom(w.c,
                         fit,
                         data,
                         "with " + w.rival->effect + " for " + step.effect,
                         &w.fit);
    });
  };
  fit_all(&swaps);
  const double log_n = BicPerTerm(fit);
  const bool roll_separates = RollSeparates(data);
  // A held term counts as fitted; judged for a tie by TieGap.
  auto rise = [&](const Swap& w) {
    const double r = Bic(w.fit) - Bic(fit) + (w.held.empty() ? 0.0 : log_n);
    if (own == nullptr || w.effect == nullptr) return r;
    return TieGap(r, *own, fit, *w.effect, w.fit, roll_separates);
  };
  ParallelFor(static_cast<int>(swaps.size()), [&](int i) {
    Swap& w = swaps[i];
    if (w.fitted && w.tied_at_step && rise(w) >= options.ambiguity_bic) {
      RefitFromRivalTerms(fit, data, &w);
    }
  });
  std::vector<Swap> held = HeldOnRidge(swaps);
  fit_all(&held);
  std::vector<CandidateFit> open;
  for (std::vector<Swap>* all : {&swaps, &held}) {
    for (Swap& w : *all) {
      const bool close =
          w.fitted && rise(w) < options.ambiguity_bic && SwapWithin(w);
      const bool as_good =
          w.unfitted_as_good || (w.held.empty() && !w.fitted) || close ||
          (w.twin && !(w.fitted && FarWorse(w, rise(w), options)));
      VLOG(1) << step.effect << " swapped for " << w.rival->effect
              << (w.held.empty() ? "" : ", " + w.held + " held at zero") << ": "
              << (as_good ? "as good" : "worse")
              << (w.fitted ? " (BIC " + FormatNumber("%+.2f", rise(w)) + ")"
                           : std::string());
      if (!as_good) continue;
      if (FindFit(open, w.rival->effect) == nullptr) open.push_back(*w.rival);
      if (close) {
        tie_models->push_back(AsTieModel(step, steps, fit, w, options));
      }
    }
  }
  return open;
}

// The rivals whose swap alone kept `step`'s tie open, none held on the
// ridge: the effects of `singles` (tie models) in its place.
std::vector<std::string> SwappedRivals(
    const DiagnosisStep& step,
    const std::vector<Diagnosis::TieModel>& singles) {
  std::vector<std::string> ids;
  for (const Diagnosis::TieModel& m : singles) {
    if (m.in_place_of == step.effect && m.held.empty() &&
        std::find(ids.begin(), ids.end(), m.effect) == ids.end()) {
      ids.push_back(m.effect);
    }
  }
  return ids;
}

// The tied steps' rivals two at a time (Diagnosis::cross_tie_models): the
// model `at`, fitted as `fit`, with a rival of each of two steps of
// `tied` in their places, each rival one whose swap alone kept its tie
// open (SwappedRivals of `singles`), into *cross when within
// ambiguity_bic of `fit` and each rival within kBoundErrors of its
// bounds (as a swap alone, RivalWithin).
void CrossTieModels(const std::vector<const DiagnosisStep*>& tied,
                    const std::vector<DiagnosisStep>& steps,
                    const Case& at,
                    const FitResult& fit,
                    const std::vector<TimeHistory>& data,
                    const DiagnoseOptions& options,
                    const std::vector<Diagnosis::TieModel>& singles,
                    std::vector<Diagnosis::TieModel>* cross) {
  struct Pair {
    const DiagnosisStep* first = nullptr;
    const DiagnosisStep* second = nullptr;
    std::array<std::string, 2> ids;
    std::array<std::vector<std::string>, 2> terms;
    Case c;
    bool fitted = false;
    FitResult fit;
  };
  std::vector<Pair> pairs;
  for (size_t i = 0; i < tied.size(); ++i) {
    for (size_t j = i + 1; j < tied.size(); ++j) {
      for (const std::string& a : SwappedRivals(*tied[i], singles)) {
        for (const std::string& b : SwappedRivals(*tied[j], singles)) {
          Pair x;
          x.first = tied[i];
          x.second = tied[j];
          x.ids = {a, b};
          Case one;
          if (RivalCase(WithoutStep(at, *tied[i]), a, &one, &x.terms[0]) &&
              RivalCase(WithoutStep(one, *tied[j]), b, &x.c, &x.terms[1])) {
            pairs.push_back(std::move(x));
          }
        }
      }
    }
  }
  ParallelFor(static_cast<int>(pairs.size()), [&](int k) {
    Pair& x = pairs[k];
    x.fitted = FitFrom(x.c,
                       fit,
                       data,
                       "with " + x.ids[0] + " and " + x.ids[1] + " for " +
                           x.first->effect + " and " + x.second->effect,
                       &x.fit);
  });
  for (const Pair& x : pairs) {
    if (!x.fitted) continue;
    const bool within =
        RivalWithin(FindEffect(x.ids[0]), x.c, x.fit, x.terms[0]) &&
        RivalWithin(FindEffect(x.ids[1]), x.c, x.fit, x.terms[1]);
    Diagnosis::TieModel m = FittedTieModel(x.fit, fit, options);
    VLOG(1) << x.ids[0] << " and " << x.ids[1] << " for " << x.first->effect
            << " and " << x.second->effect << ": BIC "
            << FormatNumber("%+.2f", m.rise)
            << (within ? "" : ", out of bounds");
    if (!within || !(m.rise < options.ambiguity_bic)) continue;
    m.in_place_of = x.second->effect;
    m.effect = x.ids[1];
    m.also_in_place_of = x.first->effect;
    m.also_effect = x.ids[0];
    for (const DiagnosisStep& s : steps) {
      m.effects.push_back(s.effect == x.first->effect    ? x.ids[0]
                          : s.effect == x.second->effect ? x.ids[1]
                                                         : s.effect);
    }
    cross->push_back(std::move(m));
  }
}

// How far BIC rises when a rival of the tied step `tied` does without
// `step`: of the tie models (`tie_models`) with a rival in `tied`'s place
// that reach the noise level, none held on a ridge, the least rise of the
// rival's model refitted without `step` (from `fit`, of the model `at`
// with the steps in) that stays at the noise level; infinity when none.
double RiseWithoutBesideRival(
    const DiagnosisStep& step,
    const DiagnosisStep& tied,
    const Case& at,
    const FitResult& fit,
    const std::vector<Diagnosis::TieModel>& tie_models,
    const std::vector<TimeHistory>& data,
    const DiagnoseOptions& options,
    std::string* rival) {
  double least = std::numeric_limits<double>::infinity();
  const Case without = WithoutStep(WithoutStep(at, tied), step);
  for (const Diagnosis::TieModel& m : tie_models) {
    if (m.in_place_of != tied.effect || !m.held.empty() ||
        !m.check.at_noise_level) {
      continue;
    }
    Case c;
    FitResult refit;
    if (!RivalCase(without, m.effect, &c) ||
        !FitFrom(c,
                 fit,
                 data,
                 "with " + m.effect + " for " + tied.effect + ", without " +
                     step.effect,
                 &refit) ||
        !CheckResiduals(refit, options).at_noise_level) {
      continue;
    }
    const double rise = Bic(refit) - m.bic;
    VLOG(1) << step.effect << " beside " << m.effect << " in " << tied.effect
            << "'s place: BIC " << FormatNumber("%+.1f", rise) << " without it";
    if (rise < least) {
      least = rise;
      *rival = m.effect;
    }
  }
  return least;
}

// The steps before `first`, the last step and the one tie, that go with
// the tied effect the search followed: needed beside it (Prune kept them
// in `steps`, the model `at` fitted as `fit`), not beside a rival in its
// place (RiseWithoutBesideRival below min_bic_drop), marked in `tied` and
// `redundant` as the steps pruned beside it are: WithoutPrunedBeforeTie
// takes them out of the final model into the partial steps. Where steps
// follow the tie, CompanionsWithinTie asks the same of the adopted
// answer. On draw 166's 3.9-s cone with a tunnel stiffness, a nonlinear
// damping and a body asymmetry a Magnus moment came in a joint set with
// the damping and the asymmetry (-29.9 +- 8.7 in the final model), and a
// tunnel damping tied with the stiffness after them; beside the stiffness
// the Magnus moment stood at -4.7 +- 8.8, and was named.
void CompanionsBeforeLastTie(const std::vector<DiagnosisStep>& steps,
                             const Case& at,
                             const FitResult& fit,
                             const std::vector<TimeHistory>& data,
                             const DiagnoseOptions& options,
                             int first,
                             std::vector<bool>* tied,
                             std::vector<bool>* redundant,
                             Diagnosis* d) {
  const DiagnosisStep& tied_step = d->steps[first];
  for (int j = 0; j < first; ++j) {
    if ((*tied)[j]) continue;
    const auto kept =
        std::find_if(steps.begin(), steps.end(), [&](const DiagnosisStep& s) {
          return s.effect == d->steps[j].effect;
        });
    if (kept == steps.end()) continue;
    std::string rival;
    const double rise = RiseWithoutBesideRival(
        *kept, tied_step, at, fit, d->tie_models, data, options, &rival);
    if (!(rise < options.min_bic_drop)) continue;
    (*tied)[j] = true;
    (*redundant)[j] = true;
    d->steps[j].note = "goes with " + tied_step.effect +
                       ": needed beside it, not beside " + rival + " (BIC " +
                       FormatNumber("%+.1f", rise) + " without it)";
    VLOG(1) << d->steps[j].effect << " " << d->steps[j].note;
  }
}

// The steps before the first tie (`first`) without rivals that the
// pruning took away (`pruned`, of `steps`) marked in doubt and redundant:
// no more needed. On draw 105's coning run with a bearing moment, a
// calibration error and a roll torque (tied with a roll damping), a tunnel
// damping taken first ended t2 = 0.058 +- 0.062, t4 = 0.033 +- 0.068 in the
// final model, each complete model 9 lower in BIC without it.
void PrunedBeforeTie(const std::vector<std::vector<CandidateFit>>& rivals,
                     const std::vector<DiagnosisStep>& pruned,
                     const std::vector<DiagnosisStep>& steps,
                     int first,
                     std::vector<bool>* tied,
                     std::vector<bool>* redundant) {
  for (int i = 0; i < first; ++i) {
    if (!rivals[i].empty() || HoldsEffect(pruned, steps[i].effect)) continue;
    (*tied)[i] = true;
    (*redundant)[i] = true;
  }
}

// Ties (the first at step *tie; `rivals` holds each step's) on the way to
// a record explained: the pruning (Prune) of every step, then the rivals
// of each step still in the model swapped in for it (Unresolved). A roll torque
// tied with a roll damping may only have taken up the roll that a missing pitch
// damping left: once that is in, neither is needed. A tunnel stiffness tied
// with a roll-synchronous reading error, both hidden in the record, is followed
// by the other: both needed, nothing ambiguous. And a calibration error tied
// with a flow angularity while a trim moment was still missing is alone in
// explaining the record once the trim moment is in: swapped for it, the flow
// angularity raises BIC by more than ambiguity_bic. When no rival of any
// step is left, *d and *current take the pruned result and the ties are
// gone; otherwise *tie becomes the first step with rivals left,
// d->ambiguous its effect and those rivals, (*tied)[i] whether step i
// (pruned or with rivals left) stays in doubt, (*redundant)[i] whether it
// was pruned, and *current is left as it was.
bool TieDissolves(const std::vector<TimeHistory>& data,
                  const DiagnoseOptions& options,
                  const std::vector<std::vector<CandidateFit>>& rivals,
                  int* tie,
                  std::vector<bool>* tied,
                  std::vector<bool>* redundant,
                  Diagnosis* d,
                  Case* current) {
  Diagnosis pruned = *d;
  Case model = *current;
  pruned.final_fit = pruned.steps.size();
  Prune(data, options, &pruned, &model);
  const FitResult& fit = pruned.FinalFit();
  const Case at = CaseAtSolution(model, fit);
  std::vector<std::vector<CandidateFit>> open_ties;
  std::vector<const DiagnosisStep*> tied_steps;
  int first = -1;
  for (size_t i = 0; i < d->steps.size(); ++i) {
    if (rivals[i].empty()) continue;
    const auto kept = std::find_if(
        pruned.steps.begin(), pruned.steps.end(), [&](const DiagnosisStep& s) {
          return s.effect == d->steps[i].effect;
        });
    // A step pruned away is not in doubt. Nor does it end the steps
    // adopted after a tie (StartAdoption): adopted with them, it is taken
    // out again where no complete model needs it (PruneWithinTie).
    (*tied)[i] = true;
    (*redundant)[i] = kept == pruned.steps.end();
    if ((*redundant)[i]) continue;
    const std::vector<CandidateFit> open = Unresolved(
        rivals[i], *kept, pruned.steps, at, fit, data, options, &d->tie_models);
    (*tied)[i] = !open.empty();
    if (open.empty()) continue;
    if (first < 0) first = static_cast<int>(i);
    tied_steps.push_back(&*kept);
    open_ties.push_back({AsContender(d->steps[i])});
    open_ties.back().insert(open_ties.back().end(), open.begin(), open.end());
  }
  if (first >= 0) {
    PrunedBeforeTie(rivals, pruned.steps, d->steps, first, tied, redundant);
    if (open_ties.size() == 1 && first + 1 == static_cast<int>(tied->size())) {
      CompanionsBeforeLastTie(
          pruned.steps, at, fit, data, options, first, tied, redundant, d);
    }
    *tie = first;
    d->cross_tie_models.clear();
    CrossTieModels(tied_steps,
                   pruned.steps,
                   at,
                   fit,
                   data,
                   options,
                   d->tie_models,
                   &d->cross_tie_models);
    d->ambiguous = open_ties[0];
    d->later_ties.assign(open_ties.begin() + 1, open_ties.end());
    return false;
  }
  *d = std::move(pruned);
  d->ambiguous.clear();
  *current = std::move(model);
  return true;
}

// Whether the effects adopted after a tie are needed with `rival` in
// place of the tied effect too: `without` (their model without any of the
// tied effects, fitted as `without_fit`) with the rival (*with_rival),
// fitted into *rival_fit, lowers BIC by min_bic_drop below the rival alone on
// the model before the tie (`before_tie`, fitted as `before`), and every effect
// in it (`effects` and the rival) stays within its bounds.
bool AdoptedWithRival(const std::vector<TimeHistory>& data,
                      const DiagnoseOptions& options,
                      const std::vector<const Effect*>& effects,
                      const Case& without,
                      const FitResult& without_fit,
                      const Case& before_tie,
                      const FitResult& before,
                      const std::string& rival,
                      Case* with_rival,
                      FitResult* rival_fit) {
  Case rival_alone;
  FitResult rival_alone_fit;
  return RivalCase(CaseAtSolution(without, without_fit), rival, with_rival) &&
         FitFrom(*with_rival, without_fit, data, "with " + rival, rival_fit) &&
         RivalCase(CaseAtSolution(before_tie, before), rival, &rival_alone) &&
         FitFrom(rival_alone,
                 before,
                 data,
                 "with " + rival + " alone",
                 &rival_alone_fit) &&
         Bic(*rival_fit) < Bic(rival_alone_fit) - options.min_bic_drop &&
         ImplausibleAmong(effects, *with_rival, *rival_fit).empty();
}

// Whether the effects adopted after a tie (`effects`, with those before
// it) are needed without any of the tied effects: `without` (the complete
// model without the tied step, fitted as `without_fit`) lowers BIC by
// min_bic_drop below `before` (the model before the tie) and keeps every
// effect within its bounds.
bool NeededWithoutTied(const DiagnoseOptions& options,
                       const std::vector<const Effect*>& effects,
                       const Case& without,
                       const FitResult& without_fit,
                       const FitResult& before) {
  const std::string implausible =
      ImplausibleAmong(effects, without, without_fit);
  if (Bic(without_fit) < Bic(before) - options.min_bic_drop &&
      implausible.empty()) {
    return true;
  }
  VLOG(1) << "without any of the tied effects: BIC "
          << Bic(before) - Bic(without_fit) << " below the model before "
          << "the tie; " << implausible;
  return false;
}

// The complete model with `rival` in place of the tied step `tied`: the
// search's last model (`full`, fitted as `full_fit`, which holds a later
// tie's followed effect too) with the rival swapped in, fitted into *fit.
// A complete model without the later tie's effect stays structured (on a
// short run a tunnel damping tied with a body asymmetry, a flow angularity
// with a roll reading error, and neither first alternative reached the
// noise without the angularity).
bool CompleteWithRival(const std::vector<TimeHistory>& data,
                       const Case& full,
                       const FitResult& full_fit,
                       const DiagnosisStep& tied,
                       const std::string& rival,
                       Case* with_rival,
                       FitResult* fit) {
  const Case without = WithoutStep(CaseAtSolution(full, full_fit), tied);
  return RivalCase(without, rival, with_rival) &&
         FitFrom(*with_rival, full_fit, data, "complete with " + rival, fit);
}

// Whether each of `steps` is needed in each complete model (`cases`,
// fitted as `fits`): without it BIC rises by more than min_bic_drop. A
// tied effect stands in for the tie only then: on a pair of runs a roll
// damping adopted after a roll torque (tied with a tunnel stiffness) went
// implausible without the torque, because it was there to cancel it.
bool NeededInEach(const std::vector<TimeHistory>& data,
                  const DiagnoseOptions& options,
                  const std::vector<const Case*>& cases,
                  const std::vector<const FitResult*>& fits,
                  const std::vector<DiagnosisStep>& steps) {
  std::vector<FitResult> without;
  std::vector<char> fitted;
  FitWithoutEach(data, cases, fits, steps, &without, &fitted);
  for (size_t k = 0; k < without.size(); ++k) {
    const FitResult& with = *fits[k / steps.size()];
    if (!fitted[k] || !(Bic(without[k]) > Bic(with) + options.min_bic_drop)) {
      VLOG(1) << steps[k % steps.size()].effect
              << " not needed in a complete model: BIC +"
              << Bic(without[k]) - Bic(with) << " without it";
      return false;
    }
  }
  return true;
}

// The effects of the model AdoptAfterTie adopts (the steps before the tie
// and `adopt`, indices into d.steps) into *effects, and the terms `adopt`
// added into *names.
void AdoptedEffects(const Diagnosis& d,
                    int tie,
                    const std::vector<int>& adopt,
                    std::vector<const Effect*>* effects,
                    std::vector<std::string>* names) {
  effects->clear();
  names->clear();
  for (int i = 0; i < tie; ++i) {
    effects->push_back(FindEffect(d.steps[i].effect));
  }
  for (int i : adopt) {
    effects->push_back(FindEffect(d.steps[i].effect));
    for (const ParameterEstimate& e : d.steps[i].step_parameters) {
      names->push_back(e.name);
    }
  }
}

// The steps of `adopt` (indices into d.steps, after the tie) that go with
// the tied effect rather than after it: out of their bounds in `without`
// (the complete model without the tied effect, fitted as `without_fit`),
// and not needed with a rival of the tie in its place (without them, that
// model's BIC rises by less than min_bic_drop). On a pair of runs a roll
// damping adopted after a roll torque (tied with a tunnel stiffness) drove
// the roll without the torque, and with the stiffness instead BIC was 4.8
// lower without it: it was the torque's companion.
std::vector<int> TieCompanions(const std::vector<TimeHistory>& data,
                               const DiagnoseOptions& options,
                               const Diagnosis& d,
                               const std::vector<int>& adopt,
                               const Case& without,
                               const FitResult& without_fit) {
  std::vector<int> companions;
  const Case at = CaseAtSolution(without, without_fit);
  for (int i : adopt) {
    const DiagnosisStep& step = d.steps[i];
    if (Implausible(*FindEffect(step.effect), without, without_fit).empty()) {
      continue;
    }
    for (size_t r = 1; r < d.ambiguous.size(); ++r) {
      Case with_rival;
      FitResult rival_fit, alone;
      if (!RivalCase(at, d.ambiguous[r].effect, &with_rival) ||
          !FitFrom(with_rival, without_fit, data, "companions", &rival_fit) ||
          !FitFrom(WithoutStep(CaseAtSolution(with_rival, rival_fit), step),
                   rival_fit,
                   data,
                   "without " + step.effect,
                   &alone)) {
        continue;
      }
      if (Bic(alone) < Bic(rival_fit) + options.min_bic_drop) {
        VLOG(1) << step.effect << " goes with the tied effect: with "
                << d.ambiguous[r].effect << " BIC +"
                << Bic(alone) - Bic(rival_fit) << " without it";
        companions.push_back(i);
        break;
      }
    }
  }
  return companions;
}

// `companions` (TieCompanions) taken out of *adopt and of *without, which
// is refitted into *without_fit; false when nothing is left to adopt or
// the fit fails.
bool WithoutCompanions(const std::vector<TimeHistory>& data,
                       const Diagnosis& d,
                       const std::vector<int>& companions,
                       std::vector<int>* adopt,
                       Case* without,
                       FitResult* without_fit) {
  Case c = CaseAtSolution(*without, *without_fit);
  for (int i : companions) {
    c = WithoutStep(c, d.steps[i]);
    adopt->erase(std::find(adopt->begin(), adopt->end(), i));
  }
  FitResult fit;
  if (adopt->empty() ||
      !FitFrom(c, *without_fit, data, "without the tie's companions", &fit)) {
    return false;
  }
  *without = std::move(c);
  *without_fit = std::move(fit);
  return true;
}

// The steps of `d` split at an adopted tie: the tied step and the steps
// after it not in `adopt` (its companions, those after the next tie) go to
// d->partial; the steps before it and `adopt` stay.
void SplitAtTie(int tie, const std::vector<int>& adopt, Diagnosis* d) {
  std::vector<DiagnosisStep> steps(d->steps.begin(), d->steps.begin() + tie);
  d->partial.assign(1, d->steps[tie]);
  for (int i = tie + 1; i < static_cast<int>(d->steps.size()); ++i) {
    const bool adopted =
        std::find(adopt.begin(), adopt.end(), i) != adopt.end();
    (adopted ? steps : d->partial).push_back(d->steps[i]);
  }
  d->steps = std::move(steps);
}

// What AdoptAfterTie weighs after a tie at step `tie`: the steps after it
// to adopt, the complete model without the tied step, and the complete
// model with each tied effect.
struct Adoption {
  int tie = 0;
  int through = 0;         // d->fits of the complete model through the last
  int full = 0;            // that with every step the search took
  bool later = false;      // a later tie's followed effects are in `full`
  std::vector<int> adopt;  // the steps after the tie to adopt
  // Each step Prune found redundant in the explained model: not asked to
  // be needed in each complete model (PruneWithinTie takes it out after).
  std::vector<bool> redundant;
  Case without;  // the complete model without the tied step
  FitResult without_fit;
  std::vector<const Effect*> effects;  // the adopted model's
  std::vector<std::string> names;      // the terms added after the tie
  std::vector<int> companions;         // TieCompanions
  bool stand_in = false;  // the adopted steps need one of the tied effects
  // The complete models with each tied effect, the first the search's;
  // the rivals' fits and cases beside them.
  std::vector<AlternativeModel> alternatives;
  std::vector<FitResult> rival_fits;
  std::vector<Case> rival_cases;
};

// The steps after the tie up to the next one (`tied` marks every step in
// doubt) into *a, with the complete model without the tied step fitted;
// a step the explained model does without (`redundant`, pruned) does not
// end the run: on a Table 6 record a nonlinear stiffness taken in a joint
// set with a bearing moment and a calibration error, redundant beside
// them, had left them partial. A step out of its bounds without the tied
// effect may be its companion (TieCompanions): it goes with it. False when
// nothing but redundant steps is left to adopt, a fit fails, or the adopted
// steps need one of the tied effects while a later tie or a companion
// leaves no stand-in.
bool StartAdoption(const std::vector<TimeHistory>& data,
                   const DiagnoseOptions& options,
                   const std::vector<Case>& models,
                   int tie,
                   const std::vector<bool>& tied,
                   const std::vector<bool>& redundant,
                   const Diagnosis& d,
                   Adoption* a) {
  int last = tie;  // the last step to adopt
  while (last + 1 < static_cast<int>(d.steps.size()) &&
         (!tied[last + 1] || redundant[last + 1])) {
    ++last;
  }
  VLOG(1) << "after the tie at step " << tie << ": " << last - tie
          << " step(s) before the next tie";
  for (int i = tie + 1; i <= last; ++i) a->adopt.push_back(i);
  a->redundant = redundant;
  const auto kept = [&](int i) { return !redundant[i]; };
  if (std::none_of(a->adopt.begin(), a->adopt.end(), kept)) return false;
  a->tie = tie;
  a->through = last + 1;
  const FitResult& complete = d.fits[a->through];
  const FitResult& before = d.fits[tie];
  a->without =
      WithoutStep(CaseAtSolution(models[a->through], complete), d.steps[tie]);
  if (!FitFrom(a->without,
               complete,
               data,
               "without " + d.steps[tie].effect,
               &a->without_fit)) {
    return false;
  }
  AdoptedEffects(d, tie, a->adopt, &a->effects, &a->names);
  bool needed = NeededWithoutTied(
      options, a->effects, a->without, a->without_fit, before);
  if (!needed) {
    a->companions =
        TieCompanions(data, options, d, a->adopt, a->without, a->without_fit);
  }
  if (!a->companions.empty()) {
    if (!WithoutCompanions(
            data, d, a->companions, &a->adopt, &a->without, &a->without_fit)) {
      return false;
    }
    AdoptedEffects(d, tie, a->adopt, &a->effects, &a->names);
    needed = NeededWithoutTied(
        options, a->effects, a->without, a->without_fit, before);
  }
  if (std::none_of(a->adopt.begin(), a->adopt.end(), kept)) return false;
  a->stand_in = !needed;
  // The complete models: with every step the search took (a later tie's
  // followed effects in).
  a->later = last + 1 < static_cast<int>(d.steps.size());
  if (a->stand_in && (a->later || !a->companions.empty())) {
    VLOG(1) << "no stand-in for the tie with a later tie or companions";
    return false;
  }
  a->full = a->later ? static_cast<int>(d.partial_fit) : a->through;
  return true;
}

// The complete models into a->alternatives: the search's, then with each
// rival instead of the tied step, against that rival alone on the model
// before the tie. False when one is not needed, not plausible or not
// fitted.
bool RivalAlternatives(const std::vector<TimeHistory>& data,
                       const DiagnoseOptions& options,
                       const std::vector<Case>& models,
                       const Diagnosis& d,
                       Adoption* a) {
  const int full = a->full;
  a->alternatives = {{d.steps[a->tie].effect,
                      CheckResiduals(d.fits[full], options),
                      d.fits[full].parameters,
                      full,
                      models[full]}};
  for (size_t r = 1; r < d.ambiguous.size(); ++r) {
    const std::string& rival = d.ambiguous[r].effect;
    // A drift in time is no model (a straight drift of the readings stands
    // in for it) and is tested only when it is the one rival.
    if (rival == kDriftInTime && d.ambiguous.size() > 2) continue;
    FitResult rival_fit;
    Case with_rival;
    if (!AdoptedWithRival(data,
                          options,
                          a->effects,
                          a->without,
                          a->without_fit,
                          models[a->tie],
                          d.fits[a->tie],
                          rival,
                          &with_rival,
                          &rival_fit)) {
      VLOG(1) << "not needed, or not plausible, with " << rival;
      return false;
    }
    if (a->later && !CompleteWithRival(data,
                                       models[full],
                                       d.fits[full],
                                       d.steps[a->tie],
                                       rival,
                                       &with_rival,
                                       &rival_fit)) {
      return false;
    }
    a->alternatives.push_back({rival,
                               CheckResiduals(rival_fit, options),
                               rival_fit.parameters,
                               -1,
                               with_rival});
    a->rival_fits.push_back(std::move(rival_fit));
    a->rival_cases.push_back(std::move(with_rival));
  }
  return true;
}

// Whether the adoption holds: a stand-in for the tie needs every complete
// model at the noise and the adopted steps needed in each (NeededInEach);
// short of that, the adopted effects must not drag the coefficients.
bool AdoptionHolds(const std::vector<TimeHistory>& data,
                   const DiagnoseOptions& options,
                   const std::vector<Case>& models,
                   const Diagnosis& d,
                   const Adoption& a) {
  // Every complete model at the noise: what the final model leaves is
  // known (the tie's signature).
  const bool known = std::all_of(
      a.alternatives.begin(),
      a.alternatives.end(),
      [](const AlternativeModel& m) { return m.check.at_noise_level; });
  if (a.stand_in && (!known || a.rival_fits.empty())) {
    VLOG(1) << "a stand-in for the tie needs every complete model at the "
            << "noise";
    return false;
  }
  if (a.stand_in) {
    std::vector<const Case*> cases = {&models[a.through]};
    std::vector<const FitResult*> fits = {&d.fits[a.through]};
    for (size_t r = 0; r < a.rival_fits.size(); ++r) {
      cases.push_back(&a.rival_cases[r]);
      fits.push_back(&a.rival_fits[r]);
    }
    std::vector<DiagnosisStep> steps;
    for (int i : a.adopt) {
      if (!a.redundant[i]) steps.push_back(d.steps[i]);
    }
    if (!NeededInEach(data, options, cases, fits, steps)) return false;
  }
  // The drag rule guards against an effect absorbing an unknown structure;
  // when every complete model reaches the noise, what the final model
  // leaves is known (the tie's signature), and the coefficients may move.
  if (!known) {
    const std::string drags =
        Drags(d.fits[a.tie], a.without_fit, a.names, options.max_drag);
    if (!drags.empty()) {
      VLOG(1) << "the adopted effects drag the coefficients: " << drags;
      return false;
    }
  }
  return true;
}

// The adoption `a` (moved from) taken into *d: the complete models
// reported as its alternatives, the final model (*current, its check in
// *final) the stand-in's or the one without the tied step, and the steps
// split at the tie (SplitAtTie).
void Adopt(const std::vector<TimeHistory>& data,
           const DiagnoseOptions& options,
           const std::vector<Case>& models,
           Adoption a,
           Diagnosis* d,
           Case* current,
           ResidualCheck* final) {
  std::vector<const Case*> complete = {&models[a.full]};
  std::vector<FitResult*> fits = {&d->fits[a.full]};
  for (size_t r = 0; r < a.rival_fits.size(); ++r) {
    complete.push_back(&a.rival_cases[r]);
    fits.push_back(&a.rival_fits[r]);
  }
  ReportedAll(complete, data, fits);
  a.alternatives[0].parameters = d->fits[a.full].parameters;
  for (size_t r = 0; r < a.rival_fits.size(); ++r) {
    a.alternatives[r + 1].parameters = a.rival_fits[r].parameters;
    d->fits.push_back(std::move(a.rival_fits[r]));
    a.alternatives[r + 1].fit = static_cast<int>(d->fits.size()) - 1;
  }
  d->alternatives = std::move(a.alternatives);
  if (a.stand_in) {
    d->stand_in = d->steps[a.tie].effect;
    d->final_fit = a.through;
    *current = models[a.through];
  } else {
    d->fits.push_back(a.without_fit);
    d->final_fit = d->fits.size() - 1;
    *current = a.without;
  }
  SplitAtTie(a.tie, a.adopt, d);
  *final = CheckResiduals(d->FinalFit(), options);
  d->steps.back().after = *final;
}

// After a tie (at step `tie`; `tied` marks every step that stays in
// doubt) followed to an explained record: the steps after it up to the
// next tie are adopted when the record needs them whichever of the tied
// effects (d->ambiguous) is in it (diagnose.h). The tied step (and any
// after the next tie) is then partial, the final model *current is the one
// before the tie with them added, d->alternatives holds the complete model
// with each of the tied effects,
// *final gets the final model's residual check, and true is returned;
// otherwise nothing changes. When the adopted effects need one of the tied
// effects (without any, they leave their bounds or explain nothing) and
// every complete model reaches the noise, the final model is the complete
// one with the first tied effect standing in for the tie
// (Diagnosis::stand_in): on a Table 6 record a roll damping and a roll
// torque are twins at constant spin, and without either the calibration
// error the bearing moment needs went out of its bounds.
bool AdoptAfterTie(const std::vector<TimeHistory>& data,
                   const DiagnoseOptions& options,
                   const std::vector<Case>& models,
                   int tie,
                   const std::vector<bool>& tied,
                   const std::vector<bool>& redundant,
                   Diagnosis* d,
                   Case* current,
                   ResidualCheck* final) {
  Adoption a;
  if (!StartAdoption(data, options, models, tie, tied, redundant, *d, &a) ||
      !RivalAlternatives(data, options, models, *d, &a) ||
      !AdoptionHolds(data, options, models, *d, a)) {
    return false;
  }
  Adopt(data, options, models, std::move(a), d, current, final);
  return true;
}

}  // namespace

std::vector<CandidateFit> Rivals(const std::vector<Contender>& contenders,
                                 int best,
                                 const Contender* probe,
                                 const std::vector<TimeHistory>& data,
                                 const DiagnoseOptions& options) {
  const Contender& lead = contenders[best];
  const bool roll_separates = RollSeparates(data);
  std::vector<CandidateFit> rivals;
  for (int i = 0; i < static_cast<int>(contenders.size()); ++i) {
    if (i != best &&
        TieGap(lead, contenders[i], roll_separates) < options.ambiguity_bic) {
      rivals.push_back(contenders[i].record);
    }
  }
  // A probe behind the lead is named beside its step, not tied
  // (WeighProbes, TakeBest).
  const bool probe_ahead = probe != nullptr && probe->bic < lead.bic;
  if (probe_ahead) rivals.push_back(probe->record);
  // A fitted drift probe is the drift in time itself, with its values.
  if (lead.candidate->effect->roll_locked && !roll_separates &&
      !(probe_ahead && probe->candidate->effect->drifts_in_time)) {
    rivals.push_back(DriftInTime());
  }
  return rivals;
}

std::vector<CandidateFit> WiderRivals(std::vector<CandidateFit> rivals,
                                      const std::vector<Contender>& contenders,
                                      int best,
                                      const DiagnoseOptions& options) {
  for (CandidateFit& k :
       Near(contenders, best, contenders[best].bic + options.rival_bic)) {
    if (std::none_of(rivals.begin(), rivals.end(), [&](const CandidateFit& r) {
          return r.effect == k.effect;
        })) {
      rivals.push_back(std::move(k));
    }
  }
  return rivals;
}

namespace {

// Whether `id` takes up a roll part of Eq. 39's tunnel moments: a roll
// moment, or a tunnel term itself.
bool TakesRollPart(const std::string& id) {
  const Effect* e = FindEffect(id);
  return IsRollMoment(id) || (e != nullptr && OnTunnelRidge(*e));
}

// Whether `steps` or the rivals of any (`earlier`) take up the roll part.
bool RollPartTaken(const std::vector<DiagnosisStep>& steps,
                   const std::vector<std::vector<CandidateFit>>& earlier) {
  for (const DiagnosisStep& s : steps) {
    if (TakesRollPart(s.effect)) return true;
  }
  for (const std::vector<CandidateFit>& rivals : earlier) {
    for (const CandidateFit& k : rivals) {
      if (TakesRollPart(k.effect)) return true;
    }
  }
  return false;
}

}  // namespace

std::vector<CandidateFit> RollPartRivals(
    std::vector<CandidateFit> rivals,
    const std::vector<Contender>& contenders,
    int best,
    const std::vector<Candidate>& candidates,
    const FitResult& fit,
    const std::vector<TimeHistory>& data,
    const std::vector<DiagnosisStep>& steps,
    const std::vector<std::vector<CandidateFit>>& earlier) {
  if (!IsRollMoment(contenders[best].record.effect) ||
      RollPartTaken(steps, earlier) ||
      FindFit(rivals, "tunnel_stiffness") != nullptr) {
    return rivals;
  }
  const auto stiffness = std::find_if(
      candidates.begin(), candidates.end(), [](const Candidate& k) {
        return k.effect->id == "tunnel_stiffness";
      });
  if (stiffness == candidates.end()) return rivals;
  const auto refitted = std::find_if(
      contenders.begin(), contenders.end(), [&](const Contender& c) {
        return c.candidate == &*stiffness;
      });
  Contender refit;
  if (refitted != contenders.end()) {
    rivals.push_back(refitted->record);
  } else if (Refit(*stiffness, fit, data, &refit)) {
    rivals.push_back(std::move(refit.record));
  }
  return rivals;
}

Case WithoutStep(const Case& at, const DiagnosisStep& step) {
  Case without = at;
  const Effect* effect = FindEffect(step.effect);
  CHECK(effect != nullptr) << step.effect;
  // The step's terms, and the effect's in the form `at` holds it in: a
  // later round may have taken the step back to its own form
  // (BackToOwnForms) while an earlier model still holds the other.
  std::vector<std::string> names;
  for (const ParameterEstimate& e : step.step_parameters) {
    names.push_back(e.name);
  }
  for (const std::string& name : TermsIn(at, *effect)) {
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      names.push_back(name);
    }
  }
  for (const std::string& term : names) {
    const int position = AddedTermPosition(without.model, term);
    if (position < 0) continue;
    const std::string& name = ParameterTable(without.model)[position].name;
    ParameterSetting& p = without.parameters[position];
    ParameterTie tie;
    if (without.model == ModelKind::kAsymmetric && SymmetricTie(name, &tie) &&
        !without.parameters[tie.source].tied()) {
      p = ParameterSetting::Tied(tie);
      continue;
    }
    p.free = false;
    if (!IsCompanion(*effect, name)) p.value = 0.0;
  }
  without.SettleTies();
  return without;
}

bool HoldsEffect(const std::vector<DiagnosisStep>& steps,
                 const std::string& effect) {
  return std::any_of(steps.begin(), steps.end(), [&](const DiagnosisStep& s) {
    return s.effect == effect;
  });
}

CandidateFit AsContender(const DiagnosisStep& step) {
  CandidateFit c;
  c.effect = step.effect;
  c.parameters = step.step_parameters;
  c.bic_drop = step.bic_drop;
  c.prediction_gain = step.prediction_gain;
  return c;
}

std::string SeparatedBy(const std::vector<CandidateFit>& ambiguous,
                        const Case& c,
                        const FitResult& fit,
                        const std::vector<TimeHistory>& data) {
  const Effect* a = FindEffect(ambiguous[0].effect);
  const Effect* b = FindEffect(ambiguous[1].effect);
  if (a != nullptr && b != nullptr) return Separation(*a, *b, c, fit);
  // A fitted drift is the drift in time a roll-locked effect is over less
  // than a revolution of roll.
  const Effect* drift = FindProbe(ambiguous[1].effect);
  if (ambiguous[1].effect == kDriftInTime ||
      (a != nullptr && drift != nullptr && DriftTwin(*a, *drift, data))) {
    return "a record spanning a revolution of roll (this one: " +
           FormatNumber("%.0f", RollSpan(data)) +
           " deg) or a run at another spin rate";
  }
  for (const CandidateFit& k : ambiguous) {
    const Effect* probe = FindProbe(k.effect);
    if (probe != nullptr && !probe->separated_by.empty()) {
      return probe->separated_by;
    }
  }
  return "a second run at another spin rate or amplitude (a drift grows "
         "with the time of each run, a catalog effect follows what the runs "
         "differ in)";
}

void SeparateTies(const Case& c,
                  const std::vector<TimeHistory>& data,
                  Diagnosis* d) {
  if (!d->ambiguous.empty()) {
    d->separated_by = SeparatedBy(d->ambiguous, c, d->FinalFit(), data);
  }
  d->later_separated_by.clear();
  for (const std::vector<CandidateFit>& tie : d->later_ties) {
    d->later_separated_by.push_back(SeparatedBy(tie, c, d->FinalFit(), data));
  }
}

namespace {

// The steps before the tie that TieDissolves pruned from the complete
// model (`tied`) taken out of the final model *current (d->FinalFit(),
// the model before the tie; *check its residual check) and reported as
// partial: beside the tie's effect they were not needed, so before it
// they only stood in for part of it. On a coning run with a roll reading
// error and a nonlinear damping (90 deg of roll), a flow angularity,
// adopted with the damping and a trim moment (tied with the reading
// error), was pruned beside the trim moment but stayed in the final
// model, a false effect. Unchanged when the refit fails.
void WithoutPrunedBeforeTie(const std::vector<TimeHistory>& data,
                            const DiagnoseOptions& options,
                            const std::vector<bool>& tied,
                            Diagnosis* d,
                            Case* current,
                            ResidualCheck* check) {
  std::vector<DiagnosisStep> kept, pruned;
  for (size_t i = 0; i < d->steps.size(); ++i) {
    (tied[i] ? pruned : kept).push_back(d->steps[i]);
  }
  if (pruned.empty()) return;
  Case without = CaseAtSolution(*current, d->FinalFit());
  for (const DiagnosisStep& s : pruned) without = WithoutStep(without, s);
  FitResult fit;
  if (!FitFrom(without, d->FinalFit(), data, "without pruned steps", &fit)) {
    return;
  }
  *check = CheckResiduals(fit, options);
  d->fits.push_back(std::move(fit));
  d->final_fit = d->fits.size() - 1;
  *current = std::move(without);
  d->partial.insert(d->partial.begin(), pruned.begin(), pruned.end());
  d->steps = std::move(kept);
  if (!d->steps.empty()) d->steps.back().after = *check;
}

// The final model *current (d->FinalFit(), the model before an open tie;
// *check its residual check), short of the noise level where the search's
// model with the tie's effect in (d->fits[d->partial_fit]) reaches it,
// with each effect it holds in the other form back in its own form where
// that model holds it so and the record no longer favors the other
// (BackToOwnFormsInModel). The search took the form back beside the tied
// effect and updated the step's parameters, but the model before the tie
// still holds the form the step was taken in: on draw 155's 3-s run with a
// bearing moment, a cubic calibration error and a roll torque, the
// calibration came first as the signed square, then the bearing moment;
// the roll torque, with the cube beside it, tied with a tunnel damping,
// and the final model, the one before it, kept the signed square while
// the complete models with either tied effect held the cube: the answer
// held the true term at zero. The refit is a new fit; the step's own fit
// keeps the form it was taken in. Unchanged when no such effect, or the
// refit fails.
void OwnFormsBeforeTie(const std::vector<TimeHistory>& data,
                       const DiagnoseOptions& options,
                       Diagnosis* d,
                       Case* current,
                       ResidualCheck* check) {
  if (check->at_noise_level || d->partial_fit >= d->fits.size()) return;
  const FitResult& complete = d->fits[d->partial_fit];
  if (!CheckResiduals(complete, options).at_noise_level) return;
  // The steps whose effect the complete model holds in its own form;
  // BackToOwnFormsInModel takes those the final model holds in the other.
  std::vector<DiagnosisStep> steps;
  for (const DiagnosisStep& s : d->steps) {
    const Effect* effect = FindEffect(s.effect);
    if (effect != nullptr && OtherForm(*effect) != nullptr &&
        !InOtherFormIn(*effect, complete)) {
      steps.push_back(s);
    }
  }
  if (steps.empty()) return;
  Case own = CaseAtSolution(*current, d->FinalFit());
  FitResult fit = d->FinalFit();
  if (!BackToOwnFormsInModel(data, &own, &fit, &steps)) return;
  for (DiagnosisStep& s : d->steps) {
    for (const DiagnosisStep& back : steps) {
      if (back.effect == s.effect) s.step_parameters = back.step_parameters;
    }
  }
  *check = CheckResiduals(fit, options);
  d->fits.push_back(std::move(fit));
  d->final_fit = d->fits.size() - 1;
  *current = std::move(own);
  if (!d->steps.empty()) d->steps.back().after = *check;
}

// Each complete model of `d`, an ambiguous answer (Diagnosis::alternatives),
// refitted without each of its steps: model m without step i in
// (*without)[m * n + i] (n steps), and what that costs in *rises (the same
// order): its BIC's rise, infinity where the refit fails or leaves the
// residuals above the noise level. False when a complete model was not
// fitted, or with fewer than two or no steps.
bool RisesWithoutEach(const std::vector<TimeHistory>& data,
                      const DiagnoseOptions& options,
                      const Diagnosis& d,
                      std::vector<FitResult>* without,
                      std::vector<double>* rises) {
  std::vector<const Case*> cases;
  std::vector<const FitResult*> fits;
  for (const AlternativeModel& a : d.alternatives) {
    if (a.fit < 0) return false;
    cases.push_back(&a.model);
    fits.push_back(&d.fits[a.fit]);
  }
  if (cases.size() < 2 || d.steps.empty()) return false;
  std::vector<char> fitted;
  FitWithoutEach(data, cases, fits, d.steps, without, &fitted);
  rises->assign(without->size(), std::numeric_limits<double>::infinity());
  for (size_t k = 0; k < without->size(); ++k) {
    if (fitted[k] && CheckResiduals((*without)[k], options).at_noise_level) {
      (*rises)[k] = Bic((*without)[k]) - Bic(*fits[k / d.steps.size()]);
    }
  }
  return true;
}

// The step of `d`, an ambiguous answer, that none of its complete models
// needs, by Prune's rule: without it each stays at the noise level and its
// BIC rises by less than min_bic_drop (RisesWithoutEach; the step whose
// greatest rise is least, that rise in *least_rise, each complete model
// without it in *without), or -1.
int RedundantInEach(const std::vector<TimeHistory>& data,
                    const DiagnoseOptions& options,
                    const Diagnosis& d,
                    std::vector<FitResult>* without,
                    double* least_rise) {
  std::vector<FitResult> each;
  std::vector<double> rises;
  if (!RisesWithoutEach(data, options, d, &each, &rises)) return -1;
  const size_t n = d.steps.size();
  const size_t models = d.alternatives.size();
  int redundant = -1;
  double least = options.min_bic_drop;
  for (size_t i = 0; i < n; ++i) {
    double rise = -std::numeric_limits<double>::infinity();
    for (size_t m = 0; m < models; ++m) rise = std::max(rise, rises[m * n + i]);
    VLOG(1) << d.steps[i].effect << " in every complete model: BIC "
            << FormatNumber("%+.1f", rise) << " at most without it";
    if (rise < least) {
      least = rise;
      redundant = static_cast<int>(i);
    }
  }
  if (redundant < 0) return -1;
  without->clear();
  for (size_t m = 0; m < models; ++m) {
    without->push_back(std::move(each[m * n + redundant]));
  }
  *least_rise = least;
  return redundant;
}

// Step i of *d taken out of the final model *current (*check its residual
// check), of the complete models (d->alternatives) marked in `out_of`,
// each refitted from its fit without it in `without` (the same order;
// Reported) and the final model from its own, all at once, and out of the
// steps into *step. With a stand-in the final model is the first complete
// one (taken out of it: out_of[0]). The step's fit_before and fit_after
// name the final model's fits with and without it. False, and *d
// unchanged, when the final model's refit fails.
bool TakeStepOut(const std::vector<TimeHistory>& data,
                 const DiagnoseOptions& options,
                 int i,
                 const std::vector<bool>& out_of,
                 std::vector<FitResult>* without,
                 Diagnosis* d,
                 Case* current,
                 ResidualCheck* check,
                 DiagnosisStep* step) {
  *step = d->steps[i];
  const bool stand_in = !d->stand_in.empty();
  CHECK(!stand_in || out_of[0]);
  const int n = static_cast<int>(d->alternatives.size());
  std::vector<Case> cases(n);
  for (int m = 0; m < n; ++m) {
    if (!out_of[m]) continue;
    const AlternativeModel& a = d->alternatives[m];
    cases[m] = WithoutStep(CaseAtSolution(a.model, d->fits[a.fit]), *step);
  }
  Case final_case =
      stand_in ? cases[0]
               : WithoutStep(CaseAtSolution(*current, d->FinalFit()), *step);
  FitResult final_fit;
  bool final_fitted = stand_in;
  ParallelFor(n + (stand_in ? 0 : 1), [&](int m) {
    if (m == n) {
      final_fitted = FitFrom(final_case,
                             d->FinalFit(),
                             data,
                             "without " + step->effect,
                             &final_fit);
    } else if (out_of[m]) {
      Reported(cases[m], data, &(*without)[m]);
    }
  });
  if (!final_fitted) return false;
  for (int m = 0; m < n; ++m) {
    if (!out_of[m]) continue;
    AlternativeModel& a = d->alternatives[m];
    a.check = CheckResiduals((*without)[m], options);
    a.parameters = (*without)[m].parameters;
    a.model = cases[m];
    d->fits.push_back(std::move((*without)[m]));
    a.fit = static_cast<int>(d->fits.size()) - 1;
  }
  step->fit_before = static_cast<int>(d->final_fit);
  if (!stand_in) {
    d->fits.push_back(std::move(final_fit));
    d->final_fit = d->fits.size() - 1;
  } else {
    d->final_fit = d->alternatives[0].fit;
  }
  step->fit_after = static_cast<int>(d->final_fit);
  *check = CheckResiduals(d->FinalFit(), options);
  *current = std::move(final_case);
  step->after = *check;
  d->steps.erase(d->steps.begin() + i);
  if (!d->steps.empty()) d->steps.back().after = *check;
  return true;
}

// The steps of an ambiguous answer that none of its complete models needs
// (RedundantInEach) taken out of *d, one at a time, as Prune takes them out
// of an explained one: out of the complete models, the final model
// *current and the steps (TakeStepOut), into d->pruned. Unchanged when a
// refit fails. On a 3-s run with a
// tunnel stiffness, a nonlinear damping and a body asymmetry (suite draw
// 39), a Magnus moment taken first ended 1.6 +- 3.4 in the final model,
// every complete model at the noise level without it and its BIC 4.8
// lower; searched without it, the stiffness ran along Eq. 43's ridge and
// the record stayed unexplained.
void PruneWithinTie(const std::vector<TimeHistory>& data,
                    const DiagnoseOptions& options,
                    Diagnosis* d,
                    Case* current,
                    ResidualCheck* check) {
  std::vector<FitResult> without;
  double rise = 0.0;
  while (true) {
    const int i = RedundantInEach(data, options, *d, &without, &rise);
    if (i < 0) return;
    const std::vector<bool> all(d->alternatives.size(), true);
    DiagnosisStep step;
    if (!TakeStepOut(
            data, options, i, all, &without, d, current, check, &step)) {
      return;
    }
    step.note =
        "needed in none of the complete models of the tie: without it each "
        "stays at the noise level and its BIC changes by " +
        FormatNumber("%.1f", rise) + " at most";
    d->pruned.push_back(std::move(step));
  }
}

// The step of `d`, an ambiguous answer without a stand-in, that goes with
// the tied effect the search followed: its complete model (the first)
// needs it, and a rival's does not (RisesWithoutEach: below min_bic_drop);
// the one with the least such rise (in *rise), each complete model without
// it in *without and those that do not need it marked in *out_of; or -1.
int CompanionOfFollowed(const std::vector<TimeHistory>& data,
                        const DiagnoseOptions& options,
                        const Diagnosis& d,
                        std::vector<FitResult>* without,
                        std::vector<bool>* out_of,
                        double* rise) {
  std::vector<FitResult> each;
  std::vector<double> rises;
  if (!d.stand_in.empty() ||
      !RisesWithoutEach(data, options, d, &each, &rises)) {
    return -1;
  }
  const size_t n = d.steps.size();
  const size_t models = d.alternatives.size();
  int companion = -1;
  *rise = options.min_bic_drop;
  for (size_t i = 0; i < n; ++i) {
    if (rises[i] < options.min_bic_drop) continue;  // the first's need
    for (size_t m = 1; m < models; ++m) {
      if (rises[m * n + i] < *rise) {
        *rise = rises[m * n + i];
        companion = static_cast<int>(i);
      }
    }
  }
  if (companion < 0) return -1;
  without->clear();
  out_of->assign(models, false);
  for (size_t m = 0; m < models; ++m) {
    without->push_back(std::move(each[m * n + companion]));
    (*out_of)[m] = rises[m * n + companion] < options.min_bic_drop;
  }
  return companion;
}

// The steps of an ambiguous answer that go with the tied effect the search
// followed (CompanionOfFollowed) taken out of *d, one at a time: out of the
// final model, the complete models that do not need them and the steps
// (TakeStepOut), into d->partial beside the tied effect
// (after it, as TieCompanions' are). The search had found them with that
// effect in the model; a rival explains the record without them, so they
// are part of one explanation, not of the answer. On draw 56's pair of
// 3-s runs with a tunnel stiffness, a nonlinear damping and a body
// asymmetry, a roll torque tied with the stiffness and a Magnus moment
// adopted after it was "needed with each": the set of effects after the
// tie was, but the Magnus moment alone raised BIC by 18.8 without it
// beside the torque and lowered it by 5.6 beside the stiffness.
void CompanionsWithinTie(const std::vector<TimeHistory>& data,
                         const DiagnoseOptions& options,
                         Diagnosis* d,
                         Case* current,
                         ResidualCheck* check) {
  std::vector<FitResult> without;
  std::vector<bool> out_of;
  double rise = 0.0;
  while (d->steps.size() >= 2 && !d->partial.empty()) {
    const int i =
        CompanionOfFollowed(data, options, *d, &without, &out_of, &rise);
    if (i < 0) return;
    DiagnosisStep step;
    if (!TakeStepOut(
            data, options, i, out_of, &without, d, current, check, &step)) {
      return;
    }
    step.note = "goes with " + d->alternatives[0].effect +
                ": needed beside it, not beside a rival (BIC " +
                FormatNumber("%+.1f", rise) + " without it)";
    VLOG(1) << step.effect << " " << step.note;
    d->partial.insert(d->partial.begin() + 1, std::move(step));
  }
}

// The case of complete model `a` (fitted as `own`) started from `best`, the
// fit of another side of the tie: its own solution with every parameter free
// in both, and the initial conditions, at best's values (CaseAtSolution of
// best with only those parameters). A side in the other program (a body
// asymmetry's side fits the asymmetric one) gives its shared terms
// through their images (ImagesIn: a symmetric Cm_q gives the asymmetric
// Cm_q and Cn_r, Cm_p_beta gives the symmetric Cm_p_alpha) and not its
// initial conditions, whose coordinates differ: read by position, its
// parameters had been written past the end of the case's table (draw 29's
// 3-s stiffness + damping + asymmetry, a heap overflow AddressSanitizer
// found; diagnose_test aborted now and then).
Case FromOtherSide(const AlternativeModel& a,
                   const FitResult& own,
                   const FitResult& best) {
  const Case at = CaseAtSolution(a.model, own);
  if (best.model != at.model) {
    Case c = at;
    for (const ParameterEstimate& e : best.parameters) {
      if (!e.free || !e.segment.empty()) continue;
      for (const ImagePosition& image : ImagesIn(c.model, best.model, e.name)) {
        ParameterSetting& p = c.parameters[image.position];
        if (!p.free || p.tied()) continue;
        p.value = image.factor * e.value;
        p.auto_start = false;
      }
    }
    c.SettleTies();
    return c;
  }
  FitResult shared = best;
  std::vector<ParameterEstimate>& terms = shared.parameters;
  terms.erase(std::remove_if(terms.begin(),
                             terms.end(),
                             [&](const ParameterEstimate& e) {
                               const ParameterSetting& p =
                                   at.parameters[e.position];
                               return !(e.free && p.free && !p.tied());
                             }),
              terms.end());
  return CaseAtSolution(at, shared);
}

// The complete models of an adopted tie (d->alternatives) each fitted again
// from the lowest one's solution where it stopped above it by more than
// ambiguity_bic, and taken when that is lower; the final model with them
// when it is a stand-in (*current, *check). Roll torque and roll damping are
// twins at constant spin, yet on a Table 6 record with a bearing moment and a
// calibration error the torque's complete model stopped 23 above the
// damping's: its bearing angle had been fitted beside a nonlinear stiffness
// later pruned (0.28 deg +- 437, truth 1.0), the damping's from its own start
// (1.05). From the damping's values the torque's reaches it (1.05 +- 0.08),
// and OutdoneTieBranch no longer searches the catalog again over the gap.
void AlignedSides(const std::vector<TimeHistory>& data,
                  const DiagnoseOptions& options,
                  Diagnosis* d,
                  Case* current,
                  ResidualCheck* check) {
  const FitResult* least = LowestCompleteFit(*d);
  if (least == nullptr) return;
  const FitResult& lowest = *least;
  const int n = static_cast<int>(d->alternatives.size());
  std::vector<Case> cases(n);
  std::vector<FitResult> fits(n);
  std::vector<char> refit(n, false);
  for (int m = 0; m < n; ++m) {
    const AlternativeModel& a = d->alternatives[m];
    refit[m] =
        a.fit >= 0 && Bic(d->fits[a.fit]) > Bic(lowest) + options.ambiguity_bic;
    if (refit[m]) cases[m] = FromOtherSide(a, d->fits[a.fit], lowest);
  }
  ParallelFor(n, [&](int m) {
    if (!refit[m]) return;
    refit[m] = FitFrom(cases[m], lowest, data, "from the other side", &fits[m]);
    if (refit[m]) Reported(cases[m], data, &fits[m]);
  });
  for (int m = 0; m < n; ++m) {
    AlternativeModel& a = d->alternatives[m];
    if (!refit[m] || !(Bic(fits[m]) < Bic(d->fits[a.fit]))) continue;
    VLOG(1) << "complete model with " << a.effect << " from the other side: "
            << "BIC "
            << FormatNumber("%+.1f", Bic(fits[m]) - Bic(d->fits[a.fit]));
    a.check = CheckResiduals(fits[m], options);
    a.parameters = fits[m].parameters;
    a.model = std::move(cases[m]);
    d->fits.push_back(std::move(fits[m]));
    a.fit = static_cast<int>(d->fits.size()) - 1;
    if (m == 0 && !d->stand_in.empty()) {
      d->final_fit = a.fit;
      *current = a.model;
      *check = a.check;
      if (!d->steps.empty()) d->steps.back().after = *check;
    }
  }
}

}  // namespace

const FitResult* LowestCompleteFit(const Diagnosis& d) {
  const FitResult* lowest = nullptr;
  for (const AlternativeModel& a : d.alternatives) {
    if (a.fit >= 0 &&
        (lowest == nullptr || Bic(d.fits[a.fit]) < Bic(*lowest))) {
      lowest = &d.fits[a.fit];
    }
  }
  return lowest;
}

ResidualCheck SettleFinalModel(
    const Case& user,
    const std::vector<TimeHistory>& data,
    const DiagnoseOptions& options,
    const std::vector<Case>& models,
    int tie,
    const std::vector<std::vector<CandidateFit>>& rivals,
    const ResidualCheck& check,
    Diagnosis* d,
    Case* current) {
  if (!Explains(check)) {
    // Nothing explains the record: the steps taken are partial and not
    // adopted (Diagnosis::partial says why), a tie on the way included.
    d->partial = std::move(d->steps);
    d->steps.clear();
    d->ambiguous.clear();
    d->separated_by.clear();
    *current = user;
    d->final_fit = 0;
    return d->initial;
  }
  std::vector<bool> tied(d->steps.size(), false);
  std::vector<bool> redundant(d->steps.size(), false);
  // Rivals within rival_bic of a step are swapped in even when none tied.
  const bool rivalled = std::any_of(
      rivals.begin(), rivals.end(), [](const auto& r) { return !r.empty(); });
  if (rivalled &&
      TieDissolves(
          data, options, rivals, &tie, &tied, &redundant, d, current)) {
    // The tied effect turned out redundant with the later ones in, or
    // no rival explains the record as well with them.
    return CheckResiduals(d->FinalFit(), options);
  }
  ResidualCheck adopted;
  if (tie >= 0 &&
      AdoptAfterTie(
          data, options, models, tie, tied, redundant, d, current, &adopted)) {
    PruneWithinTie(data, options, d, current, &adopted);
    CompanionsWithinTie(data, options, d, current, &adopted);
    AlignedSides(data, options, d, current, &adopted);
    return adopted;
  }
  if (tie >= 0) {
    // Explained, but with one of a tied pair: the final model is the one
    // before the tie, the steps from it on are reported as partial.
    d->partial.assign(d->steps.begin() + tie, d->steps.end());
    d->steps.resize(tie);
    d->final_fit = tie;
    *current = models[tie];
    ResidualCheck before = tie == 0 ? d->initial : d->steps.back().after;
    WithoutPrunedBeforeTie(data, options, tied, d, current, &before);
    OwnFormsBeforeTie(data, options, d, current, &before);
    return before;
  }
  d->final_fit = d->steps.size();
  Prune(data, options, d, current);
  return CheckResiduals(d->FinalFit(), options);
}

}  // namespace fit3dof
