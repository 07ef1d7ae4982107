// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The diagnosis loop (diagnose.h): fit, check the residuals, score every
// catalog effect not yet in the model, refit the best few, add the one that
// lowers BIC most, repeat. The pieces: effect_catalog.cc, score_test.cc,
// residual_check.cc, diagnosis_report.cc.

#include "fit3dof/diagnose.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "diagnose_internal.h"

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

bool Wanted(const DiagnoseOptions& options, const Effect& e) {
  return options.effects.empty() ||
         std::find(options.effects.begin(), options.effects.end(), e.id) !=
             options.effects.end();
}

// Every applicable effect scored at the fit's solution, best first.
std::vector<Candidate> ScoredCandidates(const Case& current,
                                        const FitResult& fit,
                                        const DiagnoseOptions& options) {
  const Case at = CaseAtSolution(current, fit);
  // The samples the fit used (selected, noise added, wild points
  // screened): read once, not once per candidate.
  std::vector<TimeHistory> data;
  for (const SegmentFit& segment : fit.segments) data.push_back(segment.data);
  std::vector<Candidate> candidates;
  for (const Effect& e : EffectCatalog()) {
    if (!Wanted(options, e)) continue;
    Candidate k{&e, Case(), {}, {}};
    if (!CandidateCase(at, e, &k.c, &k.added)) continue;
    k.score = Score(k.c, k.added, e.id, data);
    if (k.score.dof > 0) candidates.push_back(std::move(k));
  }
  std::sort(candidates.begin(),
            candidates.end(),
            [](const Candidate& a, const Candidate& b) {
              return a.score.score > b.score.score;
            });
  return candidates;
}

// Refits the best `options.refit` candidates; the index of the one with the
// lowest BIC below `bic_now` (its fit in *best_fit), or -1.
int BestRefit(const std::vector<Candidate>& candidates,
              const DiagnoseOptions& options,
              double bic_now,
              const std::string& name,
              FitResult* best_fit,
              double* best_bic) {
  int best = -1;
  *best_bic = bic_now;
  for (int i = 0; i < std::min<int>(options.refit, candidates.size()); ++i) {
    FitResult r;
    try {
      r = Fit(candidates[i].c);
    } catch (const std::exception& e) {
      LOG(WARNING) << name << ": refit with " << candidates[i].effect->id
                   << " failed: " << e.what();
      continue;
    }
    const double bic = Bic(r);
    VLOG(1) << name << ": " << candidates[i].effect->id << " score "
            << candidates[i].score.score << ", BIC " << bic_now << " -> "
            << bic;
    if (bic < *best_bic) {
      *best_bic = bic;
      best = i;
      *best_fit = r;
    }
  }
  return best;
}

// The step that adds `chosen`: its parameters as fitted in `fit`.
DiagnosisStep Step(const Candidate& chosen, const FitResult& fit) {
  DiagnosisStep step;
  step.effect = chosen.effect->id;
  step.description = chosen.effect->description;
  step.score = chosen.score.score;
  for (const ParameterEstimate& e : fit.parameters) {
    if (std::find(chosen.added.begin(), chosen.added.end(), e.name) !=
        chosen.added.end()) {
      step.parameters.push_back(e);
    }
  }
  return step;
}

std::string Verdict(const ResidualCheck& check) {
  if (check.at_noise_level) return "residuals at noise level";
  char verdict[256];
  std::snprintf(verdict,
                sizeof(verdict),
                "residuals remain above the noise level (probable error %.3g, "
                "lag-1 autocorrelation theta %.2f psi %.2f) and no catalog "
                "effect explains them significantly",
                check.probable_error,
                check.lag1.theta,
                check.lag1.psi);
  return verdict;
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

}  // namespace

Diagnosis Diagnose(const Case& c, const DiagnoseOptions& options) {
  Diagnosis d;
  Case current = c;
  FitResult fit = Fit(current);
  d.fits.push_back(fit);
  d.initial = CheckResiduals(fit, options);
  ResidualCheck check = d.initial;
  for (int step = 0; step < options.max_steps && !check.at_noise_level;
       ++step) {
    const std::vector<Candidate> candidates =
        ScoredCandidates(current, fit, options);
    const double bic_now = Bic(fit);
    FitResult best_fit;
    double best_bic = bic_now;
    const int best =
        BestRefit(candidates, options, bic_now, c.name, &best_fit, &best_bic);
    if (best < 0 || bic_now - best_bic < options.min_bic_drop) break;
    DiagnosisStep record = Step(candidates[best], best_fit);
    for (const Candidate& k : candidates) record.ranking.push_back(k.score);
    record.bic_drop = bic_now - best_bic;
    current = candidates[best].c;
    fit = best_fit;
    d.fits.push_back(fit);
    check = CheckResiduals(fit, options);
    record.after = check;
    d.steps.push_back(record);
  }
  d.final = check;
  d.final_case = FinalCase(c, current, fit);
  d.verdict = Verdict(check);
  return d;
}

}  // namespace fit3dof
