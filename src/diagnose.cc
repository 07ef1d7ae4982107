// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The diagnosis loop (diagnose.h): fit, check the residuals, score every
// catalog effect not yet in the model, refit the best few, add the best
// one that earns its place (unless a second one explains the residual as
// well), repeat. The pieces: effect_catalog.cc, score_test.cc,
// effect_validation.cc, residual_check.cc, residual_description.cc,
// diagnosis_verdict.cc, diagnosis_report.cc.

#include "fit3dof/diagnose.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "diagnose_internal.h"
#include "fit3dof/angles.h"
#include "fit3dof/model_conversion.h"
#include "fit3dof/parameters.h"
#include "fit3dof/thread_budget.h"
#include "fit_memo.h"
#include "format.h"

namespace fit3dof {
namespace {

double Bic(const FitResult& r) {
  const double n = 3.0 * r.points;
  const double rss = std::max(r.sum_of_residuals * r.sum_of_residuals, 1e-300);
  return n * std::log(rss / n) + r.free_parameters * std::log(n);
}

struct Candidate {
  const Effect* effect;
  Case c;
  std::vector<std::string> added;
  CandidateScore score;
};

// A candidate refitted in full.
struct Contender {
  const Candidate* candidate = nullptr;
  FitResult fit;
  double bic = 0.0;
  CandidateFit record;
  bool dragged = false;  // refused for dragging the coefficients (Judge)
};

bool Wanted(const DiagnoseOptions& options, const Effect& e) {
  return options.effects.empty() ||
         std::find(options.effects.begin(), options.effects.end(), e.id) !=
             options.effects.end();
}

std::vector<TimeHistory> FittedData(const FitResult& fit) {
  std::vector<TimeHistory> data;
  for (const SegmentFit& segment : fit.segments) data.push_back(segment.data);
  return data;
}

Case FromSolution(const Case& c, const FitResult& fit) {
  Case at = CaseAtSolution(c, fit);
  RefitFromSolution(&at, fit.probable_error);
  return at;
}

// The current model refitted from its solution as every contender is
// (RefitFromSolution: continuation when far from the noise). A contender's
// BIC drop must come from its effect, not from the refit settling the
// model it extends further down (a roll torque of 5e-9 +- 1e-9 lowering
// BIC by 420 once did). Replaces *fit and returns true when the refit
// lowers BIC by more than 1 (less changes no decision).
bool Polish(const Case& current,
            const std::vector<TimeHistory>& data,
            FitResult* fit) {
  try {
    const FitResult polished =
        MemoizedFitSamples(FromSolution(current, *fit), data);
    if (!(Bic(polished) < Bic(*fit) - 1.0)) return false;
    *fit = polished;
    return true;
  } catch (const std::exception& e) {
    LOG(WARNING) << fit->name
                 << ": refit of the model as it stands failed: " << e.what();
    return false;
  }
}

// Each of *candidates scored against `data` (score_test.cc; in parallel,
// within the process's thread budget, thread_budget.h), largest score
// first.
void RankByScore(const std::vector<TimeHistory>& data,
                 std::vector<Candidate>* candidates) {
  ParallelFor(static_cast<int>(candidates->size()), [&](int i) {
    Candidate& k = (*candidates)[i];
    k.score = Score(k.c, k.added, k.effect->id, data);
  });
  std::sort(candidates->begin(),
            candidates->end(),
            [](const Candidate& a, const Candidate& b) {
              return a.score.score > b.score.score;
            });
}

// Every applicable effect scored at the fit's solution, best first.
std::vector<Candidate> ScoredCandidates(const Case& current,
                                        const FitResult& fit,
                                        const DiagnoseOptions& options) {
  const Case at = CaseAtSolution(current, fit);
  const std::vector<TimeHistory> data = FittedData(fit);
  std::vector<Candidate> all;
  for (const Effect& e : EffectCatalog()) {
    if (!Wanted(options, e)) continue;
    Candidate k{&e, Case(), {}, {}};
    if (CandidateCase(at, e, &k.c, &k.added)) all.push_back(std::move(k));
  }
  RankByScore(data, &all);
  std::vector<Candidate> candidates;
  for (Candidate& k : all) {
    if (k.score.dof > 0) candidates.push_back(std::move(k));
  }
  return candidates;
}

// The estimates of `names` in `fit`.
std::vector<ParameterEstimate> Own(const FitResult& fit,
                                   const std::vector<std::string>& names) {
  std::vector<ParameterEstimate> own;
  for (const ParameterEstimate& e : fit.parameters) {
    if (e.segment.empty() &&
        std::find(names.begin(), names.end(), e.name) != names.end()) {
      own.push_back(e);
    }
  }
  return own;
}

// A fit diagnose reports (the final model's, an alternative's), of the
// search's case `model`, with the profiles the search skipped.
void Reported(const Case& model,
              const std::vector<TimeHistory>& data,
              FitResult* fit) {
  Case c = model;
  c.solver.profile_ridges = true;
  CheckRidges(c, data, fit);
}

// The case `c` fitted from `from`, its solution, into *fit; false (and a
// warning naming the refit, `what`) when the fit fails.
bool FitFrom(const Case& c,
             const FitResult& from,
             const std::vector<TimeHistory>& data,
             const std::string& what,
             FitResult* fit) {
  try {
    Case start = c;
    RefitFromSolution(&start, from.probable_error);
    *fit = MemoizedFitSamples(start, data);
    return true;
  } catch (const std::exception& e) {
    LOG(WARNING) << from.name << ": refit " << what << " failed: " << e.what();
    return false;
  }
}

// Candidate k refitted in full from the solution `fit` into *c; false
// when the fit fails.
bool Refit(const Candidate& k,
           const FitResult& fit,
           const std::vector<TimeHistory>& data,
           Contender* c) {
  c->candidate = &k;
  if (!FitFrom(k.c, fit, data, "with " + k.effect->id, &c->fit)) return false;
  c->bic = Bic(c->fit);
  c->record.effect = k.effect->id;
  c->record.parameters = Own(c->fit, k.added);
  c->record.bic_drop = Bic(fit) - c->bic;
  c->record.prediction_gain = std::numeric_limits<double>::quiet_NaN();
  return true;
}

// The probes (Probes) fitted from the solution `fit` of `current`: the
// one with the lowest BIC into *probe, its case into *candidates (which
// *probe points into); false when none could be fitted (the case has their
// parameters free already, or the fits fail).
bool FitProbes(const Case& current,
               const FitResult& fit,
               const std::vector<TimeHistory>& data,
               std::vector<Candidate>* candidates,
               Contender* probe) {
  const Case at = CaseAtSolution(current, fit);
  candidates->clear();
  for (const Effect& e : Probes()) {
    Candidate k{&e, Case(), {}, {}};
    if (CandidateCase(at, e, &k.c, &k.added)) {
      candidates->push_back(std::move(k));
    }
  }
  // Refitted: the two with the largest score statistics (a refit on the
  // 800-sample record costs as much as the scores of all five; the probes
  // are near-linear in their parameters, where the score ranks as the
  // refits do).
  RankByScore(data, candidates);
  constexpr size_t kProbesRefitted = 2;
  if (candidates->size() > kProbesRefitted) {
    candidates->resize(kProbesRefitted);
  }
  const int n = static_cast<int>(candidates->size());
  std::vector<Contender> fits(n);
  std::vector<char> fitted(n, false);  // not vector<bool>: written in parallel
  ParallelFor(n, [&](int i) {
    fitted[i] = Refit((*candidates)[i], fit, data, &fits[i]);
  });
  int best = -1;
  for (int i = 0; i < n; ++i) {
    if (fitted[i]) {
      VLOG(1) << fit.name << ": probe " << fits[i].record.effect
              << ", BIC drop " << fits[i].record.bic_drop;
    }
    if (fitted[i] && (best < 0 || fits[i].bic < fits[best].bic)) best = i;
  }
  if (best < 0) return false;
  *probe = std::move(fits[best]);
  return true;
}

// Every contender not rejected otherwise is rejected for the probe, which
// explains the residual better.
void OutdoneByProbe(const Contender& probe,
                    std::vector<Contender>* contenders) {
  for (Contender& k : *contenders) {
    if (!k.record.rejected.empty()) continue;
    k.record.rejected = probe.candidate->effect->description +
                        " explains the residual better (BIC lower by " +
                        FormatNumber("%.1f", k.bic - probe.bic) + ")";
  }
}

// The best `options.refit` candidates refitted on the first fit's samples:
// those that lower BIC by more than min_bic_drop, lowest BIC first.
std::vector<Contender> Contenders(const std::vector<Candidate>& candidates,
                                  const FitResult& fit,
                                  const std::vector<TimeHistory>& data,
                                  const DiagnoseOptions& options) {
  const int n = std::min<int>(options.refit, candidates.size());
  std::vector<Contender> refits(n);
  std::vector<char> fitted(n, false);  // not vector<bool>: written in parallel
  ParallelFor(n, [&](int i) {
    fitted[i] = Refit(candidates[i], fit, data, &refits[i]);
  });
  std::vector<Contender> contenders;
  for (int i = 0; i < n; ++i) {
    if (!fitted[i]) continue;
    Contender& c = refits[i];
    VLOG(1) << fit.name << ": " << c.record.effect << " score "
            << c.candidate->score.score << ", BIC drop " << c.record.bic_drop;
    if (c.record.bic_drop >= options.min_bic_drop) {
      contenders.push_back(std::move(c));
    }
  }
  std::sort(
      contenders.begin(),
      contenders.end(),
      [](const Contender& a, const Contender& b) { return a.bic < b.bic; });
  return contenders;
}

// The out-of-sample check of one round: the current model fitted to the
// first part of each segment once, each contender against it.
class OutOfSample {
 public:
  OutOfSample(const Case& current,
              const FitResult& fit,
              const DiagnoseOptions& options)
      : current_(FromSolution(current, fit)),
        data_(FittedData(fit)),
        held_out_(HoldOut(data_, options.held_out_blocks)) {
    for (const SegmentFit& s : fit.segments) weights_.push_back(s.sigma_deg);
    for (const std::vector<bool>& held : held_out_.held) {
      held_samples_ += 3 * std::count(held.begin(), held.end(), true);
    }
  }

  // n_test ln(RSS_without / RSS_with) over the held-out samples; -infinity
  // when the contender cannot be fitted or integrated there.
  double Gain(const Case& with) {
    if (held_samples_ == 0) return 0.0;
    if (rss_without_ < 0.0) rss_without_ = Rss(current_);
    return held_samples_ * std::log(rss_without_ / Rss(with));
  }

 private:
  double Rss(const Case& c) const {
    try {
      const FitResult trained = MemoizedFitSamples(c, held_out_.train);
      return PredictionRss(c, trained, data_, held_out_, weights_);
    } catch (const std::exception&) {
      return std::numeric_limits<double>::infinity();
    }
  }

  const Case current_;
  const std::vector<TimeHistory> data_;
  const HeldOut held_out_;
  std::vector<ChannelValues> weights_;
  int held_samples_ = 0;
  double rss_without_ = -1.0;
};

// Whether the contender earns its place (diagnose.h): fills
// record.rejected with why not. `added`: the effects already added.
void Judge(const FitResult& current,
           const std::vector<const Effect*>& added,
           const DiagnoseOptions& options,
           OutOfSample* out_of_sample,
           Contender* c) {
  const Candidate& k = *c->candidate;
  std::string why = Implausible(*k.effect, k.c, c->fit);
  // The newcomer may push an earlier effect out of its bounds (a
  // roll-synchronous reading error of 0.15 deg to 0.23 once a trim moment
  // came in beside it): the pair is then no more plausible than that one.
  if (why.empty()) why = ImplausibleAmong(added, k.c, c->fit);
  // A coefficient may move far only when the new model explains the record
  // down to the noise: a missing effect's bias hides in the fit (the part
  // it absorbs leaves no residual), so no error bar of the fit without it
  // covers the move (diagnose.h).
  if (why.empty() && !CheckResiduals(c->fit, options).at_noise_level) {
    why = Drags(current, c->fit, k.added, options.max_drag);
    c->dragged = !why.empty();
  }
  if (why.empty()) {
    const double gain = out_of_sample->Gain(FromSolution(k.c, c->fit));
    c->record.prediction_gain = gain;
    const double needed = options.gain_per_parameter * k.added.size();
    if (!(gain > needed)) {
      why =
          "it does not predict the held-out part of the record better "
          "(log-likelihood gain " +
          FormatNumber("%.3g", gain) + ", needs " +
          FormatNumber("%.3g", needed) + ")";
    }
  }
  c->record.rejected = why;
}

// The contenders judged in BIC order until the best that earns its place
// and every other within ambiguity_bic of it are known; returns the
// indices of those that earned it.
std::vector<int> Earned(const FitResult& current,
                        const std::vector<const Effect*>& added,
                        const DiagnoseOptions& options,
                        OutOfSample* out_of_sample,
                        std::vector<Contender>* contenders) {
  std::vector<int> earned;
  for (size_t i = 0; i < contenders->size(); ++i) {
    Contender& c = (*contenders)[i];
    if (!earned.empty() &&
        c.bic - (*contenders)[earned[0]].bic >= options.ambiguity_bic) {
      break;
    }
    Judge(current, added, options, out_of_sample, &c);
    VLOG(1) << current.name << ": " << c.record.effect << " (BIC drop "
            << c.record.bic_drop << ") "
            << (c.record.rejected.empty() ? "earns its place"
                                          : "refused: " + c.record.rejected);
    if (c.record.rejected.empty()) earned.push_back(static_cast<int>(i));
  }
  return earned;
}

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

// The contenders a joint set is drawn from: the one refused for its drag
// and up to three after it.
constexpr int kJointPool = 4;

// `at` with the effects of `members` (indices into `contenders`) added in
// turn into *model (its `added`: the last member's terms); *terms gets the
// number of terms they add. False when one cannot be added.
bool WithEffects(const Case& at,
                 const std::vector<Contender>& contenders,
                 const std::vector<int>& members,
                 Candidate* model,
                 int* terms) {
  Case c = at;
  std::vector<std::string> added;
  *terms = 0;
  for (int m : members) {
    Case next;
    if (!CandidateCase(c, *contenders[m].candidate->effect, &next, &added)) {
      return false;
    }
    c = std::move(next);
    *terms += static_cast<int>(added.size());
  }
  *model = Candidate{contenders[members.back()].candidate->effect,
                     std::move(c),
                     std::move(added),
                     contenders[members.back()].candidate->score};
  return true;
}

// Whether the set `members` fitted as `fit` (model `c`) earns its place
// together: residuals at the noise level, every effect in the model within
// its bounds, and the held-out part predicted better (gain per parameter
// as for one effect) into *gain.
bool EarnedTogether(const Case& c,
                    const FitResult& fit,
                    const std::vector<int>& members,
                    const std::vector<Contender>& contenders,
                    std::vector<const Effect*> effects,
                    int terms,
                    const DiagnoseOptions& options,
                    OutOfSample* out_of_sample,
                    double* gain) {
  if (!CheckResiduals(fit, options).at_noise_level) return false;
  for (int m : members) effects.push_back(contenders[m].candidate->effect);
  if (!ImplausibleAmong(effects, c, fit).empty()) return false;
  *gain = out_of_sample->Gain(FromSolution(c, fit));
  return *gain > options.gain_per_parameter * terms;
}

// When a contender was refused only for dragging the coefficients, and
// none better (lower BIC) earned its place, the effects missing beside it
// may be what makes the drag: each alone explains part of the record and moves
// the coefficients that the others biased (on the 48-s Table 6 record with a
// tunnel stiffness, a nonlinear damping and a body yaw asymmetry, the
// stiffness alone moved Cm_alpha by 3700 of its errors while lowering
// the probable error 1.4-fold, and asymmetric_body, whose Cn_r then took
// up the missing damping, was out of its bounds). The drag rule lets a
// model that explains the record to the noise move them; so does it a
// set: the refused contender with one or two of the next three, fitted
// together, earns its place together (EarnedTogether). The best contender
// may be refused otherwise and the dragged one come second: on a 3-s run
// with a tunnel damping, a Magnus moment and a flow angularity, a body yaw
// asymmetry (predicting nothing held out) came before the dragged
// damping, the Magnus moment was taken alone, and nothing after it
// earned its place. `earned` (Earned) tells which contenders were judged
// better than every one that earned its place. The lowest-BIC set that
// earns its place goes into *joint; false when none.
bool Jointly(const Case& current,
             const FitResult& fit,
             const std::vector<TimeHistory>& data,
             const DiagnoseOptions& options,
             const std::vector<const Effect*>& added,
             OutOfSample* out_of_sample,
             const std::vector<Contender>& contenders,
             const std::vector<int>& earned,
             JointSet* joint) {
  if (!options.joint_sets) return false;
  const int judged =
      earned.empty() ? static_cast<int>(contenders.size()) : earned[0];
  int lead = 0;
  while (lead < judged && !contenders[lead].dragged) ++lead;
  if (lead >= judged) return false;
  const int pool = std::min<int>(lead + kJointPool, contenders.size());
  std::vector<std::vector<int>> sets;
  for (int a = lead + 1; a < pool; ++a) {
    sets.push_back({lead, a});
    for (int b = a + 1; b < pool; ++b) sets.push_back({lead, a, b});
  }
  const Case at = CaseAtSolution(current, fit);
  const int n = static_cast<int>(sets.size());
  std::vector<Candidate> models(n);
  std::vector<int> terms(n, 0);
  std::vector<FitResult> fits(n);
  std::vector<char> fitted(n, false);  // not vector<bool>: written in parallel
  ParallelFor(n, [&](int i) {
    fitted[i] = WithEffects(at, contenders, sets[i], &models[i], &terms[i]) &&
                FitFrom(models[i].c, fit, data, "with a joint set", &fits[i]);
  });
  std::vector<int> order;
  for (int i = 0; i < n; ++i) {
    if (fitted[i]) order.push_back(i);
  }
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return Bic(fits[a]) < Bic(fits[b]);
  });
  for (int i : order) {
    double gain = 0.0;
    if (!EarnedTogether(models[i].c,
                        fits[i],
                        sets[i],
                        contenders,
                        added,
                        terms[i],
                        options,
                        out_of_sample,
                        &gain)) {
      continue;
    }
    VLOG(1) << fit.name << ": joint set of " << sets[i].size()
            << " earns its place, BIC " << Bic(fits[i]) << ", gain " << gain;
    // The prefixes: the first member's contender, the pair before a triple.
    int pair = -1;
    if (sets[i].size() == 3) {
      const std::vector<int> prefix = {lead, sets[i][1]};
      pair = static_cast<int>(std::find(sets.begin(), sets.end(), prefix) -
                              sets.begin());
      if (!fitted[pair]) continue;
    }
    joint->members = sets[i];
    joint->prediction_gain = gain;
    joint->models = {*contenders[lead].candidate};
    joint->fits = {contenders[lead].fit};
    if (pair >= 0) {
      joint->models.push_back(models[pair]);
      joint->fits.push_back(fits[pair]);
    }
    joint->models.push_back(models[i]);
    joint->fits.push_back(fits[i]);
    return true;
  }
  return false;
}

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

// The step that adds contender c.
DiagnosisStep Step(const Contender& c, const std::vector<Contender>& all) {
  DiagnosisStep step;
  const Candidate& k = *c.candidate;
  step.effect = k.effect->id;
  step.description = k.effect->description;
  step.score = k.score.score;
  step.step_parameters = c.record.parameters;
  step.bic_drop = c.record.bic_drop;
  step.prediction_gain = c.record.prediction_gain;
  for (const Contender& other : all) step.contenders.push_back(other.record);
  return step;
}

// Each free estimate of `final_fit` widened to cover `models`, each with
// its weight against the final model (`weights`, or 1 for each when
// empty), with a line in its pipeline naming them (`by`) when one grew;
// each widened estimate's error before any widening goes into
// *model_errors (a second widening keeps the first's).
// For a model m of weight w the error about the final value is
//
//   sqrt((1 - w) error^2 + w (max(error, error_m)^2 + (value_m - value)^2)),
//
// Burnham and Anderson's unconditional variance of two models; the
// largest over the models is taken. A tie's models weigh as much as the
// final one (w = 1, WidenForTie).
void WidenErrorBars(
    const std::vector<const std::vector<ParameterEstimate>*>& models,
    const std::vector<double>& weights,
    const std::string& by,
    FitResult* final_fit,
    std::map<std::string, double>* model_errors) {
  std::string widest;
  double widest_ratio = 1.0;
  for (ParameterEstimate& e : final_fit->parameters) {
    if (!e.free || !e.segment.empty() || !(e.standard_error > 0.0)) continue;
    const double error = e.standard_error;
    double widened = error;
    for (size_t i = 0; i < models.size(); ++i) {
      const ParameterEstimate* other = SharedEstimate(*models[i], e.name);
      if (other == nullptr || !other->free) continue;
      const double w = weights.empty() ? 1.0 : weights[i];
      const double own = std::isnan(other->standard_error)
                             ? error
                             : std::max(error, other->standard_error);
      const double shift = other->value - e.value;
      widened = std::max(widened,
                         std::sqrt((1.0 - w) * error * error +
                                   w * (own * own + shift * shift)));
    }
    if (widened / error > widest_ratio) {
      widest_ratio = widened / error;
      widest = e.name;
    }
    if (widened > error) model_errors->emplace(e.name, error);
    e.rms_error *= widened / error;
    e.standard_error = widened;
  }
  if (!widest.empty()) {
    final_fit->pipeline.push_back("error bars widened by " + by +
                                  " (the largest shift: " + widest + ", x" +
                                  FormatNumber("%.3g", widest_ratio) + ")");
  }
}

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
void WidenForTie(Diagnosis* d) {
  if (d->ambiguous.empty()) return;
  std::vector<const std::vector<ParameterEstimate>*> models;
  auto add_fit = [&](size_t k) {
    if (k != d->final_fit) models.push_back(&d->fits[k].parameters);
  };
  for (const AlternativeModel& a : d->alternatives) {
    if (a.fit >= 0) add_fit(a.fit);
  }
  if (!d->partial.empty()) add_fit(d->partial_fit);
  for (const auto& m : d->tie_models) models.push_back(&m);
  WidenErrorBars(models,
                 {},
                 "the tie's complete models",
                 &d->fits[d->final_fit],
                 &d->model_standard_errors);
}

// A complete model of the diagnosis, its fit and its effects.
struct CompleteModel {
  Case c;
  const FitResult* fit;
  std::vector<const Effect*> effects;
};

// The final model and, when steps stayed partial, the last model of the
// search (which holds them).
std::vector<CompleteModel> CompleteModels(const Diagnosis& d,
                                          const std::vector<Case>& models,
                                          const Case& current) {
  std::vector<CompleteModel> complete = {{current, &d.FinalFit(), {}}};
  for (const DiagnosisStep& s : d.steps) {
    complete[0].effects.push_back(FindEffect(s.effect));
  }
  if (!d.partial.empty() && d.partial_fit != d.final_fit) {
    complete.push_back({models[d.partial_fit], &d.fits[d.partial_fit], {}});
    for (const auto* steps : {&d.steps, &d.partial}) {
      for (const DiagnosisStep& s : *steps) {
        complete.back().effects.push_back(FindEffect(s.effect));
      }
    }
  }
  return complete;
}

// Whether effect `id` is in a tie the diagnosis leaves open.
bool InTie(const Diagnosis& d, const std::string& id) {
  auto in = [&](const std::vector<CandidateFit>& tie) {
    return std::any_of(tie.begin(), tie.end(), [&](const CandidateFit& k) {
      return k.effect == id;
    });
  };
  return in(d.ambiguous) ||
         std::any_of(d.later_ties.begin(), d.later_ties.end(), in);
}

// `fit` with the parameters `names` moved toward zero by `k` of their
// standard errors (not past zero).
FitResult Shrunk(FitResult fit,
                 const std::vector<std::string>& names,
                 double k) {
  for (ParameterEstimate& e : fit.parameters) {
    if (!e.segment.empty() || !(e.standard_error > 0.0) ||
        std::find(names.begin(), names.end(), e.name) == names.end()) {
      continue;
    }
    const double shrink = std::min(std::abs(e.value), k * e.standard_error);
    e.value -= std::copysign(shrink, e.value);
  }
  return fit;
}

// Why `effect` (its parameters `added`), fitted beside the effects
// `model` into `fit`, lies outside the bounds (empty if it does not):
// the model's effects as fitted, `effect` within two of its standard
// errors. Along a ridge the point fit lands anywhere the record allows: a
// tunnel stiffness beside a body asymmetry on one coning run lowered BIC
// by 6.7 with t1 = 0.138 +- 0.051, past its bound (0.115) by half an
// error, and Cm_alpha at -0.368 +- 0.051 (truth -0.23), where the final
// model said -0.2299 +- 2e-5.
std::string ImplausibleBeside(const std::vector<const Effect*>& model,
                              const Effect& effect,
                              const std::vector<std::string>& added,
                              const Case& c,
                              const FitResult& fit) {
  const std::string why = ImplausibleAmong(model, c, fit);
  if (!why.empty()) return why;
  return Implausible(effect, c, Shrunk(fit, added, 2.0));
}

// The contenders of the search's rounds (`contended`: each lowered BIC by
// more than min_bic_drop where it was tried) that the record cannot
// exclude beside a complete model (tied effects aside: WidenForTie covers
// them): added to it (not swapped in, as the final swap tries them), its
// BIC rises by less than ambiguity_bic and the effects stay within their
// bounds (ImplausibleBeside: its own within two of its errors). Their fits
// go into d->not_excluded (bic_drop against the model without) and their
// parameters into d->not_excluded_models.
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
void FindNotExcluded(const std::vector<const Effect*>& contended,
                     const std::vector<Case>& models,
                     const Case& current,
                     const std::vector<TimeHistory>& data,
                     const DiagnoseOptions& options,
                     Diagnosis* d) {
  // A record left not explained keeps the nominal fit as its final model,
  // and what might have absorbed part of its unknown structure says
  // nothing about that fit's errors (Conclude's rule).
  if (d->ambiguous.empty() && !d->final.at_noise_level) return;
  const std::vector<CompleteModel> complete =
      CompleteModels(*d, models, current);
  // A tied effect's models are the tie's (WidenForTie).
  std::vector<const Effect*> effects;
  for (const Effect* e : contended) {
    if (!InTie(*d, e->id)) effects.push_back(e);
  }
  struct Beside {
    const CompleteModel* model;
    const Effect* effect;
    Case c;
    std::vector<std::string> added;
    FitResult fit;
  };
  std::vector<Beside> trials;
  for (const CompleteModel& m : complete) {
    for (const Effect* e : effects) {
      if (std::find(m.effects.begin(), m.effects.end(), e) == m.effects.end()) {
        trials.push_back({&m, e, Case(), {}, FitResult()});
      }
    }
  }
  std::vector<char> fitted(trials.size(), false);  // written in parallel
  ParallelFor(static_cast<int>(trials.size()), [&](int i) {
    Beside& t = trials[i];
    fitted[i] = CandidateCase(CaseAtSolution(t.model->c, *t.model->fit),
                              *t.effect,
                              &t.c,
                              &t.added) &&
                FitFrom(t.c,
                        *t.model->fit,
                        data,
                        "with " + t.effect->id + " beside",
                        &t.fit);
  });
  for (size_t i = 0; i < trials.size(); ++i) {
    const Beside& t = trials[i];
    if (!fitted[i]) continue;
    const double rise = Bic(t.fit) - Bic(*t.model->fit);
    const std::string implausible =
        ImplausibleBeside(t.model->effects, *t.effect, t.added, t.c, t.fit);
    VLOG(1) << t.effect->id << " beside the complete model: BIC "
            << (rise >= 0.0 ? "+" : "") << rise << " " << implausible;
    if (!(rise < options.ambiguity_bic) || !implausible.empty()) continue;
    d->not_excluded_models.push_back(t.fit.parameters);
    // Its BIC weight against the model without it.
    d->not_excluded_weights.push_back(1.0 / (1.0 + std::exp(0.5 * rise)));
    // Each effect once: beside the final model when it is not excluded
    // there.
    if (std::any_of(
            d->not_excluded.begin(),
            d->not_excluded.end(),
            [&](const CandidateFit& k) { return k.effect == t.effect->id; })) {
      continue;
    }
    CandidateFit k;
    k.effect = t.effect->id;
    k.parameters = Own(t.fit, t.added);
    k.bic_drop = -rise;
    k.prediction_gain = std::numeric_limits<double>::quiet_NaN();
    k.rejected = "not needed beside the " +
                 std::string(t.model == &complete[0] ? "final" : "search's") +
                 " model, nor excluded (BIC " + FormatNumber("%+.1f", rise) +
                 ")";
    d->not_excluded.push_back(std::move(k));
  }
}

// The final error bars cover the models of the effects the record cannot
// exclude (FindNotExcluded), each with its BIC weight against the model
// it was added to, exp(-rise / 2) / (1 + exp(-rise / 2)): neither the
// search nor the final swap added or swapped them in, but the values the
// record allows with them are part of its answer. Weighted, not the
// tie's worst case: along Eq. 43 a tunnel damping leaves only Cm_q + t2
// determined, and one that raised BIC by 9.3 beside a roll damping (two
// runs) widened Cm_q 138-fold in the worst case, 13-fold weighted.
void WidenForNotExcluded(Diagnosis* d) {
  std::vector<const std::vector<ParameterEstimate>*> models;
  for (const auto& m : d->not_excluded_models) models.push_back(&m);
  std::string which;  // not_excluded holds each effect once
  for (const CandidateFit& k : d->not_excluded) {
    which += (which.empty() ? "" : ", ") + k.effect;
  }
  WidenErrorBars(models,
                 d->not_excluded_weights,
                 "effects the record cannot exclude beside it (" + which + ")",
                 &d->fits[d->final_fit],
                 &d->model_standard_errors);
}

// final.yaml reruns the fit: the solution with the user's solver settings
// and initial-condition modes.
Case FinalCase(const Case& user, const Case& current, const FitResult& fit) {
  Case final_case = CaseAtSolution(current, fit);
  final_case.solver = user.solver;
  for (size_t s = 0; s < final_case.segments.size() && s < user.segments.size();
       ++s) {
    final_case.segments[s].initial_conditions =
        user.segments[s].initial_conditions;
  }
  return final_case;
}

// Each step's parameters as the final model has them (a partial step's as
// the last partial model has them). A later step may have switched the
// model to the asymmetric program, where the effect's terms have other
// names (a Magnus moment's Cm_p_alpha is Cm_p_beta and Cn_p_alpha there):
// the effect's own list for that program finds them.
void FinalValues(Diagnosis* d) {
  d->final_parameters = d->FinalFit().parameters;
  for (std::vector<DiagnosisStep>* steps :
       {&d->steps, &d->partial, &d->pruned, &d->stood_in}) {
    const FitResult& fit =
        steps == &d->partial ? d->fits[d->partial_fit] : d->FinalFit();
    for (DiagnosisStep& step : *steps) {
      std::vector<std::string> names;
      for (const ParameterEstimate& e : step.step_parameters) {
        names.push_back(e.name);
      }
      const Effect* effect = FindEffect(step.effect);
      if (effect != nullptr) {
        const std::vector<std::string>& own = fit.model == ModelKind::kSymmetric
                                                  ? effect->symmetric
                                                  : effect->asymmetric;
        names.insert(names.end(), own.begin(), own.end());
      }
      step.parameters = Own(fit, names);
    }
  }
}

// The largest roll angle any segment sweeps (deg).
double RollSpan(const std::vector<TimeHistory>& data) {
  double span = 0.0;
  for (const TimeHistory& h : data) {
    if (h.size() == 0) continue;
    const auto [lo, hi] = std::minmax_element(h.phi.begin(), h.phi.end());
    span = std::max(span, *hi - *lo);
  }
  return span;
}

// Whether a roll-locked signature can be told from a drift in time: a
// segment sweeps a revolution of roll, or two segments roll at rates that
// differ by more than a fifth (the same roll angle at different times).
bool RollSeparates(const std::vector<TimeHistory>& data) {
  if (RollSpan(data) >= 360.0) return true;
  std::vector<double> rates;
  for (const TimeHistory& h : data) {
    if (h.size() < 2 || h.t.back() <= h.t.front()) continue;
    rates.push_back(std::abs(h.phi.back() - h.phi.front()) /
                    (h.t.back() - h.t.front()));
  }
  if (rates.size() < 2) return false;
  const auto [lo, hi] = std::minmax_element(rates.begin(), rates.end());
  return *hi > 1.2 * *lo;
}

// The lowest BIC of `contenders`, refused or not (+inf when none).
double BestBic(const std::vector<Contender>& contenders) {
  double best = std::numeric_limits<double>::infinity();
  for (const Contender& k : contenders) best = std::min(best, k.bic);
  return best;
}

// How much lower the probe's BIC must be than that of `best`, the best
// catalog effect that earned its place, for the record to be not
// explained: ambiguity_bic; but a roll-locked effect on records that
// sweep less than a revolution of roll is already a drift in time there
// (DriftInTime), and when a fitted drift (of the readings or of the
// dynamic pressure) does better it has nothing left to show for itself.
// A flow stiffer in one plane is no drift: it needs the margin.
double ProbeMargin(const Contender& best,
                   const Contender& probe,
                   const std::vector<TimeHistory>& data,
                   const DiagnoseOptions& options) {
  return probe.candidate->effect->drifts_in_time &&
                 best.candidate->effect->roll_locked && !RollSeparates(data)
             ? 0.0
             : options.ambiguity_bic;
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

// Whatever explains a round's residual as well as contenders[best]
// (diagnose.h): the other contenders within ambiguity_bic of its BIC, the
// probe (when fitted) within it, and for a roll-locked effect on less than
// a revolution of roll a drift in time. Contenders refused at this round
// count too: with the effects still missing in, a roll reading error
// refused beside an unexplained nonlinear damping may explain the record
// as well as the trim moment adopted (the final swap decides, Unresolved).
std::vector<CandidateFit> Rivals(const std::vector<Contender>& contenders,
                                 int best,
                                 const Contender* probe,
                                 const std::vector<TimeHistory>& data,
                                 const DiagnoseOptions& options) {
  const double within = contenders[best].bic + options.ambiguity_bic;
  std::vector<CandidateFit> rivals = Near(contenders, best, within);
  if (probe != nullptr && probe->bic < within) rivals.push_back(probe->record);
  if (contenders[best].candidate->effect->roll_locked && !RollSeparates(data)) {
    rivals.push_back(DriftInTime());
  }
  return rivals;
}

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

// The case `at` without the effect that `step` added: the terms it added
// fixed at zero (a companion keeps its value, inert without them); an
// image it had untied (an asymmetric body) tied again.
Case WithoutStep(const Case& at, const DiagnosisStep& step) {
  Case without = at;
  const Effect* effect = FindEffect(step.effect);
  CHECK(effect != nullptr) << step.effect;
  for (const ParameterEstimate& e : step.step_parameters) {
    const int position = AddedTermPosition(without.model, e.name);
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
    if (!IsCompanion(*effect, e.name)) p.value = 0.0;
  }
  without.SettleTies();
  return without;
}

// Each model (`cases`, fitted as `fits`) refitted from its solution
// without each of `steps` in turn, all in parallel: (*without)[k], for
// k = m * steps.size() + i, is model m without steps[i], and (*fitted)[k]
// whether that fit ran.
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

// Backward elimination (diagnose.h): while the record is explained by two
// or more effects, the one whose removal costs least is dropped if the
// residuals stay at the noise level and BIC rises by less than
// min_bic_drop. `current` is the final model (d->FinalFit()'s case).
void Prune(const std::vector<TimeHistory>& data,
           const DiagnoseOptions& options,
           Diagnosis* d,
           Case* current) {
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
      if (!fitted[i] || !CheckResiduals(without[i], options).at_noise_level) {
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

}  // namespace

const char* VerdictToString(Verdict verdict) {
  switch (verdict) {
    case Verdict::kNoiseLevel:
      return "noise_level";
    case Verdict::kExplained:
      return "explained";
    case Verdict::kAmbiguous:
      return "ambiguous";
    case Verdict::kNotExplained:
      return "not_explained";
  }
  return "";
}

namespace {

// The case `at` with the tied rival `id` free (CandidateCase): a catalog
// effect, a probe, or for drift_in_time the drift of the readings (what a
// roll-locked reading error is over part of a revolution); false when it
// does not apply.
bool RivalCase(const Case& at, const std::string& id, Case* out) {
  const Effect* e = FindEffect(id);
  if (e == nullptr) e = FindProbe(id == kDriftInTime ? "reading_drift" : id);
  std::vector<std::string> added;
  return e != nullptr && CandidateCase(at, *e, out, &added);
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

// The rivals of `step` (recorded when the search added it) that still
// explain the record as well in the explained model `fit` (of case `at`,
// whose effects are `steps`): swapped in for it, BIC within ambiguity_bic
// of the model's and their values within their bounds. A drift in time
// (not fitted) always does, and so does a roll-locked rival of a
// roll-locked effect unless a segment spins fast enough to separate them
// (on two runs at 30 and 60 deg/s a trim moment had won the swap from the
// roll reading error that was there); a rival in the model is none. The
// fits of the rivals that were fitted and kept the tie open go into
// *as_good_fits.
std::vector<CandidateFit> Unresolved(const std::vector<CandidateFit>& rivals,
                                     const DiagnosisStep& step,
                                     const std::vector<DiagnosisStep>& steps,
                                     const Case& at,
                                     const FitResult& fit,
                                     const std::vector<TimeHistory>& data,
                                     const DiagnoseOptions& options,
                                     std::vector<FitResult>* as_good_fits) {
  const Case without = WithoutStep(at, step);
  const Effect* own = FindEffect(step.effect);
  const bool twins_separate = SpinSeparatesRollLocked(at, fit, data);
  std::vector<CandidateFit> open;
  for (const CandidateFit& rival : rivals) {
    if (std::any_of(steps.begin(), steps.end(), [&](const DiagnosisStep& s) {
          return s.effect == rival.effect;
        })) {
      continue;
    }
    Case swapped;
    FitResult swapped_fit;
    bool fitted = false;
    const Effect* effect = FindEffect(rival.effect);
    // Twins are rivals unfitted only when they tied at the step; one
    // that lost there by more (WiderRivals) must win the swap.
    const bool tied_at_step =
        step.bic_drop - rival.bic_drop < options.ambiguity_bic;
    const bool twins = own != nullptr && own->roll_locked &&
                       effect != nullptr && effect->roll_locked &&
                       !twins_separate && tied_at_step;
    const bool as_good =
        rival.effect == kDriftInTime || twins ||
        !RivalCase(without, rival.effect, &swapped) ||
        !(fitted = FitFrom(swapped,
                           fit,
                           data,
                           "with " + rival.effect + " for " + step.effect,
                           &swapped_fit)) ||
        (Bic(swapped_fit) < Bic(fit) + options.ambiguity_bic &&
         (effect == nullptr ||
          Implausible(*effect, swapped, swapped_fit).empty()));
    VLOG(1) << step.effect << " swapped for " << rival.effect << ": "
            << (as_good ? "as good" : "worse");
    if (as_good) open.push_back(rival);
    if (as_good && fitted) as_good_fits->push_back(std::move(swapped_fit));
  }
  return open;
}

// The step's effect as the contender it was.
CandidateFit AsContender(const DiagnosisStep& step) {
  CandidateFit c;
  c.effect = step.effect;
  c.parameters = step.step_parameters;
  c.bic_drop = step.bic_drop;
  c.prediction_gain = step.prediction_gain;
  return c;
}

// What a second run would change to separate the tied `ambiguous` (the
// first and its rivals), for the model fitted as `fit`.
std::string SeparatedBy(const std::vector<CandidateFit>& ambiguous,
                        const Case& c,
                        const FitResult& fit,
                        const std::vector<TimeHistory>& data) {
  const Effect* a = FindEffect(ambiguous[0].effect);
  const Effect* b = FindEffect(ambiguous[1].effect);
  if (a != nullptr && b != nullptr) return Separation(*a, *b, c, fit);
  if (ambiguous[1].effect == kDriftInTime) {
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
// (pruned or with rivals left) stays in doubt, and *current is left as it
// was.
bool TieDissolves(const std::vector<TimeHistory>& data,
                  const DiagnoseOptions& options,
                  const std::vector<std::vector<CandidateFit>>& rivals,
                  int* tie,
                  std::vector<bool>* tied,
                  Diagnosis* d,
                  Case* current) {
  Diagnosis pruned = *d;
  Case model = *current;
  pruned.final_fit = pruned.steps.size();
  Prune(data, options, &pruned, &model);
  const FitResult& fit = pruned.FinalFit();
  const Case at = CaseAtSolution(model, fit);
  std::vector<std::vector<CandidateFit>> open_ties;
  int first = -1;
  for (size_t i = 0; i < d->steps.size(); ++i) {
    if (rivals[i].empty()) continue;
    const auto kept = std::find_if(
        pruned.steps.begin(), pruned.steps.end(), [&](const DiagnosisStep& s) {
          return s.effect == d->steps[i].effect;
        });
    // A step pruned away is not in doubt; but it is not adopted either.
    (*tied)[i] = true;
    if (kept == pruned.steps.end()) continue;
    std::vector<FitResult> swapped;
    const std::vector<CandidateFit> open = Unresolved(
        rivals[i], *kept, pruned.steps, at, fit, data, options, &swapped);
    for (const FitResult& f : swapped) d->tie_models.push_back(f.parameters);
    (*tied)[i] = !open.empty();
    if (open.empty()) continue;
    if (first < 0) first = static_cast<int>(i);
    open_ties.push_back({AsContender(d->steps[i])});
    open_ties.back().insert(open_ties.back().end(), open.begin(), open.end());
  }
  if (first >= 0) {
    *tie = first;
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
                   Diagnosis* d,
                   Case* current,
                   ResidualCheck* final) {
  int last = tie;  // the last step to adopt
  while (last + 1 < static_cast<int>(d->steps.size()) && !tied[last + 1]) {
    ++last;
  }
  VLOG(1) << "after the tie at step " << tie << ": " << last - tie
          << " step(s) before the next tie";
  if (last == tie) return false;
  // The complete model through `last` (its fit and case).
  const int through = last + 1;
  const FitResult& complete = d->fits[through];
  const FitResult& before = d->fits[tie];
  std::vector<int> adopt;  // the steps after the tie to adopt
  for (int i = tie + 1; i <= last; ++i) adopt.push_back(i);
  Case without =
      WithoutStep(CaseAtSolution(models[through], complete), d->steps[tie]);
  FitResult without_fit;
  if (!FitFrom(without,
               complete,
               data,
               "without " + d->steps[tie].effect,
               &without_fit)) {
    return false;
  }
  std::vector<const Effect*> effects;  // the adopted model's
  std::vector<std::string> names;      // the terms added after the tie
  AdoptedEffects(*d, tie, adopt, &effects, &names);
  // A step out of its bounds without the tied effect may be its companion
  // (TieCompanions): it goes with it.
  std::vector<int> companions;
  bool needed =
      NeededWithoutTied(options, effects, without, without_fit, before);
  if (!needed) {
    companions = TieCompanions(data, options, *d, adopt, without, without_fit);
  }
  if (!companions.empty()) {
    if (!WithoutCompanions(
            data, *d, companions, &adopt, &without, &without_fit)) {
      return false;
    }
    AdoptedEffects(*d, tie, adopt, &effects, &names);
    needed = NeededWithoutTied(options, effects, without, without_fit, before);
  }
  const bool stand_in = !needed;
  // The complete models: with every step the search took (a later tie's
  // followed effects in).
  const bool later = last + 1 < static_cast<int>(d->steps.size());
  if (stand_in && (later || !companions.empty())) {
    VLOG(1) << "no stand-in for the tie with a later tie or companions";
    return false;
  }
  const int full = later ? static_cast<int>(d->partial_fit) : through;
  // With each rival instead of the first, against that rival alone on the
  // model before the tie.
  std::vector<AlternativeModel> alternatives = {
      {d->steps[tie].effect,
       CheckResiduals(d->fits[full], options),
       d->fits[full].parameters,
       full}};
  bool known = alternatives[0].check.at_noise_level;
  std::vector<FitResult> rival_fits;
  std::vector<Case> rival_cases;
  for (size_t r = 1; r < d->ambiguous.size(); ++r) {
    const std::string& rival = d->ambiguous[r].effect;
    // A drift in time is no model (a straight drift of the readings stands
    // in for it) and is tested only when it is the one rival.
    if (rival == kDriftInTime && d->ambiguous.size() > 2) continue;
    FitResult rival_fit;
    Case with_rival;
    if (!AdoptedWithRival(data,
                          options,
                          effects,
                          without,
                          without_fit,
                          models[tie],
                          before,
                          rival,
                          &with_rival,
                          &rival_fit)) {
      VLOG(1) << "not needed, or not plausible, with " << rival;
      return false;
    }
    if (later && !CompleteWithRival(data,
                                    models[full],
                                    d->fits[full],
                                    d->steps[tie],
                                    rival,
                                    &with_rival,
                                    &rival_fit)) {
      return false;
    }
    alternatives.push_back(
        {rival, CheckResiduals(rival_fit, options), rival_fit.parameters, -1});
    known = known && alternatives.back().check.at_noise_level;
    rival_fits.push_back(std::move(rival_fit));
    rival_cases.push_back(std::move(with_rival));
  }
  if (stand_in && (!known || rival_fits.empty())) {
    VLOG(1) << "a stand-in for the tie needs every complete model at the "
            << "noise";
    return false;
  }
  if (stand_in) {
    std::vector<const Case*> cases = {&models[through]};
    std::vector<const FitResult*> fits = {&complete};
    for (size_t r = 0; r < rival_fits.size(); ++r) {
      cases.push_back(&rival_cases[r]);
      fits.push_back(&rival_fits[r]);
    }
    std::vector<DiagnosisStep> steps;
    for (int i : adopt) steps.push_back(d->steps[i]);
    if (!NeededInEach(data, options, cases, fits, steps)) return false;
  }
  // The drag rule guards against an effect absorbing an unknown structure;
  // when every complete model reaches the noise, what the final model
  // leaves is known (the tie's signature), and the coefficients may move.
  if (!known) {
    const std::string drags =
        Drags(before, without_fit, names, options.max_drag);
    if (!drags.empty()) {
      VLOG(1) << "the adopted effects drag the coefficients: " << drags;
      return false;
    }
  }
  Reported(models[full], data, &d->fits[full]);
  alternatives[0].parameters = d->fits[full].parameters;
  for (size_t r = 0; r < rival_fits.size(); ++r) {
    Reported(rival_cases[r], data, &rival_fits[r]);
    alternatives[r + 1].parameters = rival_fits[r].parameters;
    d->fits.push_back(std::move(rival_fits[r]));
    alternatives[r + 1].fit = static_cast<int>(d->fits.size()) - 1;
  }
  d->alternatives = std::move(alternatives);
  if (stand_in) {
    d->stand_in = d->steps[tie].effect;
    d->final_fit = through;
    *current = models[through];
  } else {
    d->fits.push_back(without_fit);
    d->final_fit = d->fits.size() - 1;
    *current = without;
  }
  SplitAtTie(tie, adopt, d);
  *final = CheckResiduals(d->FinalFit(), options);
  d->steps.back().after = *final;
  return true;
}

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
    Case* current) {
  if (!check.at_noise_level) {
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
  // Rivals within rival_bic of a step are swapped in even when none tied.
  const bool rivalled = std::any_of(
      rivals.begin(), rivals.end(), [](const auto& r) { return !r.empty(); });
  if (rivalled &&
      TieDissolves(data, options, rivals, &tie, &tied, d, current)) {
    // The tied effect turned out redundant with the later ones in, or
    // no rival explains the record as well with them.
    return CheckResiduals(d->FinalFit(), options);
  }
  ResidualCheck adopted;
  if (tie >= 0 &&
      AdoptAfterTie(data, options, models, tie, tied, d, current, &adopted)) {
    return adopted;
  }
  if (tie >= 0) {
    // Explained, but with one of a tied pair: the final model is the one
    // before the tie, the steps from it on are reported as partial.
    d->partial.assign(d->steps.begin() + tie, d->steps.end());
    d->steps.resize(tie);
    d->final_fit = tie;
    *current = models[tie];
    return tie == 0 ? d->initial : d->steps.back().after;
  }
  d->final_fit = d->steps.size();
  Prune(data, options, d, current);
  return CheckResiduals(d->FinalFit(), options);
}

// The probes outside the catalog at one round of the search, against the
// best catalog contender that earned its place (earned[0], if any): better
// by a margin (ProbeMargin), and the probe's fit goes into
// d->outside_catalog, every contender rejected for it (nothing is adopted);
// within the margin the caller ties them. A catalog effect refused here
// that explains more than the probe (a calibration error just past its
// bound while two effects beside it are missing) keeps the search in the
// catalog. Returns whether a probe was fitted that lowers BIC enough to
// count (*probe, pointing into *probes).
bool WeighProbes(const Case& current,
                 const FitResult& fit,
                 const std::vector<TimeHistory>& data,
                 const DiagnoseOptions& options,
                 const std::vector<int>& earned,
                 std::vector<Candidate>* probes,
                 Contender* probe,
                 std::vector<Contender>* contenders,
                 Diagnosis* d) {
  const bool probed = options.probes &&
                      FitProbes(current, fit, data, probes, probe) &&
                      probe->record.bic_drop >= options.min_bic_drop &&
                      probe->bic < BestBic(*contenders);
  if (!probed) return false;
  if (earned.empty() ||
      probe->bic <
          (*contenders)[earned[0]].bic -
              ProbeMargin((*contenders)[earned[0]], *probe, data, options)) {
    d->outside_catalog = probe->record;
    d->outside_at_noise_level =
        CheckResiduals(probe->fit, options).at_noise_level;
    OutdoneByProbe(*probe, contenders);
  }
  return true;
}

// Adds `best` to the search's record *d as its next step (its fit, the
// round's contenders and score ranking) and returns the residual check of
// its fit.
ResidualCheck TakeStep(const Contender& best,
                       const std::vector<Contender>& contenders,
                       const std::vector<Candidate>& candidates,
                       const DiagnoseOptions& options,
                       Diagnosis* d) {
  DiagnosisStep record = Step(best, contenders);
  for (const Candidate& k : candidates) record.ranking.push_back(k.score);
  d->fits.push_back(best.fit);
  record.fit_before = static_cast<int>(d->fits.size()) - 2;
  record.fit_after = static_cast<int>(d->fits.size()) - 1;
  record.after = CheckResiduals(best.fit, options);
  d->steps.push_back(record);
  return record.after;
}

// A roll-locked member of a joint set ties with its twins (diagnose.h)
// even where its round did not fit them: a roll reading error, which
// ties with a trim moment once a Magnus moment is in, had lowered BIC by
// 8 beside the missing Magnus moment, no contender, when the trim moment
// was adopted with it. Each is added to *rivals unfitted, as the step's
// equal (the final swap decides whether a spin rate separates them).
void AddTwins(const Contender& member,
              const DiagnoseOptions& options,
              std::vector<CandidateFit>* rivals) {
  if (!member.candidate->effect->roll_locked) return;
  for (const Effect& e : EffectCatalog()) {
    if (!Wanted(options, e) || !e.roll_locked || e.id == member.record.effect ||
        std::any_of(rivals->begin(), rivals->end(), [&](const CandidateFit& r) {
          return r.effect == e.id;
        })) {
      continue;
    }
    CandidateFit twin;
    twin.effect = e.id;
    twin.bic_drop = member.record.bic_drop;
    twin.prediction_gain = std::numeric_limits<double>::quiet_NaN();
    rivals->push_back(std::move(twin));
  }
}

// Adds the members of `joint` (Jointly) to the search's record *d as
// steps in turn (TakeStep), each with the round's rivals outside the set,
// as a step taken alone would have them (*tie, *rivals), and with its
// model and fit (*models, *current, *fit); returns the residual check of
// the last.
ResidualCheck TakeJointSteps(const JointSet& joint,
                             const std::vector<Contender>& contenders,
                             const std::vector<Candidate>& candidates,
                             const std::vector<TimeHistory>& data,
                             const DiagnoseOptions& options,
                             int* tie,
                             std::vector<std::vector<CandidateFit>>* rivals,
                             std::vector<Case>* models,
                             Case* current,
                             FitResult* fit,
                             Diagnosis* d) {
  const auto member = [&](const std::string& id) {
    return std::any_of(joint.members.begin(), joint.members.end(), [&](int m) {
      return contenders[m].record.effect == id;
    });
  };
  const auto outside = [&](std::vector<CandidateFit> r) {
    r.erase(
        std::remove_if(r.begin(),
                       r.end(),
                       [&](const CandidateFit& k) { return member(k.effect); }),
        r.end());
    return r;
  };
  ResidualCheck check;
  for (size_t j = 0; j < joint.members.size(); ++j) {
    const int m = joint.members[j];
    std::vector<CandidateFit> step_rivals =
        outside(Rivals(contenders, m, nullptr, data, options));
    if (*tie < 0 && !step_rivals.empty()) {
      *tie = static_cast<int>(d->steps.size());
    }
    rivals->push_back(
        outside(WiderRivals(std::move(step_rivals), contenders, m, options)));
    AddTwins(contenders[m], options, &rivals->back());
    Contender step;
    step.candidate = &joint.models[j];
    step.fit = joint.fits[j];
    step.bic = Bic(step.fit);
    step.record = contenders[m].record;
    step.record.parameters = Own(step.fit, joint.models[j].added);
    step.record.rejected.clear();
    step.record.prediction_gain =
        j + 1 == joint.members.size()
            ? joint.prediction_gain
            : std::numeric_limits<double>::quiet_NaN();
    *current = joint.models[j].c;
    *fit = step.fit;
    models->push_back(*current);
    check = TakeStep(step, contenders, candidates, options, d);
    std::string others;
    for (int k : joint.members) {
      if (k == m) continue;
      others += (others.empty() ? "" : " and ") + contenders[k].record.effect;
    }
    d->steps.back().note =
        "adopted together with " + others + ": " +
        (j == 0 ? "alone it dragged the coefficients; " : "") +
        "together they explain the record to the noise level, within their "
        "bounds, and predict its held-out part better";
  }
  return check;
}

// The complete model `m` with `set` in `step`'s place: *c and *fit; the
// terms each of `set` added in *added. False when it was not fitted.
bool SetInPlace(const CompleteModel& m,
                const DiagnosisStep& step,
                const std::vector<const Effect*>& set,
                const std::vector<TimeHistory>& data,
                Case* c,
                FitResult* fit,
                std::vector<std::vector<std::string>>* added) {
  *c = WithoutStep(CaseAtSolution(m.c, *m.fit), step);
  added->assign(set.size(), {});
  for (size_t j = 0; j < set.size(); ++j) {
    if (!CandidateCase(*c, *set[j], c, &(*added)[j])) return false;
  }
  return FitFrom(
      *c, *m.fit, data, "the effects not excluded for " + step.effect, fit);
}

// The members of `set` (their terms `added`) that the model `c`, fitted
// as `fit`, needs: without each, the residuals leave the noise level or
// BIC rises by min_bic_drop or more. An effect the record cannot exclude
// may be one it cannot see at all (a roll torque on a coning run): it
// rides along in a set without doing anything.
std::vector<const Effect*> Needed(
    const Case& c,
    const FitResult& fit,
    const std::vector<const Effect*>& set,
    const std::vector<std::vector<std::string>>& added,
    const std::vector<TimeHistory>& data,
    const DiagnoseOptions& options) {
  const int n = static_cast<int>(set.size());
  std::vector<FitResult> without(n);
  std::vector<char> fitted(n, false);  // written in parallel
  ParallelFor(n, [&](int j) {
    DiagnosisStep member;
    member.effect = set[j]->id;
    for (const std::string& name : added[j]) {
      member.step_parameters.push_back(ParameterEstimate());
      member.step_parameters.back().name = name;
    }
    fitted[j] = FitFrom(WithoutStep(CaseAtSolution(c, fit), member),
                        fit,
                        data,
                        "the set without " + set[j]->id,
                        &without[j]);
  });
  std::vector<const Effect*> needed;
  for (int j = 0; j < n; ++j) {
    if (!fitted[j] || !CheckResiduals(without[j], options).at_noise_level ||
        !(Bic(without[j]) - Bic(fit) < options.min_bic_drop)) {
      needed.push_back(set[j]);
    }
  }
  return needed;
}

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
std::string FindSetReplacements(const std::vector<Case>& models,
                                const Case& current,
                                const std::vector<TimeHistory>& data,
                                const DiagnoseOptions& options,
                                Diagnosis* d) {
  if (d->not_excluded.size() < 2 || d->steps.empty()) return "";
  const CompleteModel m = CompleteModels(*d, models, current).back();
  if (!CheckResiduals(*m.fit, options).at_noise_level) return "";
  std::vector<const Effect*> set;
  for (const CandidateFit& k : d->not_excluded) {
    set.push_back(FindEffect(k.effect));
  }
  const int n = static_cast<int>(d->steps.size());
  std::vector<Case> cases(n);
  std::vector<FitResult> fits(n);
  std::vector<std::vector<std::vector<std::string>>> added(n);
  std::vector<char> fitted(n, false);  // written in parallel
  ParallelFor(n, [&](int i) {
    fitted[i] =
        SetInPlace(m, d->steps[i], set, data, &cases[i], &fits[i], &added[i]);
  });
  // Judged with `members` in step i's place.
  auto rise_of = [&](int i, const std::vector<const Effect*>& members) {
    if (!CheckResiduals(fits[i], options).at_noise_level) {
      return std::numeric_limits<double>::infinity();
    }
    std::vector<const Effect*> effects = members;
    for (const Effect* e : m.effects) {
      if (e->id != d->steps[i].effect) effects.push_back(e);
    }
    const double rise = Bic(fits[i]) - Bic(*m.fit);
    const std::string why = ImplausibleAmong(effects, cases[i], fits[i]);
    VLOG(1) << "the effects not excluded for " << d->steps[i].effect << ": BIC "
            << (rise >= 0.0 ? "+" : "") << rise << " " << why;
    return why.empty() ? rise : std::numeric_limits<double>::infinity();
  };
  int best = -1;
  double least = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    const double rise =
        fitted[i] ? rise_of(i, set) : std::numeric_limits<double>::infinity();
    if (rise < least) {
      least = rise;
      best = i;
    }
  }
  if (best < 0 || !(least < options.ambiguity_bic)) return "";
  // Only the members the replacement needs; one alone is a swap's
  // (Unresolved), not a set's.
  const std::vector<const Effect*> needed =
      Needed(cases[best], fits[best], set, added[best], data, options);
  if (needed.size() < 2) return "";
  if (needed.size() < set.size()) {
    set = needed;
    if (!SetInPlace(m,
                    d->steps[best],
                    set,
                    data,
                    &cases[best],
                    &fits[best],
                    &added[best])) {
      return "";
    }
    least = rise_of(best, set);
    if (!(least < options.ambiguity_bic)) return "";
  }
  // Better by ambiguity_bic or more: the search took the wrong turn, and
  // DiagnoseFrom searches again without the step's effect.
  if (!(least > -options.ambiguity_bic)) return d->steps[best].effect;
  Reported(cases[best], data, &fits[best]);
  WidenErrorBars(
      {&fits[best].parameters},
      {},
      "the effects not excluded in " + d->steps[best].effect + "'s place",
      &d->fits[d->final_fit],
      &d->model_standard_errors);
  std::vector<CandidateFit> tie = {AsContender(d->steps[best])};
  std::vector<std::string> ids;
  for (const CandidateFit& k : d->not_excluded) {
    if (std::find(set.begin(), set.end(), FindEffect(k.effect)) != set.end()) {
      tie.push_back(k);
      ids.push_back(k.effect);
    }
  }
  (d->ambiguous.empty() ? d->ambiguous : d->later_ties.emplace_back()) = tie;
  d->stood_in.push_back(d->steps[best]);
  d->stood_in_for.push_back(ids);
  d->steps.erase(d->steps.begin() + best);
  return "";
}

// The forward search (diagnose.h) from `nominal`, the fit of `c`, with
// `options`' catalog; *tied_first
// gets the effect it followed at a tie of two catalog effects (empty if
// none).
Diagnosis Search(const Case& c,
                 const FitResult& nominal,
                 const DiagnoseOptions& options,
                 std::string* tied_first,
                 std::string* outdone) {
  tied_first->clear();
  Diagnosis d;
  // The search's fits skip the profiles (fit.h, CheckRidges); the fits it
  // reports get them (Reported).
  Case quiet = c;
  quiet.solver.profile_ridges = false;
  Case current = quiet;
  FitResult fit = nominal;
  const std::vector<TimeHistory> data = FittedData(fit);
  d.fits.push_back(fit);
  std::vector<Case> models = {current};  // the model of each of d.fits
  d.initial = CheckResiduals(fit, options);
  ResidualCheck check = d.initial;
  // The step at which two contenders first tied (diagnose.h), or -1, and
  // whether each step tied.
  int tie = -1;
  std::vector<std::vector<CandidateFit>> rivals;
  // Every round's contenders, each once: the effects tried beside the
  // complete model (FindNotExcluded).
  std::vector<const Effect*> contended;
  for (int step = 0; step < options.max_steps && !check.at_noise_level;
       ++step) {
    if (Polish(current, data, &fit)) {
      // The same model, further down: the steps' record follows it.
      d.fits.back() = fit;
      check = CheckResiduals(fit, options);
      if (d.steps.empty()) {
        d.initial = check;
      } else {
        d.steps.back().after = check;
      }
      if (check.at_noise_level) break;
    }
    const std::vector<Candidate> candidates =
        ScoredCandidates(current, fit, options);
    std::vector<Contender> contenders =
        Contenders(candidates, fit, data, options);
    for (const Contender& k : contenders) {
      const Effect* e = k.candidate->effect;
      if (std::find(contended.begin(), contended.end(), e) == contended.end()) {
        contended.push_back(e);
      }
    }
    OutOfSample out_of_sample(current, fit, options);
    std::vector<const Effect*> added;
    for (const DiagnosisStep& s : d.steps)
      added.push_back(FindEffect(s.effect));
    const std::vector<int> earned =
        Earned(fit, added, options, &out_of_sample, &contenders);
    std::vector<Candidate> probes;
    Contender probe;
    const bool probed = WeighProbes(
        current, fit, data, options, earned, &probes, &probe, &contenders, &d);
    JointSet joint;
    if (d.outside_catalog.effect.empty() && Jointly(current,
                                                    fit,
                                                    data,
                                                    options,
                                                    added,
                                                    &out_of_sample,
                                                    contenders,
                                                    earned,
                                                    &joint)) {
      check = TakeJointSteps(joint,
                             contenders,
                             candidates,
                             data,
                             options,
                             &tie,
                             &rivals,
                             &models,
                             &current,
                             &fit,
                             &d);
      continue;
    }
    if (earned.empty() || !d.outside_catalog.effect.empty()) {
      for (const Contender& k : contenders) d.rejected.push_back(k.record);
      break;
    }
    const Contender& best = contenders[earned[0]];
    std::vector<CandidateFit> step_rivals =
        Rivals(contenders, earned[0], probed ? &probe : nullptr, data, options);
    if (tie < 0 && !step_rivals.empty()) {
      // Go on with the best: whether the rest of the record is explained
      // decides between `ambiguous` and `not_explained`.
      tie = static_cast<int>(d.steps.size());
      if (earned.size() > 1) *tied_first = best.record.effect;
    }
    rivals.push_back(
        WiderRivals(std::move(step_rivals), contenders, earned[0], options));
    current = best.candidate->c;
    fit = best.fit;
    models.push_back(current);
    check = TakeStep(best, contenders, candidates, options, &d);
  }
  d.partial_fit = d.fits.size() - 1;
  d.final = SettleFinalModel(
      quiet, data, options, models, tie, rivals, check, &d, &current);
  Reported(current, data, &d.fits[d.final_fit]);
  if (!d.partial.empty() && d.partial_fit != d.final_fit) {
    Reported(models[d.partial_fit], data, &d.fits[d.partial_fit]);
  }
  WidenForTie(&d);
  FindNotExcluded(contended, models, current, data, options, &d);
  *outdone = FindSetReplacements(models, current, data, options, &d);
  WidenForNotExcluded(&d);
  if (!d.ambiguous.empty()) {
    d.separated_by = SeparatedBy(d.ambiguous, quiet, d.FinalFit(), data);
  }
  d.final_case = FinalCase(c, current, d.FinalFit());
  FinalValues(&d);
  Conclude(&d);
  return d;
}

// Whether a diagnosis explains the record: outright, or with ties whose
// every branch does (`ambiguous`).
bool ExplainsRecord(const Diagnosis& d) {
  return d.verdict == Verdict::kExplained || d.verdict == Verdict::kAmbiguous;
}

// The tied effect `first` as the search that followed it found it: its
// record from the first step that had it among the contenders.
CandidateFit FollowedFirst(const Diagnosis& d, const std::string& first) {
  for (const DiagnosisStep& s : d.partial) {
    for (const CandidateFit& k : s.contenders) {
      if (k.effect == first) return k;
    }
  }
  CandidateFit none;
  none.effect = first;
  return none;
}

Diagnosis DiagnoseFrom(const Case& c,
                       const FitResult& nominal,
                       const DiagnoseOptions& options);

// A probe outside the catalog outdid every catalog effect at one round of
// `d`; but it was weighed against single effects, and several may explain
// the record between them. The diagnosis without probes, when it explains
// the record (or ties with every branch explained) and its complete
// model's BIC is lower than the probe's model's by more than
// ambiguity_bic, is the answer (the probe among its rejected): a reading
// lag had beaten a Magnus moment at the first step of a record that a
// Magnus moment, a nonlinear damping and a calibration error explain. A
// probe that one catalog effect only matches (a flow stiffer in one plane
// against a Magnus moment) keeps its verdict. No second search when the
// probe explains the record to the noise (nothing can lower BIC much below
// a noise-level fit). A probe that lowers BIC by more than all the round's
// catalog contenders together is no exception: interacting effects do more
// together than the sum of what each does alone (on a Table 6 record,
// after a calibration error, the round's five catalog effects lowered BIC
// by 1566 between them, one at a time, a bearing friction by 2000; a Magnus
// moment and a nonlinear damping together explain the record).
Diagnosis CatalogAlone(const Case& c,
                       const FitResult& nominal,
                       const DiagnoseOptions& options,
                       Diagnosis d) {
  if (d.outside_at_noise_level) return d;
  DiagnoseOptions without = options;
  without.probes = false;
  Diagnosis other = DiagnoseFrom(c, nominal, without);
  if (!ExplainsRecord(other)) return d;
  // The complete model: the final one, or the search's last (what an open
  // tie leaves out of the final model, pruning may have dropped).
  const double catalog_bic =
      std::min(Bic(other.FinalFit()), Bic(other.fits[other.partial_fit]));
  const double probe_bic = Bic(d.fits.back()) - d.outside_catalog.bic_drop;
  const double margin = probe_bic - catalog_bic;
  if (!(margin > options.ambiguity_bic)) return d;
  CandidateFit outside = d.outside_catalog;
  outside.rejected = "explains more than any one catalog effect at step " +
                     std::to_string(d.steps.size() + 1) + ", but the " +
                     "catalog's effects together explain the record (BIC " +
                     FormatNumber("%.1f", margin) + " lower)";
  other.rejected.push_back(outside);
  return other;
}

// Search, and when a probe outdid the catalog, CatalogAlone (whose
// answer has no *outdone).
Diagnosis Searched(const Case& c,
                   const FitResult& nominal,
                   const DiagnoseOptions& options,
                   std::string* tied_first,
                   std::string* outdone) {
  Diagnosis d = Search(c, nominal, options, tied_first, outdone);
  if (d.outside_catalog.effect.empty()) return d;
  outdone->clear();
  return CatalogAlone(c, nominal, options, std::move(d));
}

// `options` without the catalog effect `id`.
DiagnoseOptions Without(const DiagnoseOptions& options, const std::string& id) {
  DiagnoseOptions without = options;
  without.effects.clear();
  for (const Effect& e : EffectCatalog()) {
    if (Wanted(options, e) && e.id != id) without.effects.push_back(e.id);
  }
  return without;
}

// The BIC of a diagnosis's complete model: the final one, or the search's
// last (what an open tie leaves out of the final model).
double CompleteBic(const Diagnosis& d) {
  return std::min(Bic(d.FinalFit()), Bic(d.fits[d.partial_fit]));
}

// A step that the effects not excluded beat together by ambiguity_bic or
// more (FindSetReplacements, `outdone`) was the search's wrong turn: the
// search without its effect is the answer when it explains the record
// with a lower BIC.
bool ReplacedStep(const Case& c,
                  const FitResult& nominal,
                  const DiagnoseOptions& options,
                  const std::string& outdone,
                  Diagnosis* d) {
  std::string first, unused;
  Diagnosis other =
      Searched(c, nominal, Without(options, outdone), &first, &unused);
  const double margin = CompleteBic(*d) - CompleteBic(other);
  if (!ExplainsRecord(other) || !(margin > 0.0)) return false;
  for (const DiagnosisStep& s : d->steps) {
    if (s.effect != outdone) continue;
    CandidateFit step = AsContender(s);
    step.rejected =
        "stood in for effects that together explain the record "
        "better (BIC " +
        FormatNumber("%.1f", margin) + " lower without it)";
    other.rejected.push_back(step);
  }
  other.verdict_text += "; " + Describe(outdone) +
                        ", taken first, stood in for effects that together "
                        "explain the record better";
  *d = std::move(other);
  return true;
}

// A tie followed down the better branch that leaves the record unexplained
// is followed down the other: a Magnus moment and an asymmetric body lower
// BIC alike on one short run, but only with the Magnus moment do the
// other effects in the record bring the residuals to the noise level. The
// other branch's answer is taken when it explains the record, with or
// without a tie of its own: on a coning run with a roll reading error and
// a nonlinear damping, a trim moment tied with a flow angularity at the
// first step and, once in, left the damping predicting nothing held out;
// without it a flow angularity or the reading error (a tie) and the
// damping explain the record.
Diagnosis DiagnoseFrom(const Case& c,
                       const FitResult& nominal,
                       const DiagnoseOptions& options) {
  std::string first, outdone;
  Diagnosis d = Searched(c, nominal, options, &first, &outdone);
  if (!outdone.empty() && ReplacedStep(c, nominal, options, outdone, &d)) {
    return d;
  }
  if (d.verdict != Verdict::kNotExplained || first.empty()) return d;
  std::string unused, none;
  Diagnosis other =
      Searched(c, nominal, Without(options, first), &unused, &none);
  if (!ExplainsRecord(other)) return d;
  CandidateFit followed = FollowedFirst(d, first);
  followed.rejected =
      "as good at its step as the effect that replaced it, but whatever "
      "followed it the residuals stayed structured";
  other.rejected.push_back(followed);
  other.verdict_text += "; " + Describe(first) +
                        ", as good at one step, leaves the residuals "
                        "structured whatever follows it";
  return other;
}

}  // namespace

Diagnosis Diagnose(const Case& c, const DiagnoseOptions& options) {
  return DiagnoseFrom(c, Fit(c), options);
}

}  // namespace fit3dof
