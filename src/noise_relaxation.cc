// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Per-channel noise levels by relaxation (noise_relaxation.h).

#include "noise_relaxation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "assembly.h"
#include "fit3dof/input_error.h"
#include "format.h"
#include "stage_solver.h"

namespace fit3dof {
namespace {

constexpr int kMaxRounds = 10;
constexpr double kSettled = 0.01;  // relative change of every weight
// A floor for an estimated noise level (deg): a channel that fits exactly
// (a simulated record without noise) must not get an infinite weight.
constexpr double kFloorDeg = 1e-9;
// DataNoiseDeg's difference orders and floor.
constexpr int kLeastOrder = 2;
constexpr int kMostOrder = 8;
constexpr double kDataFloorDeg = 1e-4;

// Each segment's RMS residual per channel (deg) at `values`.
std::vector<ChannelValues> ResidualRms(const FitProblem& p,
                                       const std::vector<double>& values,
                                       const std::string& source) {
  const Assembly a = Assemble(p.segments,
                              p.free,
                              p.model,
                              values,
                              std::vector<double>(p.free.size(), 1.0));
  std::vector<double> residuals;
  double cost = 0.0;
  if (!a.problem->Evaluate(ceres::Problem::EvaluateOptions(),
                           &cost,
                           &residuals,
                           nullptr,
                           nullptr)) {
    throw InputError(source +
                     ": the motion cannot be integrated at the solution");
  }
  std::vector<ChannelValues> rms;
  size_t row = 0;
  for (const PreparedSegment& s : p.segments) {
    double sum[3] = {0.0, 0.0, 0.0};
    const int n = s.data.size();
    for (int i = 0; i < n; ++i) {
      for (int ch = 0; ch < 3; ++ch) {
        const double r = residuals[row++] * s.sigma[ch];
        sum[ch] += r * r;
      }
    }
    rms.push_back(
        {std::sqrt(sum[0] / n), std::sqrt(sum[1] / n), std::sqrt(sum[2] / n)});
  }
  return rms;
}

// Sets the auto channels' weights to `rms`; the largest relative change.
double Reweight(const std::array<bool, 3>& automatic,
                const std::vector<ChannelValues>& rms,
                std::vector<PreparedSegment>* segments) {
  double change = 0.0;
  for (size_t s = 0; s < segments->size(); ++s) {
    ChannelValues& sigma = (*segments)[s].sigma;
    for (int ch = 0; ch < 3; ++ch) {
      if (!automatic[ch]) continue;
      const double updated = std::max(rms[s][ch], kFloorDeg);
      change = std::max(change, std::abs(updated - sigma[ch]) / updated);
      sigma[ch] = updated;
    }
  }
  return change;
}

// How much of a level the next difference order must keep for the motion
// to count as gone (MotionGoneLevel). A motion sampled N times per cycle
// keeps about sin(pi / N) of its level per order (0.31 at 10), white noise
// all of it.
constexpr double kFlatOrder = 0.9;

// The noise level from `levels`, a series' RMS d-th differences over their
// white-noise gain for d = kLeastOrder.. in turn: where the next two
// orders each keep kFlatOrder of the one before, the first of them (at the
// order before, up to a fourth of the variance can still be the motion's:
// 1.12 times the noise on a Table 6-like pitch record), else the least. The
// least of all orders had been the level: the higher orders weigh the
// highest frequencies most and spread most (relative variance about
// (2 / n) C(4d, 2d) / C(2d, d)^2, 1.9 / n at d = 2, 3.6 / n at 8), so a
// noise draw short of power there held a channel low. On a pair of 3-s
// runs (suite draw 92, 29 samples each) the roll readings' levels fell
// from 0.0083 deg at d = 2 to 0.0051 at 8, against a true 0.01; held at
// 0.0051, the true model (a roll reading error and a Magnus moment, both
// found) left roll 1.8 times that level and the record `not_explained`.
// Over the kept sigma-auto records of draws 79-95 (3069 channels, each
// pooled over its segments with the residual's level, as diagnose holds
// them) the least held 8.3% under 0.75 of the true noise and 4.1% over
// 1.25; this rule 4.8% and 5.3% (a level held too high is held again lower
// once a fit shows it, diagnose's HeldAgain; one held too low is held
// again higher only where the search finds the record at the noise level).
double MotionGoneLevel(const std::vector<double>& levels) {
  for (size_t i = 0; i + 2 < levels.size(); ++i) {
    if (levels[i + 1] >= kFlatOrder * levels[i] &&
        levels[i + 2] >= kFlatOrder * levels[i + 1]) {
      return levels[i + 1];
    }
  }
  return *std::min_element(levels.begin(), levels.end());
}

std::string Summary(const FitProblem& p, const RelaxationOutcome& r) {
  std::string text = "sigma: auto: " + std::to_string(r.rounds) +
                     (r.rounds == 1 ? " round" : " rounds") +
                     (r.settled ? "" : " (not settled)") + ", weights (deg)";
  for (const PreparedSegment& s : p.segments) {
    if (p.segments.size() > 1) text += " '" + s.name + "'";
    text += " phi " + FormatNumber("%.3g", s.sigma.phi) + " theta " +
            FormatNumber("%.3g", s.sigma.theta) + " psi " +
            FormatNumber("%.3g", s.sigma.psi);
  }
  return text;
}

}  // namespace

double DataNoiseDeg(const std::vector<double>& samples) {
  std::vector<double> d = samples;
  std::vector<double> levels;  // orders kLeastOrder.. in turn
  // C(2d, d), the sum of the squared binomial weights of a d-th difference.
  double gain = 1.0;
  for (int order = 1; order <= kMostOrder; ++order) {
    gain *= 2.0 * (2.0 * order - 1.0) / order;
    if (d.size() < 2) break;
    for (size_t i = 0; i + 1 < d.size(); ++i) d[i] = d[i + 1] - d[i];
    d.pop_back();
    if (order < kLeastOrder) continue;
    double sum = 0.0;
    for (double x : d) sum += x * x;
    levels.push_back(std::sqrt(sum / d.size() / gain));
  }
  const double level = levels.empty() ? 0.0 : MotionGoneLevel(levels);
  if (!std::isfinite(level)) return kDataFloorDeg;
  return std::max(level, kDataFloorDeg);
}

void StartNoiseWeights(const Case& c, FitProblem* problem) {
  for (PreparedSegment& s : problem->segments) {
    for (int ch = 0; ch < 3; ++ch) {
      if (c.sigma_auto[ch]) s.sigma[ch] = DataNoiseDeg(s.data.channel(ch));
    }
  }
}

RelaxationOutcome RelaxNoiseWeights(const Case& c,
                                    FitProblem* problem,
                                    std::vector<double>* values) {
  RelaxationOutcome outcome;
  if (!c.AnySigmaAuto()) return outcome;
  StageSettings settings;
  settings.tolerance = c.solver.tolerance;
  settings.max_iterations = c.solver.max_iterations;
  while (outcome.rounds < kMaxRounds) {
    const double change = Reweight(c.sigma_auto,
                                   ResidualRms(*problem, *values, c.source),
                                   &problem->segments);
    ++outcome.rounds;
    if (change < kSettled) {
      outcome.settled = true;
      break;
    }
    std::vector<double> trial = *values;
    const StageOutcome stage = SolveStage(problem->segments,
                                          problem->free,
                                          problem->model,
                                          problem->names,
                                          settings,
                                          &trial);
    if (!stage.integrable) break;  // keep the last solution and weights
    outcome.iterations += stage.iterations;
    *values = trial;
  }
  outcome.summary = Summary(*problem, outcome);
  return outcome;
}

}  // namespace fit3dof
