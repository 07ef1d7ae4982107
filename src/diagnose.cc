// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The diagnosis loop (diagnose.h): fit, check the residuals, score every
// catalog effect not yet in the model, refit the best few, add the best
// one that earns its place (unless a second one explains the residual as
// well), repeat. This file runs the search (Search); its second thoughts
// and the answer taken are diagnose_second_thoughts.cc (DiagnoseFrom), a
// round diagnose_round.cc, ties and the final model diagnose_ties.cc, the
// final error bars diagnose_error_bars.cc. The
// other pieces: effect_catalog.cc, score_test.cc, effect_validation.cc,
// residual_check.cc, residual_description.cc, diagnosis_verdict.cc,
// diagnosis_report.cc.

#include "fit3dof/diagnose.h"

#include <glog/logging.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "diagnose_search.h"
#include "fit3dof/input_error.h"
#include "fit3dof/integration_step.h"
#include "fit3dof/model_conversion.h"
#include "fit3dof/wild_points.h"
#include "noise_relaxation.h"

namespace fit3dof {

namespace {

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

// The names of `step`'s values in `fit`: its effect's terms in the form
// the effect has there, and what else the step held. A step taken in one
// form may be reported by a model that holds the other (a search's later
// round took a calibration back to its cube; the final model, the one
// before a tie, kept the signed square): the held terms of the other form
// had read as the effect's values (theta_cal3 = 0 (held) on draw 95's pair
// of runs, whose final model held theta_cal2 = -0.038 +- 0.025).
std::vector<std::string> FinalNames(const DiagnosisStep& step,
                                    const FitResult& fit) {
  static const std::vector<std::string> kNone;
  const Effect* effect = FindEffect(step.effect);
  const Effect* form = effect == nullptr ? nullptr : OtherForm(*effect);
  const std::vector<std::string>& own =
      effect == nullptr ? kNone : effect->Terms(fit.model);
  const std::vector<std::string>& other =
      form == nullptr ? kNone : form->Terms(fit.model);
  const auto in = [](const std::vector<std::string>& terms,
                     const std::string& name) {
    return std::find(terms.begin(), terms.end(), name) != terms.end();
  };
  std::vector<std::string> names;
  for (const ParameterEstimate& e : step.step_parameters) {
    if (!in(own, e.name) && !in(other, e.name)) names.push_back(e.name);
  }
  const std::vector<std::string>& terms =
      effect != nullptr && InOtherFormIn(*effect, fit) ? other : own;
  names.insert(names.end(), terms.begin(), terms.end());
  return names;
}

}  // namespace

bool InOtherFormIn(const Effect& effect, const FitResult& fit) {
  const Effect* form = OtherForm(effect);
  if (form == nullptr) return false;
  for (const std::string& name : form->Terms(fit.model)) {
    const auto e = std::find_if(
        fit.parameters.begin(),
        fit.parameters.end(),
        [&](const ParameterEstimate& p) { return p.name == name; });
    if (e == fit.parameters.end() || !e->free) return false;
  }
  return true;
}

void FinalValues(Diagnosis* d) {
  d->final_parameters = d->FinalFit().parameters;
  for (std::vector<DiagnosisStep>* steps :
       {&d->steps, &d->partial, &d->pruned, &d->stood_in}) {
    const FitResult& fit =
        steps == &d->partial ? d->fits[d->partial_fit] : d->FinalFit();
    for (DiagnosisStep& step : *steps) {
      step.parameters = Own(fit, FinalNames(step, fit));
    }
  }
}

namespace {

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
        FindFit(*rivals, e.id) != nullptr) {
      continue;
    }
    CandidateFit twin;
    twin.effect = e.id;
    twin.bic_drop = member.record.bic_drop;
    twin.prediction_gain = std::numeric_limits<double>::quiet_NaN();
    rivals->push_back(std::move(twin));
  }
}

// The rivals (Rivals, with WiderRivals' when `wider`) of the joint set's
// member contenders[m] outside the set. A member drawn from the round's
// lesser refits is weighed against them too (`pooled`: the contenders,
// then the lesser refits): on a 3-s coning run with a gas-bearing moment,
// a calibration nonlinearity and a roll torque (suite draw 29), the set
// took a roll damping, which lowered BIC by 8.07993 alone against the
// roll torque's 8.07981 (at one spin rate the two are one constant roll
// acceleration), and named it alone.
std::vector<CandidateFit> MemberRivals(const JointSet& joint,
                                       const std::vector<Contender>& contenders,
                                       const std::vector<Contender>& pooled,
                                       int m,
                                       const std::vector<TimeHistory>& data,
                                       const DiagnoseOptions& options,
                                       bool wider) {
  const std::vector<Contender>* field = &contenders;
  int at = m;
  if (contenders[m].minor) {
    field = &pooled;
    at = static_cast<int>(std::find_if(pooled.begin(),
                                       pooled.end(),
                                       [&](const Contender& k) {
                                         return k.record.effect ==
                                                contenders[m].record.effect;
                                       }) -
                          pooled.begin());
    CHECK_LT(at, static_cast<int>(pooled.size()));
  }
  std::vector<CandidateFit> r = Rivals(*field, at, nullptr, data, options);
  if (wider) r = WiderRivals(std::move(r), *field, at, options);
  r.erase(std::remove_if(
              r.begin(),
              r.end(),
              [&](const CandidateFit& k) {
                return std::any_of(
                    joint.members.begin(), joint.members.end(), [&](int i) {
                      return contenders[i].record.effect == k.effect;
                    });
              }),
          r.end());
  return r;
}

// The members of `joint` (Jointly) reordered for a first tie among them:
// when the first member ties with no effect outside the set, the member
// that ties closest (its rival's BIC nearest its own) goes first, then the
// members that tie with none, then the other tied ones (InOrder), so
// that the untied members follow the tie and precede any later one, as
// AdoptAfterTie expects. Unchanged when no member ties, the first does, or
// a refit fails.
void TieFirst(const Case& current,
              const FitResult& fit,
              const std::vector<TimeHistory>& data,
              const DiagnoseOptions& options,
              const std::vector<Contender>& contenders,
              const std::vector<Contender>& pooled,
              JointSet* joint) {
  const size_t n = joint->members.size();
  std::vector<double> gap(n, std::numeric_limits<double>::infinity());
  for (size_t j = 0; j < n; ++j) {
    const int m = joint->members[j];
    for (const CandidateFit& r :
         MemberRivals(*joint, contenders, pooled, m, data, options, false)) {
      gap[j] =
          std::min(gap[j],
                   r.effect == kDriftInTime
                       ? options.ambiguity_bic
                       : std::abs(r.bic_drop - contenders[m].record.bic_drop));
    }
  }
  const size_t first = std::min_element(gap.begin(), gap.end()) - gap.begin();
  if (std::isinf(gap[first]) || !std::isinf(gap[0])) return;
  std::vector<int> order = {joint->members[first]};
  for (bool untied : {true, false}) {
    for (size_t j = 0; j < n; ++j) {
      if (j != first && std::isinf(gap[j]) == untied) {
        order.push_back(joint->members[j]);
      }
    }
  }
  InOrder(current, fit, data, contenders, order, joint);
}

// The round's `contenders` with the members of *joint drawn from beyond
// them in `pooled` (Contenders' lesser refits) appended, *joint's indices
// mapped to theirs: the lesser refits are rivals only of a member drawn
// from them (MemberRivals, on `pooled`).
std::vector<Contender> WithMembers(const std::vector<Contender>& contenders,
                                   const std::vector<Contender>& pooled,
                                   JointSet* joint) {
  std::vector<Contender> with = contenders;
  for (int& m : joint->members) {
    if (m < static_cast<int>(contenders.size())) continue;
    with.push_back(pooled[m]);
    m = static_cast<int>(with.size()) - 1;
  }
  return with;
}

// What the forward search (Search) carries from round to round.
struct SearchState {
  // The user's case, its fits without the profiles (fit.h, CheckRidges;
  // the fits the search reports get them, Reported).
  Case quiet;
  Case current;   // the model as it stands
  FitResult fit;  // its fit
  std::vector<TimeHistory> data;
  std::vector<Case> models;  // the model of each of d.fits
  ResidualCheck check;       // of `fit`
  // The step at which two contenders first tied (diagnose.h), or -1; each
  // step's rivals.
  int tie = -1;
  std::vector<std::vector<CandidateFit>> rivals;
  // Every round's contenders, each once: the effects tried beside the
  // complete model (FindNotExcluded); and the lesser refits (those that
  // lowered BIC by less than min_bic_drop), tried there when their score
  // calls for it.
  std::vector<const Effect*> contended;
  std::vector<const Effect*> lesser;
  Diagnosis d;
};

// Adds the members of `joint` (Jointly) to the search's record s->d as
// steps in turn (TakeStep), each with the round's rivals outside the set
// (`pooled`: the contenders, then the lesser refits; MemberRivals),
// as a step taken alone would have them (s->tie, s->rivals), and with its
// model and fit (s->models, s->current, s->fit); returns the residual
// check of the last. At the search's first tie a member that ties goes first
// (TieFirst): the steps after a tie are judged against its rivals
// (AdoptAfterTie), a step before it is not. On a 3-s run with a roll
// reading error and a nonlinear damping, the set {nonlinear damping, flow
// angularity, trim moment} was adopted and the trim moment tied with the
// reading error; the flow angularity, needed only beside the trim moment,
// had come before the tie and stayed in the final model (it tied with the
// reading error too, but less closely, and was redundant beside the trim
// moment).
ResidualCheck TakeJointSteps(JointSet joint,
                             const std::vector<Contender>& contenders,
                             const std::vector<Contender>& pooled,
                             const std::vector<Candidate>& candidates,
                             const DiagnoseOptions& options,
                             SearchState* s) {
  const std::vector<TimeHistory>& data = s->data;
  Diagnosis* d = &s->d;
  if (s->tie < 0) {
    TieFirst(s->current, s->fit, data, options, contenders, pooled, &joint);
  }
  ResidualCheck check;
  for (size_t j = 0; j < joint.members.size(); ++j) {
    const int m = joint.members[j];
    if (s->tie < 0 &&
        !MemberRivals(joint, contenders, pooled, m, data, options, false)
             .empty()) {
      s->tie = static_cast<int>(d->steps.size());
    }
    s->rivals.push_back(
        MemberRivals(joint, contenders, pooled, m, data, options, true));
    AddTwins(contenders[m], options, &s->rivals.back());
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
    s->current = joint.models[j].c;
    s->fit = step.fit;
    s->models.push_back(s->current);
    check = TakeStep(step, contenders, candidates, options, d);
    std::string others;
    for (int k : joint.members) {
      if (k == m) continue;
      others += (others.empty() ? "" : " and ") + contenders[k].record.effect;
      d->steps.back().adopted_with.push_back(contenders[k].record.effect);
    }
    d->steps.back().joint_set = true;
    d->steps.back().note =
        "adopted together with " + others + ": " +
        (contenders[m].dragged ? "alone it dragged the coefficients; " : "") +
        "together they explain the record to the noise level, within their "
        "bounds, and predict its held-out part better";
  }
  return check;
}

// Whether a contender refused for leaving its bounds comes ahead of every
// one that earned its place (`earned`, Earned).
bool BoundedLead(const std::vector<Contender>& contenders,
                 const std::vector<int>& earned) {
  const int judged =
      earned.empty() ? static_cast<int>(contenders.size()) : earned[0];
  return std::any_of(contenders.begin(),
                     contenders.begin() + judged,
                     [](const Contender& k) { return k.out_of_bounds; });
}

// Into notes->blocker (the first only): the effect added before that alone
// refused the round's best contender (Contender::blocked_by) when that
// contender lowered BIC by min_bic_drop more than any that earned its
// place, or than the model if none did.
void NoteBlocker(const std::vector<Contender>& contenders,
                 const std::vector<int>& earned,
                 const DiagnoseOptions& options,
                 SearchNotes* notes) {
  if (!notes->blocker.empty() || contenders.empty()) return;
  const Contender& best = contenders[0];
  if (best.blocked_by.empty()) return;
  if (!earned.empty() &&
      !(best.bic < contenders[earned[0]].bic - options.min_bic_drop)) {
    return;
  }
  notes->blocker = best.blocked_by;
}

// Whether a contender after the best that earned its place (`earned`,
// Earned) and not refused comes within near_tie_bic of it. Earned judges
// none beyond ambiguity_bic; the search without the best judges them.
bool NearTie(const std::vector<Contender>& contenders,
             const std::vector<int>& earned,
             const DiagnoseOptions& options) {
  if (earned.empty()) return false;
  const Contender& best = contenders[earned[0]];
  for (size_t i = earned[0] + 1; i < contenders.size(); ++i) {
    const Contender& k = contenders[i];
    if (!k.record.rejected.empty()) continue;
    return best.record.bic_drop - k.record.bic_drop <= options.near_tie_bic;
  }
  return false;
}

// Whether `k` (scored at `fit`) is a near twin of its free parameters
// (IsNearTwin) whose score may earn a place (ScoreMayEarn's rule) and
// which moves a coefficient of the model (TwinShifts). At the noise
// level, with sigma given, the search stops; but a twin's signature hides
// in the parameters it moves, and the residuals reach the noise with the
// effect there. On a 3-s run with a nonlinear damping at 0.9 of its bound,
// Cm_q took it (-4.5 for -5.5, 61 of its errors off), the nominal fit
// reached the noise, and the damping's score (16.0, novelty 0.0014) stood
// 11 above ln(n): the true model's BIC was 11.4 lower. A twin of the
// initial conditions alone moves no coefficient: left out at the noise
// level it biases none, and its score there is as likely the noise's. On
// clean Table 6 records (suite draw 67) a product of inertia, novelty
// 0.0006, scored 24.2 (16.4 above ln(n)) on one whose noise held a line
// at the spin frequency (4.3 times its mean amplitude in theta), and was
// added at 5.0 of its errors; on 46 others of the same motion it stood
// within 2.5 (z spread 0.99).
bool HiddenTwin(const Candidate& k,
                const FitResult& fit,
                const DiagnoseOptions& options) {
  return IsNearTwin(k.score) && ScoreMayEarn({k}, fit, options) &&
         !TwinShifts(k.c, k.added, FittedData(fit)).empty();
}

// Of `candidates` (scored at `fit`), the hidden twins (HiddenTwin).
std::vector<Candidate> HiddenTwins(std::vector<Candidate> candidates,
                                   const FitResult& fit,
                                   const DiagnoseOptions& options) {
  std::vector<Candidate> twins;
  for (Candidate& k : candidates) {
    if (HiddenTwin(k, fit, options)) twins.push_back(std::move(k));
  }
  return twins;
}

// Of `candidates` (scored at `fit`, the search at the noise level with
// sigma given), those a round may still add: the effects named past the
// noise (DiagnoseOptions::past_noise) and, in the search's first round,
// the hidden twins (HiddenTwins).
std::vector<Candidate> AtNoiseLevel(std::vector<Candidate> candidates,
                                    const FitResult& fit,
                                    const DiagnoseOptions& options,
                                    bool first) {
  const std::vector<std::string>& named = options.past_noise;
  std::vector<Candidate> kept;
  for (Candidate& k : candidates) {
    if (std::find(named.begin(), named.end(), k.effect->id) != named.end() ||
        (first && HiddenTwin(k, fit, options))) {
      kept.push_back(std::move(k));
    }
  }
  return kept;
}

// The final model *current (fitted as d->FinalFit()) back in the user's
// symmetric program (`user`) when the steps that took it to the
// asymmetric one were pruned and nothing is tied (ToSymmetric): the
// same motion, reported with the symmetric program's terms. On a 3-s run
// with a tunnel damping, a Magnus moment and a flow angularity, the body
// asymmetry taken first was dropped once the Magnus moment was in, and
// the final model had reported the Magnus moment as Cm_p_beta and
// Cn_p_alpha. Left as it is when the conversion or the refit fails.
void BackToSymmetric(const Case& user,
                     const std::vector<TimeHistory>& data,
                     Diagnosis* d,
                     Case* current) {
  if (user.model != ModelKind::kSymmetric ||
      current->model != ModelKind::kAsymmetric || !d->ambiguous.empty() ||
      !d->final.at_noise_level) {
    return;
  }
  Case symmetric;
  try {
    symmetric = ToSymmetric(CaseAtSolution(*current, d->FinalFit()));
  } catch (const InputError&) {
    return;  // an asymmetry stays in the model
  }
  FitResult fit;
  if (!FitFrom(
          symmetric, d->FinalFit(), data, "in the symmetric program", &fit)) {
    return;
  }
  *current = symmetric;
  d->fits[d->final_fit] = std::move(fit);
}

// `d`, the search's answer for the model `current`, with its error bars
// widened by what it cannot exclude (WidenForNotExcluded, WidenAlternatives),
// what would separate a tie, its final values and its verdict.
Diagnosis Concluded(const Case& c,
                    const Case& quiet,
                    const Case& current,
                    const std::vector<TimeHistory>& data,
                    const DiagnoseOptions& options,
                    Diagnosis d) {
  WidenForNotExcluded(&d);
  WidenAlternatives(data, options, &d);
  SeparateTies(quiet, data, &d);
  d.final_case = FinalCase(c, current, d.FinalFit());
  FinalValues(&d);
  Conclude(&d);
  return d;
}

// The search's state before its first round: the nominal fit of `c`.
SearchState StartSearch(const Case& c,
                        const FitResult& nominal,
                        const DiagnoseOptions& options) {
  SearchState s;
  s.quiet = c;
  s.quiet.solver.profile_ridges = false;
  s.current = s.quiet;
  s.fit = nominal;
  s.data = FittedData(s.fit);
  s.d.fits.push_back(s.fit);
  s.models = {s.current};
  s.d.noise_held = options.noise_held;
  s.d.absent = options.absent;
  s.d.initial = CheckResiduals(s.fit, options);
  s.check = s.d.initial;
  return s;
}

// The steps' record follows the model as it stands, s->fit.
void Restated(const DiagnoseOptions& options, SearchState* s) {
  s->d.fits.back() = s->fit;
  s->check = CheckResiduals(s->fit, options);
  if (s->d.steps.empty()) {
    s->d.initial = s->check;
  } else {
    s->d.steps.back().after = s->check;
  }
}

// An effect a step added in its other form back in its own where the
// record no longer favors the other (BackToOwnForms); returns whether one
// went back.
bool ReformRound(const DiagnoseOptions& options, SearchState* s) {
  if (!BackToOwnForms(s->data, &s->current, &s->fit, &s->d.steps)) {
    return false;
  }
  s->models.back() = s->current;
  Restated(options, s);
  return true;
}

// A round's start: ReformRound, then Polish (diagnose_search.h) takes the
// model as it stands further down where it can. Returns whether either
// moved it.
bool PolishRound(const DiagnoseOptions& options, SearchState* s) {
  const bool reformed = ReformRound(options, s);
  if (!Polish(s->current, s->data, &s->fit)) return reformed;
  Restated(options, s);
  return true;
}

// A round's candidates into *candidates: scored at the model as it
// stands, or the first round's hidden twins (*twins, moved from) when
// they were scored at that very fit (`at_twins`). At the noise level with
// sigma given, and past it (noise_held) when no refit's score can earn a
// place, a round holds only the effects named past the noise (and, with
// sigma given, the `first` round's hidden twins). False when none is
// left: the search ends.
bool RoundCandidates(bool first,
                     bool at_twins,
                     std::vector<Candidate>* twins,
                     const DiagnoseOptions& options,
                     const SearchState& s,
                     std::vector<Candidate>* candidates) {
  *candidates = at_twins ? std::move(*twins)
                         : ScoredCandidates(s.current, s.fit, options);
  // The twins are AtNoiseLevel's first round already, at this fit: not
  // judged again (HiddenTwin evaluates each one's Jacobian).
  if (!at_twins && s.check.at_noise_level &&
      (!options.noise_held || !ScoreMayEarn(*candidates, s.fit, options))) {
    *candidates = AtNoiseLevel(
        std::move(*candidates), s.fit, options, first && !options.noise_held);
    if (candidates->empty()) return false;
  }
  return true;
}

// Each effect of a round's refits once in s->contended (`contenders`) or
// s->lesser (`minor`).
void NoteContended(const std::vector<Contender>& contenders,
                   const std::vector<Contender>& minor,
                   SearchState* s) {
  for (const std::vector<Contender>* refits : {&contenders, &minor}) {
    std::vector<const Effect*>* list =
        refits == &contenders ? &s->contended : &s->lesser;
    for (const Contender& k : *refits) {
      const Effect* e = k.candidate->effect;
      if (std::find(list->begin(), list->end(), e) == list->end()) {
        list->push_back(e);
      }
    }
  }
}

// The last round's record when none of its `contenders` earned its place
// (`earned`, Earned) or `probe` outdid them: each rejected, those the
// probe outdid kept as such, and short of the noise those refused for
// dragging the coefficients.
void RejectRound(const std::vector<Contender>& contenders,
                 const std::vector<int>& earned,
                 const Contender& probe,
                 SearchState* s) {
  Diagnosis* d = &s->d;
  for (const Contender& k : contenders) d->rejected.push_back(k.record);
  if (probe.candidate != nullptr && probe.unpredicted) {
    d->rejected.push_back(probe.record);
  }
  if (!d->outside_catalog.effect.empty()) {
    KeepOutdoneByProbe(probe, contenders, earned, s->fit, d);
  }
  if (!s->check.at_noise_level) KeepRefusedForDrag(contenders, s->fit, d);
}

// The fitted motions of `a` and `b`, two fits of one record, apart: the
// sum over samples of their squared difference in units of the residual
// weights (a's).
double MotionApart(const FitResult& a, const FitResult& b) {
  CHECK_EQ(a.segments.size(), b.segments.size());
  double sum = 0.0;
  for (size_t k = 0; k < a.segments.size(); ++k) {
    const SegmentFit& x = a.segments[k];
    const SegmentFit& y = b.segments[k];
    CHECK_EQ(x.computed.size(), y.computed.size());
    for (size_t i = 0; i < x.computed.size(); ++i) {
      const double apart = (x.computed[i] - y.computed[i]) / x.sigma_deg[i % 3];
      sum += apart * apart;
    }
  }
  return sum;
}

// Whether the effect of `k` lies outside its bounds at the point fit, its
// errors taken as nil (Implausible's allowances, such as a roll damping's
// two errors of driving, all spent).
bool OutsideAtThePoint(const Contender& k) {
  FitResult point = k.fit;
  for (ParameterEstimate& e : point.parameters) e.standard_error = 0.0;
  return !Implausible(TermsOf(*k.candidate), k.candidate->c, point).empty();
}

// Between twins that earned their place first and second (the same fitted
// motion, MotionApart), the one within its bounds at the point fit leads
// when the other is not: the record cannot choose, the physics can. On draw
// 145's Table 6 record with a bearing moment, a calibration error and a roll
// torque (sigma: auto) a roll damping led its twin, the roll torque, by
// 0.001 of BIC at Cl_p = +6.1e-6 +- 3.7e-6 (a damping that drives the roll,
// within its two errors); with each later effect beside it that sign grew
// determined and refused them all, and the record ended unexplained with
// nothing named.
void PlausibleTwinFirst(const std::vector<Contender>& contenders,
                        std::vector<int>* earned) {
  if (earned->size() < 2) return;
  const Contender& best = contenders[(*earned)[0]];
  const Contender& twin = contenders[(*earned)[1]];
  if (!(MotionApart(best.fit, twin.fit) < kSearchBicTolerance) ||
      !OutsideAtThePoint(best) || OutsideAtThePoint(twin)) {
    return;
  }
  VLOG(1) << best.fit.name << ": " << twin.record.effect << " leads its twin "
          << best.record.effect << ", outside its bounds at the point fit";
  std::swap((*earned)[0], (*earned)[1]);
}

// The round's best that earned its place (contenders[earned[0]]) taken as
// the next step, with its rivals (Rivals; `probe`, when fitted, among
// them): a tie opens there when it has one, and *notes records a near tie
// and a first step taken alone.
void TakeBest(const std::vector<Contender>& contenders,
              const std::vector<int>& earned,
              const std::vector<Candidate>& candidates,
              const Contender* probe,
              const DiagnoseOptions& options,
              SearchNotes* notes,
              SearchState* s) {
  const Contender& best = contenders[earned[0]];
  std::vector<CandidateFit> step_rivals =
      Rivals(contenders, earned[0], probe, s->data, options);
  if (s->tie < 0 && !step_rivals.empty()) {
    // Go on with the best: whether the rest of the record is explained
    // decides between `ambiguous` and `not_explained`.
    s->tie = static_cast<int>(s->d.steps.size());
    if (earned.size() > 1) {
      notes->tied_first = best.record.effect;
      notes->tied_first_twin =
          MotionApart(best.fit, contenders[earned[1]].fit) <
          kSearchBicTolerance;
    }
  }
  if (NearTie(contenders, earned, options)) {
    notes->led_steps.push_back(best.record.effect);
  }
  if (s->d.steps.empty() && step_rivals.empty()) {
    notes->first_alone = best.record.effect;
  }
  s->rivals.push_back(RollPartRivals(
      WiderRivals(std::move(step_rivals), contenders, earned[0], options),
      contenders,
      earned[0],
      candidates,
      s->fit,
      s->data,
      s->d.steps,
      s->rivals));
  s->current = best.candidate->c;
  s->fit = best.fit;
  s->models.push_back(s->current);
  s->check = TakeStep(best, contenders, candidates, options, &s->d);
  if (probe != nullptr && !(probe->bic < best.bic)) {
    s->d.steps.back().outside_alike = probe->record;
    s->d.steps.back().outside_alike_bic = probe->bic - best.bic;
    s->d.steps.back().outside_alike_model = probe->fit.parameters;
  }
}

// A round of the search on `candidates`: the best few refitted
// (Contenders), judged (Earned) and weighed against the probes
// (WeighProbes); a joint set adopted (Jointly, TakeJointSteps) or the best
// that earned its place taken (TakeBest). False when the search ends:
// nothing earned its place, or a probe outdid the catalog (RejectRound).
bool SearchRound(const std::vector<Candidate>& candidates,
                 const DiagnoseOptions& options,
                 SearchNotes* notes,
                 SearchState* s) {
  std::vector<Contender> minor;
  std::vector<Contender> contenders =
      Contenders(candidates, s->fit, s->data, options, &minor);
  NoteContended(contenders, minor, s);
  OutOfSample out_of_sample(s->current, s->fit, options);
  std::vector<const Effect*> added;
  for (const DiagnosisStep& step : s->d.steps) {
    added.push_back(FindEffect(step.effect));
  }
  std::vector<int> earned =
      Earned(s->fit, added, options, &out_of_sample, &contenders);
  PlausibleTwinFirst(contenders, &earned);
  notes->bounded_lead |= BoundedLead(contenders, earned);
  NoteBlocker(contenders, earned, options, notes);
  std::vector<Candidate> probes;
  Contender probe;
  const bool probed = WeighProbes(s->current,
                                  s->fit,
                                  s->data,
                                  options,
                                  earned,
                                  &out_of_sample,
                                  &probes,
                                  &probe,
                                  &contenders,
                                  &s->d);
  const bool outside = !s->d.outside_catalog.effect.empty();
  if (probed && outside) {
    notes->probe_case = probe.candidate->c;
    notes->probe_fit = probe.fit;
  }
  // A joint set draws on the round's lesser refits too (after the
  // contenders, which keep their indices): on a coning run with a body
  // yaw asymmetry (added), a nonlinear damping and a tunnel stiffness
  // (suite draw 18), the damping dragged Cn_r and was the round's only
  // contender, the stiffness lowering BIC by 3 beside it alone.
  std::vector<Contender> pooled = contenders;
  pooled.insert(pooled.end(), minor.begin(), minor.end());
  JointSet joint;
  if (!outside && Jointly(s->current,
                          s->fit,
                          s->data,
                          options,
                          added,
                          &out_of_sample,
                          candidates,
                          earned,
                          &pooled,
                          &joint)) {
    const std::vector<Contender> with = WithMembers(contenders, pooled, &joint);
    s->check = TakeJointSteps(joint, with, pooled, candidates, options, s);
    return true;
  }
  if (earned.empty() || outside) {
    RejectRound(contenders, earned, probe, s);
    return false;
  }
  TakeBest(contenders,
           earned,
           candidates,
           probed ? &probe : nullptr,
           options,
           notes,
           s);
  return true;
}

// The search's answer once its rounds are done: the final model settled
// (SettleFinalModel), back in the user's program where it can be
// (BackToSymmetric), reported, and its error bars widened for a tie or a
// probe alike; what is left to do is AnswerErrorBars'.
void SettleAnswer(const DiagnoseOptions& options, SearchState* s) {
  Diagnosis& d = s->d;
  const std::vector<TimeHistory>& data = s->data;
  // A probe that outdoes the catalog, even past the noise level
  // (noise_held), is structure the catalog lacks: the record is not
  // explained by it.
  if (!d.outside_catalog.effect.empty()) s->check.at_noise_level = false;
  d.partial_fit = d.fits.size() - 1;
  d.final = SettleFinalModel(s->quiet,
                             data,
                             options,
                             s->models,
                             s->tie,
                             s->rivals,
                             s->check,
                             &d,
                             &s->current);
  BackToSymmetric(s->quiet, data, &d, &s->current);
  // The final model and the partial one, when it is another.
  std::vector<const Case*> reported = {&s->current};
  std::vector<FitResult*> fits = {&d.fits[d.final_fit]};
  if (!d.partial.empty() && d.partial_fit != d.final_fit) {
    reported.push_back(&s->models[d.partial_fit]);
    fits.push_back(&d.fits[d.partial_fit]);
  }
  ReportedAll(reported, data, fits);
  WidenForTie(options, &d);
  WidenForOutsideAlike(&d);
}

// The settled answer of the search `s` (SettleAnswer; moved from), with
// the effects it cannot exclude beside it (FindNotExcluded), a step that
// effects in its place outdo (notes->outdone, with the answer that has
// them tied), then the error bars widened and the verdict (Concluded).
Diagnosis AnswerErrorBars(const Case& c,
                          const DiagnoseOptions& options,
                          SearchNotes* notes,
                          SearchState s) {
  Diagnosis& d = s.d;
  const std::vector<TimeHistory>& data = s.data;
  // What the search was run without is tried beside its model too: the
  // record may not exclude it there (DiagnoseOptions::searched_without;
  // catalog effects only, as contenders are).
  for (const std::string& id : options.searched_without) {
    const Effect* e = FindEffect(id);
    if (e == nullptr) continue;
    if (std::find(s.contended.begin(), s.contended.end(), e) ==
        s.contended.end()) {
      s.contended.push_back(e);
    }
  }
  std::vector<const Effect*> open_ridge;
  FindNotExcluded(s.contended,
                  s.lesser,
                  s.models,
                  s.current,
                  data,
                  options,
                  &d,
                  &open_ridge);
  // A step outdone (by ambiguity_bic or more) by one effect in its place
  // stands in a tie with it only where the search without it does not
  // explain the record better (DiagnoseFrom): the answer with the tie is
  // kept aside. Not so for a set in its place: two or three effects beat
  // a true body yaw asymmetry by 10 or more on draws 22 and 25's coning
  // runs, and the asymmetry is named.
  notes->outdone =
      FindSetReplacements(s.models, s.current, data, options, open_ridge, &d);
  if (notes->outdone.empty()) {
    Diagnosis tie;
    notes->outdone =
        FindSingleReplacement(s.models, s.current, data, options, &d, &tie);
    if (!notes->outdone.empty()) {
      notes->outdone_tie =
          Concluded(c, s.quiet, s.current, data, options, std::move(tie));
    }
  }
  return Concluded(c, s.quiet, s.current, data, options, std::move(d));
}

// The forward search's rounds from `nominal`, the fit of `c`, with
// `options`' catalog, to its settled answer (SettleAnswer); *notes gets
// what else it found.
SearchState SettledSearch(const Case& c,
                          const FitResult& nominal,
                          const DiagnoseOptions& options,
                          SearchNotes* notes) {
  *notes = SearchNotes();
  SearchState s = StartSearch(c, nominal, options);
  // At the noise level with sigma given, one round for the near twins alone
  // (HiddenTwins), scored here once.
  std::vector<Candidate> twins;
  if (s.check.at_noise_level && !options.noise_held) {
    twins = HiddenTwins(
        ScoredCandidates(s.current, s.fit, options), s.fit, options);
  }
  const bool hidden = !twins.empty();
  // At the noise level the search goes on only for a round it may add in.
  const bool past = !options.past_noise.empty();
  const auto on_at_noise = [&](int step) {
    return options.noise_held || past || (hidden && step == 0);
  };
  for (int step = 0; step < options.max_steps &&
                     (!s.check.at_noise_level || on_at_noise(step));
       ++step) {
    const bool polished = PolishRound(options, &s);
    if (polished && s.check.at_noise_level && !on_at_noise(step)) break;
    // The twins' round scores the fit the twins were found at, unless
    // Polish moved it.
    std::vector<Candidate> candidates;
    if (!RoundCandidates(step == 0,
                         hidden && step == 0 && !polished,
                         &twins,
                         options,
                         s,
                         &candidates) ||
        !SearchRound(candidates, options, notes, &s)) {
      break;
    }
  }
  // The last step's effects beside a step in its other form.
  ReformRound(options, &s);
  SettleAnswer(options, &s);
  return s;
}

}  // namespace

// What a search left undone (SearchUnfinished): its settled state and
// what AnswerErrorBars needs besides.
struct UnfinishedSearch {
  Case c;
  DiagnoseOptions options;
  SearchState s;
};

Diagnosis Search(const Case& c,
                 const FitResult& nominal,
                 const DiagnoseOptions& options,
                 SearchNotes* notes) {
  return AnswerErrorBars(
      c, options, notes, SettledSearch(c, nominal, options, notes));
}

Diagnosis SearchUnfinished(const Case& c,
                           const FitResult& nominal,
                           const DiagnoseOptions& options,
                           SearchNotes* notes) {
  SearchState s = SettledSearch(c, nominal, options, notes);
  Diagnosis d = s.d;
  d.final_case = FinalCase(c, s.current, d.FinalFit());
  Conclude(&d);
  notes->unfinished = std::make_shared<UnfinishedSearch>(
      UnfinishedSearch{c, options, std::move(s)});
  return d;
}

Diagnosis Finished(Diagnosis d, SearchNotes* notes) {
  if (notes->unfinished == nullptr) return d;
  std::shared_ptr<UnfinishedSearch> u = std::move(notes->unfinished);
  CHECK(d.steps.size() == u->s.d.steps.size() &&
        d.fits.size() == u->s.d.fits.size())
      << "an answer other than the unfinished search's";
  return AnswerErrorBars(u->c, u->options, notes, std::move(u->s));
}

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

// A channel's model-free noise level (DataNoiseDeg) from a segment's
// nominal fit: the least of the data's and its residual's. High-order
// differences leave a little of a motion sampled 8-10 times per cycle;
// the residual's hold the noise and the small part the model misses (on a
// 3-s run at 9 points per cycle, 6.3 deg, the pitch data's level was
// 0.0122-0.0150 deg against a true 0.01, its residual's 0.0089-0.0117).
double ModelFreeNoiseDeg(const SegmentFit& s, int ch) {
  return std::min(DataNoiseDeg(s.data.channel(ch)),
                  DataNoiseDeg(ChannelResidual(s, ch)));
}

// The least level channel `ch` of `fit`'s segments is held at: where its
// readings lie on a grid (ReadingStepDeg), the rounding's standard
// deviation, the step over sqrt(12), else 0. A reading moving across its
// counts errs by that much whatever the fit; held lower, the rounding's
// sawtooth reads as structure. On draw 146's 4-s run with its roll read in
// 2-deg counts at 1.79 deg a sample (the colored errors' `quantized`), roll
// was held at 0.373 deg, the sawtooth's period near the pitch period, and
// a product of inertia that took part of it lowered BIC by 10.3 and was
// named (`explained`) on a record with no effect.
double RoundingLevelDeg(const FitResult& fit, int ch) {
  double level = 0.0;
  for (const SegmentFit& s : fit.segments) {
    level = std::max(level, ReadingStepDeg(s.data, ch) / std::sqrt(12.0));
  }
  return level;
}

// How far below the held level a fit of the search must leave a channel
// for the level to be held again at that fit's (HeldAgain), and how far
// above it.
constexpr double kHeldTooHigh = 1.3;
constexpr double kHeldTooLow = 1.3;

// How many times the search runs again at levels held again.
constexpr int kHeldRounds = 2;

// Channel `ch`'s RMS residual in `fit` taken over the residuals' degrees
// of freedom (sqrt(n / (n - p)) on the whole fit); infinity without one.
double CorrectedResidual(const FitResult& fit, int ch) {
  const int n = 3 * fit.points;
  if (n <= fit.free_parameters) return std::numeric_limits<double>::infinity();
  return fit.rms_residual_deg[ch] *
         std::sqrt(1.0 * n / (n - fit.free_parameters));
}

// The least RMS residual of channel `ch` any fit of the search `d` left,
// taken over the residuals' degrees of freedom (sqrt(n / (n - p)) on the
// whole fit); *at is that fit (nullptr when none has a degree of freedom).
double LeastResidual(const Diagnosis& d, int ch, const FitResult** at) {
  double least = std::numeric_limits<double>::infinity();
  *at = nullptr;
  for (const FitResult& fit : d.fits) {
    const double rms = CorrectedResidual(fit, ch);
    if (rms < least) {
      least = rms;
      *at = &fit;
    }
  }
  return least;
}

// The catalog effects `d`, an answer that leaves the record unexplained,
// took or refused after they lowered BIC by min_bic_drop or more (its
// partial steps and its rejected contenders), fitted together from its
// final model into *fit; false when there are fewer than two or the fit
// fails. A level held too high shows in no single fit of such a search:
// on a 3-s run with a bearing moment, a cubic calibration error and a roll
// torque (draw 105) pitch was held at 0.0225 deg (true 0.01: the cube's
// third harmonic, at a third of the sampling rate, passes the model-free
// estimate for noise); each contender left 0.022, a pressure-drift probe
// 0.019, and at that level the probe explained the record.
bool FittedTogether(const Diagnosis& d,
                    const DiagnoseOptions& options,
                    FitResult* fit) {
  if (d.verdict != Verdict::kNotExplained) return false;
  std::vector<const Effect*> effects;
  const auto take = [&](const std::string& id, double bic_drop) {
    const Effect* e = FindEffect(id);
    if (e != nullptr && bic_drop >= options.min_bic_drop &&
        std::find(effects.begin(), effects.end(), e) == effects.end()) {
      effects.push_back(e);
    }
  };
  for (const DiagnosisStep& s : d.partial) take(s.effect, s.bic_drop);
  for (const CandidateFit& k : d.rejected) take(k.effect, k.bic_drop);
  if (effects.size() < 2) return false;
  Case together = CaseAtSolution(d.final_case, d.FinalFit());
  // Its residual is all that is read: no profile error bars (fit.h,
  // CheckRidges, WidenTradedStiffness), which would only cost refits.
  together.solver.profile_ridges = false;
  for (const Effect* e : effects) {
    Case with;
    std::vector<std::string> added;
    if (CandidateCase(together, *e, &with, &added)) together = std::move(with);
  }
  return FitFrom(together,
                 d.FinalFit(),
                 FittedData(d.FinalFit()),
                 "the effects that lowered BIC together",
                 fit);
}

// Whether channel `ch` of `fit` has a residual whose lag-1
// autocorrelation is within what noise reaches (CheckResiduals).
bool WhiteChannel(const FitResult& fit,
                  int ch,
                  const DiagnoseOptions& options) {
  const ResidualCheck check = CheckResiduals(fit, options);
  return check.lag1[ch] < check.whiteness_limit;
}

// Whether `fit`, leaving channel `ch` at `residual` (its RMS over the
// fit's degrees of freedom), shows the level held there, `level`, too
// low: kHeldTooLow or more below a white residual (HeldAgain,
// HeldAgainByTheProbe).
bool ShowsHeldTooLow(const FitResult& fit,
                     int ch,
                     double residual,
                     double level,
                     const DiagnoseOptions& options) {
  return residual >= kHeldTooLow * level && WhiteChannel(fit, ch, options);
}

// Channel `ch`'s residual in `fit` over its degrees of freedom
// (CorrectedResidual), read no higher than the middle of the three
// channels': one instrument reads the three, and a channel far above the
// other two holds a structure of its own, not the noise.
double ReadNoHigherThanTheMiddle(const FitResult& fit, int ch) {
  std::array<double, 3> sorted;
  for (int k = 0; k < 3; ++k) sorted[k] = CorrectedResidual(fit, k);
  const double own = sorted[ch];
  std::sort(sorted.begin(), sorted.end());
  return std::min(own, sorted[1]);
}

// Whether the last partial step of `d`, a search that leaves the record
// unexplained, leaves white residuals just past the noise level's limit
// (within kHeldTooLow of it) and channel `ch` kHeldTooLow or more above
// `level`, the level held there, read no higher than the middle of the
// three channels' residuals (each over the fit's degrees of freedom); if
// so, *residual is that reading. HeldAgain reads a level held low only at
// the noise level; a catalog effect that whitens the record shows it too.
// On draw 147's 3-s run with a roll torque (sigma: auto) pitch and yaw
// were held at 0.0053 and 0.0061 deg (true 0.01); the torque left 0.0101
// and 0.0097, white, at a probable error of 1.60 against a limit of 1.56,
// and the answer was `not_explained` with nothing named.
// Just past the limit: far past it a white residual is a structure the
// whiteness test misses. On draw 142's 3-s run with a lag of the pitch
// reading (outside the catalog) a Magnus moment left pitch at 0.033 deg,
// white, at a probable error of 2.22 against a limit of 1.52 (held at
// 0.0095); held there, the lag passed for the Magnus moment's look-alike.
// No higher than the middle channel: one instrument reads the three, and a
// channel far above the other two holds a structure of its own. On draws
// 146 and 147 a pitch reading's lag and an even calibration error left
// pitch at 0.022-0.028 deg beside 0.009-0.012 in roll and yaw, within
// that limit, and held there, both passed for catalog look-alikes.
bool HeldLowByWhiteSteps(const Diagnosis& d,
                         int ch,
                         double level,
                         double* residual) {
  if (d.verdict != Verdict::kNotExplained || d.partial.empty()) return false;
  const DiagnosisStep& last = d.partial.back();
  const ResidualCheck& after = last.after;
  if (!after.white || after.at_noise_level || last.fit_after < 0 ||
      after.probable_error > kHeldTooLow * after.noise_limit) {
    return false;
  }
  *residual = ReadNoHigherThanTheMiddle(d.fits[last.fit_after], ch);
  // Every channel is white there already (after.white, the step's own
  // residual check): only the level is left to read.
  return *residual >= kHeldTooLow * level;
}

// Holds channel `ch` of *held again at `level` (deg), which `source`
// showed.
void HoldAgainAt(
    const Case& c, int ch, double level, const char* source, Case* held) {
  VLOG(1) << c.name << ": " << ChannelName(ch) << " noise held again at "
          << source << level << " deg (" << held->sigma[ch] << " before)";
  held->sigma[ch] = level;
}

// Whether the search `d` found the record at the noise level, no model
// outside the catalog standing for it. With nothing added, its residuals
// perhaps dependent (Explains): a level held low hides what depends on it
// (a cube of the pitch reading in a yaw level held low). With effects named
// or tied (explained or ambiguous), since the 84th session: a level held
// low there weighs the channel's fall past what its errors warrant, and the
// effects' BIC with it. On draw 162's 3-s run with no effect and reading
// errors that are not white (an AR(1) error of lag-1 autocorrelation 0.6
// beside white noise, 0.014 deg in all; the model-free level reads their
// fast part) yaw was held at 0.0079 deg and every fit left it above 0.0118,
// white; a tunnel damping whose BIC drop of 21.7 lay in roll and yaw was
// named.
bool AtTheNoiseInTheCatalog(const Diagnosis& d) {
  return d.outside_catalog.effect.empty() && d.final.at_noise_level;
}

// Whether some fit of the search `d` (held at held->sigma) left an auto
// channel's residual (LeastResidual; where `d` leaves the record
// unexplained, the effects it found fitted together too, FittedTogether)
// below the held level by kHeldTooHigh or more, or, where `d` found the record
// at the noise level (with or without effects named, AtTheNoiseInTheCatalog),
// every fit left it above by kHeldTooLow or more, white
// (its lag-1 autocorrelation within what noise reaches); if so, held->sigma
// holds that channel at the least level. Too high: the model-free level takes
// structure near the Nyquist frequency for noise: a calibration error's cube
// puts the pitch motion's third harmonic there at 8 points per cycle, and on a
// pair of 3-s runs with a bearing moment, that calibration and a roll torque
// the pitch level was held at 0.0218 deg while the three fitted together left
// 0.0094 (true noise 0.01). Weighed at 0.0218 the calibration's other form and
// a gain error of the pitch reading, 0.019 deg, passed for the noise. Too low:
// a noise draw short of power at high frequencies holds a channel low by its
// differences, and the probable error it inflates blurs every other channel's
// evidence (the score is in units of E^2). On a 3-s run of 37 samples with a
// cubic error of the pitch reading
// (tests/data/short_calibration_in_pitch_varied101.yaml) yaw was held at
// 0.0053 deg (true 0.01; its residual 0.0108, lag-1 0.29), E was 1.48,
// and the calibration's score, 14.5 at 2 terms, missed the 10 of BIC it
// needed: `noise_level`, Cm_alpha 10.8 of its errors off. A colored error's
// slow part escapes the differences too, and a level held under it puts a
// false effect past the BIC margin (AtTheNoiseInTheCatalog). Only at the noise
// level: a channel a missed effect holds above its level is the record's
// structure, and a level raised to it would hide it; or where the search
// leaves the record unexplained, its partial steps whiten it just past the
// limit (HeldLowByWhiteSteps).
bool HeldAgain(const Case& c,
               const Diagnosis& d,
               const DiagnoseOptions& options,
               Case* held) {
  bool again = false;
  FitResult together;
  const bool fitted = FittedTogether(d, options, &together);
  for (int ch = 0; ch < 3; ++ch) {
    if (!c.sigma_auto[ch]) continue;
    const FitResult* at = nullptr;
    double least = LeastResidual(d, ch, &at);
    if (at == nullptr) continue;
    const double level = held->sigma[ch];
    if (fitted) {
      const double joint = CorrectedResidual(together, ch);
      if (joint * kHeldTooHigh <= level) least = std::min(least, joint);
    }
    least = std::max(least, RoundingLevelDeg(*at, ch));
    const bool too_high = least * kHeldTooHigh <= level;
    const bool too_low = AtTheNoiseInTheCatalog(d) &&
                         ShowsHeldTooLow(*at, ch, least, level, options);
    if (too_high || too_low) {
      HoldAgainAt(c, ch, least, "", held);
      again = true;
      continue;
    }
    double white = 0.0;
    if (HeldLowByWhiteSteps(d, ch, level, &white)) {
      HoldAgainAt(c, ch, white, "the partial steps' ", held);
      again = true;
    }
  }
  return again;
}

// Whether the model of the probe outside the catalog that outdid the
// search `d` (notes.probe_fit), which reaches the noise level at the held
// levels (Diagnosis::outside_at_noise_level), leaves an auto channel white
// and kHeldTooLow or more above its held level; if so, held->sigma holds
// it there, read no higher than the middle channel (HeldAgain's low
// level, read where the verdict is not the noise level's but a model
// outside the catalog explains the record). A level
// held low inflates every contender's evidence in that channel, the
// flexible probe's most: on draw 116's 3-s coning run with a bearing
// moment at 2 deg, pitch was held at 0.0058 deg (true 0.01), a pressure
// drift came 12.1 in BIC below the bearing moment, and the answer was
// `not_explained` with nothing named; the drift's model left pitch
// 0.0081 over its degrees of freedom (0.0078 RMS), white; the true model's
// own fit 0.0082. Held there, the two tie. No higher than the middle
// channel: a probe that misses a catalog effect leaves that effect's
// channel above the noise, white to a test of 40 samples. On draw 156's
// 3-s run with a tunnel stiffness, a nonlinear damping and a body
// asymmetry a lag of the pitch reading left roll, pitch and yaw at 0.0124,
// 0.0159 and 0.0123 deg (held at 0.0085, 0.0108, 0.0085; the true model's
// own fit 0.0108, 0.0089, 0.0090). Held at the pitch's 0.0159 a tunnel
// damping passed for the nonlinear damping, and was named.
bool HeldAgainByTheProbe(const Case& c,
                         const Diagnosis& d,
                         const SearchNotes& notes,
                         const DiagnoseOptions& options,
                         Case* held) {
  if (!d.outside_at_noise_level || notes.probe_fit.parameters.empty()) {
    return false;
  }
  bool again = false;
  for (int ch = 0; ch < 3; ++ch) {
    if (!c.sigma_auto[ch]) continue;
    const double residual = ReadNoHigherThanTheMiddle(notes.probe_fit, ch);
    if (ShowsHeldTooLow(
            notes.probe_fit, ch, residual, held->sigma[ch], options)) {
      HoldAgainAt(c, ch, residual, "the probe's ", held);
      again = true;
    }
  }
  return again;
}

// Whether `again`, the search at levels held again, is taken over `last`,
// the one before: unless it leaves the record short of the noise where
// `last` reached its own (the fit that showed the lower level was not
// found again).
bool TakenAgain(const Diagnosis& again, const Diagnosis& last) {
  return again.final.at_noise_level || !last.final.at_noise_level;
}

// The diagnosis at the levels *held, or, where its search's own answer
// already holds them again (HeldAgain), at the levels held again (*held
// those, *round 1): that search's second thoughts would be thrown away.
// The first search's are thought only where the search at the levels
// held again is not taken over the first (TakenAgain; *round then
// kHeldRounds). On draw
// 105's 3-s run with a bearing moment, a cubic calibration error and a
// roll torque (sigma: auto) the pitch level is held again; the second
// thoughts at the first level had taken 1.9 of the record's 6.3 s. A
// probe's model at the noise level holds the levels again too
// (HeldAgainByTheProbe).
Diagnosis FirstHeld(const Case& c,
                    const DiagnoseOptions& past,
                    Case* held,
                    int* round) {
  const FitResult fit = Fit(*held);
  SearchNotes notes;
  Diagnosis searched = FirstSearch(*held, fit, past, &notes);
  Case next = *held;
  if (!HeldAgain(c, searched, past, &next) &&
      !HeldAgainByTheProbe(c, searched, notes, past, &next)) {
    return Rethought(*held, fit, past, std::move(notes), std::move(searched));
  }
  Diagnosis again = DiagnoseFrom(next, Fit(next), past);
  if (!TakenAgain(again, searched)) {
    *round = kHeldRounds;
    return Rethought(*held, fit, past, std::move(notes), std::move(searched));
  }
  *held = next;
  *round = 1;
  return again;
}

// sigma: auto, whose fits each set their own weights (each channel's RMS
// residual, noise_relaxation.h): the search's BICs would not compare, and
// every fit's probable error would be 1, its level no test. The noise is
// estimated once and held for the search: each channel's the lesser of the
// nominal fit's RMS residual and the model-free noise level
// (ModelFreeNoiseDeg), pooled over the segments. The RMS alone takes in what
// the model misses: a body asymmetry left the roll residual at 3.2 times
// the noise on a 3-s run, and held there it weighed roll so little that
// a Magnus moment and a tunnel stiffness were named instead. The data's
// level alone took in some of the motion: on a 3-s run of another body
// (tools/diagnose_suite --vary-conditions, draw 79) a pitch reading's lag
// held at 1.22 times the true noise in pitch left 2.0 times that noise
// there, under the held level's limit, and a Magnus moment and a body
// asymmetry were named. The level's limit widens by that estimate's
// spread (CheckResiduals), and the search goes on past it while an effect
// earns its place (noise_held). On a 3-s run with a Magnus moment at 1.3
// times the noise, the fit with sigma: auto had left residuals as white as
// noise at its own level, and the diagnosis had said `noise_level`. The
// final config keeps sigma: auto for its rerun.
Diagnosis WithNoiseHeld(const Case& c,
                        const FitResult& relaxed,
                        const DiagnoseOptions& options) {
  Case held = c;
  for (int ch = 0; ch < 3; ++ch) {
    if (!c.sigma_auto[ch]) continue;
    double rms = 0.0, data = 0.0;
    int n = 0;
    for (const SegmentFit& s : relaxed.segments) {
      const double free = ModelFreeNoiseDeg(s, ch);
      rms += s.data.size() * s.sigma_deg[ch] * s.sigma_deg[ch];
      data += s.data.size() * free * free;
      n += s.data.size();
    }
    CHECK_GT(n, 0);
    held.sigma[ch] = std::max(std::sqrt(std::min(rms, data) / n),
                              RoundingLevelDeg(relaxed, ch));
    held.sigma_auto[ch] = false;
  }
  DiagnoseOptions past = options;
  past.noise_held = true;
  int round = 0;
  Diagnosis d = FirstHeld(c, past, &held, &round);
  for (; round < kHeldRounds && HeldAgain(c, d, past, &held); ++round) {
    // The search again at the levels held again (TakenAgain). A second
    // round holds what the first one's effects showed (the pitch level
    // once the calibration above is fitted).
    Diagnosis again = DiagnoseFrom(held, Fit(held), past);
    if (!TakenAgain(again, d)) break;
    d = std::move(again);
  }
  d.final_case.sigma_auto = c.sigma_auto;
  return d;
}

}  // namespace

namespace {

// Effects declared absent must be the catalog's or its probes': a
// misspelt id would silently leave the effect in.
void CheckAbsent(const DiagnoseOptions& options) {
  for (const std::string& id : options.absent) {
    if (FindEffect(id) != nullptr || FindProbe(id) != nullptr) continue;
    auto ids = [](const std::vector<Effect>& effects) {
      std::string text;
      for (const Effect& e : effects) text += " " + e.id;
      return text;
    };
    throw InputError(
        "effects known absent (--absent): '" + id +
        "' is not an effect of the catalog (one of:" + ids(EffectCatalog()) +
        ") nor a probe (one of:" + ids(Probes()) + ")");
  }
}

// The free shared error bars of `fit` set back to the model's own
// (`own`: Diagnosis::model_standard_errors) where a widening changed them;
// returns them as they were.
std::vector<ParameterEstimate> ToOwnErrorBars(
    const std::map<std::string, double>& own, FitResult* fit) {
  std::vector<ParameterEstimate> widened = fit->parameters;
  for (ParameterEstimate& e : fit->parameters) {
    const auto it = own.find(e.name);
    if (!e.segment.empty() || it == own.end() || !(e.standard_error > 0.0)) {
      continue;
    }
    e.rms_error *= it->second / e.standard_error;
    e.standard_error = it->second;
  }
  return widened;
}

// The final model's error bars of the stiffness its bearing moment trades
// with on its ridge, widened to their profiles' (WidenTradedStiffness,
// fit.h), once the diagnosis has decided: its decisions read the error bars
// of the models it reports, and profiling each of those took draw 105's
// 3-s run with a bearing moment, a calibration error and a roll torque from
// 4.8 to 42 s (1267 frozen refits where there had been 114). The final
// values (a tie's or an effect not excluded may have widened them more)
// keep the wider; the model's own error is the profile's.
void StiffnessOnTheRidge(Diagnosis* d) {
  FitResult& fit = d->fits[d->final_fit];
  // At the noise levels the fit had: under sigma: auto, final_case holds
  // the levels held (WithNoiseHeld), flagged auto again for final.yaml.
  Case c = d->final_case;
  c.sigma_auto = {{false, false, false}};
  // From the model's own error bars: a profile steps out from the error
  // bar it is given, and on a curved ridge one already widened (by a tie,
  // an effect not excluded, a probe alike) starts it elsewhere and ends it
  // elsewhere. On draw 149's 3-s run with a bearing moment fading at half
  // a degree Cm_alpha's profile was 0.056 from its own 0.00048 and 0.019
  // from 0.0074, a pressure-drift probe's model having widened it.
  const std::vector<ParameterEstimate> widened =
      ToOwnErrorBars(d->model_standard_errors, &fit);
  const std::vector<std::string> profiled =
      WidenTradedStiffness(c, FittedData(fit), &fit);
  for (size_t i = 0; i < fit.parameters.size(); ++i) {
    ParameterEstimate& e = fit.parameters[i];
    const auto own = d->model_standard_errors.find(e.name);
    if (own != d->model_standard_errors.end() &&
        std::find(profiled.begin(), profiled.end(), e.name) != profiled.end()) {
      own->second = e.standard_error;
    }
    e.standard_error = std::max(e.standard_error, widened[i].standard_error);
    e.rms_error = std::max(e.rms_error, widened[i].rms_error);
  }
  for (const std::string& name : profiled) {
    const ParameterEstimate* e = SharedEstimate(fit, name);
    for (ParameterEstimate& f : d->final_parameters) {
      if (f.name != name) continue;
      f.standard_error = std::max(f.standard_error, e->standard_error);
      f.rms_error = std::max(f.rms_error, e->rms_error);
    }
  }
}

// `c` with the search step set (SolverOptions::search_step) from `first`,
// its fit at the config's step: the coarsest step whose motion there stays
// within a 16th of kStepChiSquare, so that the models the search fits,
// whose effects change the motion little, keep within kStepChiSquare (the
// motion's integration error grows as the step to the 8th power in it: a
// step twice as coarse is 256 times further).
Case AtSearchStep(const Case& c,
                  const FitResult& first,
                  const DiagnoseOptions& options) {
  Case searched = c;
  if (!options.coarse_search || c.solver.method == FitMethod::kFilterError) {
    return searched;
  }
  const double step =
      CoarsestStep(c, FittedData(first), first, kStepChiSquare / 16.0);
  if (step > c.solver.step) searched.solver.search_step = step;
  return searched;
}

}  // namespace

Diagnosis Diagnose(const Case& c, const DiagnoseOptions& options) {
  CheckAbsent(options);
  // The first fit is the config's own, at its step: the search's fits at
  // a coarser one are within kStepChiSquare of it.
  const FitResult first = Fit(c);
  const Case searched = AtSearchStep(c, first, options);
  Diagnosis d = c.AnySigmaAuto() ? WithNoiseHeld(searched, first, options)
                                 : DiagnoseFrom(searched, first, options);
  StiffnessOnTheRidge(&d);
  d.search_step = std::max(searched.solver.step, searched.solver.search_step);
  d.final_case.solver.search_step = 0.0;
  return d;
}

}  // namespace fit3dof
