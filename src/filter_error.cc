// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The filter-error fit's relaxation (filter_error.h): noise levels by
// maximum likelihood, the filter's gains, Levenberg-Marquardt with the
// gains held; round after round.

#include "filter_error.h"

#include <glog/logging.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "assembly.h"
#include "boost/math/tools/minima.hpp"
#include "fit3dof/interrupt.h"
#include "format.h"
#include "stage_solver.h"

namespace fit3dof {
namespace {

constexpr int kMaxRounds = 20;
// Rounds end when the deviance (twice the negative log likelihood) moves
// by less than this between them: a likelihood ratio of 1.005.
constexpr double kDevianceTolerance = 0.01;
// The first search for an auto intensity goes up to this factor of the
// reference intensity (IntensityScales); later rounds search this factor
// either side of the last value, and down to the lowest intensity always.
constexpr double kFirstHigh = 30.0;
constexpr double kLaterSpan = 3.0;
// Brent's searches: bits of precision (relative to the log level: 2^-9,
// 0.2%, of ln q ~ -3 is 0.6%) and most evaluations.
constexpr int kSearchBits = 10;
constexpr int kMaxSearchIterations = 40;

const char* const kAxes[3] = {"roll", "pitch", "yaw"};
const double kInfinity = std::numeric_limits<double>::infinity();

// The levels the filter runs with: per axis the process-noise intensity
// (deg/s^1.5), per channel the measurement noise (deg, one for all
// segments). Coordinate i < 3 is an intensity, i >= 3 a sigma.
struct NoiseLevels {
  std::array<double, 6> level{};
  std::array<bool, 6> estimated{};
  std::array<double, 3> process() const {
    return {level[0], level[1], level[2]};
  }
  std::array<double, 3> sigma() const { return {level[3], level[4], level[5]}; }
};

// A segment's readings, three per sample.
std::vector<double> Interleaved(const TimeHistory& d) {
  std::vector<double> m(3 * d.size());
  for (int i = 0; i < d.size(); ++i) {
    m[3 * i] = d.phi[i];
    m[3 * i + 1] = d.theta[i];
    m[3 * i + 2] = d.psi[i];
  }
  return m;
}

// What every filter run needs: the segments' parameter vectors at the
// current values and their readings.
struct FilterInputs {
  const FitProblem* problem;
  std::vector<std::vector<double>> full;
  std::vector<std::vector<double>> measured;

  FilterInputs(const FitProblem& p, const std::vector<double>& values)
      : problem(&p) {
    const Assembly a = Assemble(p.segments,
                                p.free,
                                p.model,
                                values,
                                std::vector<double>(p.free.size(), 1.0));
    for (size_t s = 0; s < p.segments.size(); ++s) {
      full.push_back(SegmentFullValues(a, s));
      measured.push_back(Interleaved(p.segments[s].data));
    }
  }

  // The summed deviance of the filter over every segment at `levels`;
  // infinity where the motion cannot be followed.
  double Deviance(const NoiseLevels& levels,
                  std::vector<MotionModel::FilterRun>* runs) const {
    runs->resize(full.size());
    double deviance = 0.0;
    for (size_t s = 0; s < full.size(); ++s) {
      const TimeHistory& d = problem->segments[s].data;
      if (!problem->model->Filter(full[s].data(),
                                  d.t.data(),
                                  d.size(),
                                  measured[s].data(),
                                  levels.process(),
                                  levels.sigma(),
                                  &(*runs)[s],
                                  nullptr)) {
        return kInfinity;
      }
      deviance += (*runs)[s].deviance;
    }
    return deviance;
  }
  double Deviance(const NoiseLevels& levels) const {
    std::vector<MotionModel::FilterRun> runs;
    return Deviance(levels, &runs);
  }
};

// The minimum of f on [lo, hi] by Brent's method (golden section with
// parabolic steps: the deviance is smooth in a log level), to about
// kSearchBits binary digits of the interval.
double Minimize(const std::function<double(double)>& f, double lo, double hi) {
  boost::uintmax_t iterations = kMaxSearchIterations;
  return boost::math::tools::brent_find_minima(
             f, lo, hi, kSearchBits, iterations)
      .first;
}

// The range an intensity is sought in. The reference: the intensity at
// which the angles wander, over one sample interval dt, by the measurement
// noise (sigma / dt^1.5). The lowest: at which they wander over the longest
// record T by a thousandth of it (1e-3 sigma / T^1.5): no process noise,
// for all the filter can tell; an estimate within kNone times it is
// reported as none.
constexpr double kNone = 1.5;
constexpr double kSignificantDrop = 2.71;
struct IntensityScales {
  double reference = 0.0;
  double lowest = 0.0;
};
IntensityScales Scales(const FitProblem& p, const NoiseLevels& levels) {
  const double sigma = (levels.level[4] + levels.level[5]) / 2.0;
  double dt = std::numeric_limits<double>::infinity(), longest = 0.0;
  for (const PreparedSegment& segment : p.segments) {
    const TimeHistory& d = segment.data;
    const double span = d.t.back() - d.t.front();
    longest = std::max(longest, span);
    dt = std::min(dt, span / std::max(1, d.size() - 1));
  }
  return {sigma / std::pow(dt, 1.5), 1e-3 * sigma / std::pow(longest, 1.5)};
}

// The maximum-likelihood levels at the inputs' values: each estimated
// coordinate by Brent's method in its logarithm, `sweeps` times over all
// of them; the first round (`first`) searches intensities from near zero.
void EstimateLevels(const FilterInputs& inputs,
                    bool first,
                    const IntensityScales& scales,
                    NoiseLevels* levels) {
  const int sweeps = first ? 2 : 1;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    for (int i = 0; i < 6; ++i) {
      if (!levels->estimated[i]) continue;
      const double x0 = std::log(levels->level[i]);
      double lo = x0 - std::log(kLaterSpan), hi = x0 + std::log(kLaterSpan);
      if (i < 3) {
        // An intensity may always fall to none at all (the data may hold
        // no process noise; a poor start makes the first rounds' large).
        lo = std::log(scales.lowest);
        if (first && sweep == 0) hi = std::log(scales.reference * kFirstHigh);
      }
      NoiseLevels trial = *levels;
      auto deviance = [&](double x) {
        trial.level[i] = std::exp(x);
        return inputs.Deviance(trial);
      };
      levels->level[i] = std::exp(Minimize(deviance, lo, hi));
    }
  }
}

// The weights a segment's residuals take from a filter run: its gains, and
// L^-1 of each innovation covariance S = L L^T.
std::shared_ptr<const InnovationWeights> Weights(
    const MotionModel::FilterRun& run) {
  auto w = std::make_shared<InnovationWeights>();
  w->gains = run.gains;
  const int n = static_cast<int>(run.covariance.size() / 9);
  w->whitening.resize(9 * n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Map<const Eigen::Matrix3d> s(&run.covariance[9 * i]);
    const Eigen::Matrix3d inverse =
        s.llt().matrixL().solve(Eigen::Matrix3d::Identity());
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(
        &w->whitening[9 * i]) = inverse;
  }
  return w;
}

// The estimate of intensity `axis` with its error from the deviance's
// curvature in the logarithm: var(ln q) = 2 / D''.
ProcessNoiseEstimate IntensityEstimate(const FilterInputs& inputs,
                                       const NoiseLevels& levels,
                                       const IntensityScales& scales,
                                       int axis) {
  ProcessNoiseEstimate e;
  e.axis = kAxes[axis];
  e.intensity = levels.level[axis];
  e.estimated = levels.estimated[axis];
  e.standard_error = std::numeric_limits<double>::quiet_NaN();
  if (!e.estimated) return e;
  // None detected: at the floor, or not significantly above it (the
  // likelihood-ratio test of intensity 0, a boundary value: 5% at a
  // deviance drop of 2.71).
  const double at_estimate = inputs.Deviance(levels);
  NoiseLevels floor = levels;
  floor.level[axis] = scales.lowest;
  if (e.intensity < kNone * scales.lowest ||
      inputs.Deviance(floor) - at_estimate < kSignificantDrop) {
    e.intensity = 0.0;
    return e;
  }
  const double h = 0.1;
  NoiseLevels plus = levels, minus = levels;
  plus.level[axis] *= std::exp(h);
  minus.level[axis] *= std::exp(-h);
  const double curvature =
      (inputs.Deviance(plus) - 2.0 * at_estimate + inputs.Deviance(minus)) /
      (h * h);
  if (curvature > 0.0) {
    e.standard_error = e.intensity * std::sqrt(2.0 / curvature);
  }
  return e;
}

// The starting levels: the config's intensities (auto ones at the
// reference), the segments' sigmas (the first segment's for all).
NoiseLevels StartLevels(const Case& c,
                        const FitProblem& p,
                        IntensityScales* scales) {
  NoiseLevels levels;
  const ChannelValues& sigma = p.segments[0].sigma;
  levels.level[3] = sigma.phi;
  levels.level[4] = sigma.theta;
  levels.level[5] = sigma.psi;
  for (int ch = 0; ch < 3; ++ch) levels.estimated[3 + ch] = c.sigma_auto[ch];
  *scales = Scales(p, levels);
  for (int axis = 0; axis < 3; ++axis) {
    levels.estimated[axis] = c.process_noise.estimated[axis];
    levels.level[axis] = levels.estimated[axis]
                             ? scales->reference
                             : c.process_noise.intensity[axis];
  }
  return levels;
}

// Sets each segment's weights from `runs` and its sigmas from `levels`.
// With process noise, the error bars count the innovations' correlation
// over at least kLagFloor lags: the filter models the random moments as
// white, and moments correlated over a few samples leave small
// correlations at each of those lags, each inside the band that would let
// the colored-residual covariance count it (colored_covariance.h) but
// adding up. Measured (tools/process_noise_study, 0.05-s moments sampled
// at 0.01 s): scatter / standard error 1.27-1.35 without the floor,
// 1.03-1.08 with it. Without process noise the innovations are the
// output-error residuals and keep their own window.
constexpr int kLagFloor = 10;
void HoldFilter(const std::vector<MotionModel::FilterRun>& runs,
                const NoiseLevels& levels,
                const IntensityScales& scales,
                FitProblem* p) {
  bool noisy = false;
  for (int axis = 0; axis < 3; ++axis) {
    noisy |= levels.level[axis] >= kNone * scales.lowest;
  }
  for (size_t s = 0; s < p->segments.size(); ++s) {
    PreparedSegment& segment = p->segments[s];
    segment.innovation_weights = Weights(runs[s]);
    segment.sigma = {levels.level[3], levels.level[4], levels.level[5]};
    segment.min_lag_window = noisy ? kLagFloor : 0;
  }
}

std::string Describe(const std::vector<ProcessNoiseEstimate>& estimates) {
  std::string text;
  for (const ProcessNoiseEstimate& e : estimates) {
    if (!text.empty()) text += ", ";
    text += e.axis + " " + FormatNumber("%.3g", e.intensity);
    if (std::isfinite(e.standard_error)) {
      text += " +- " + FormatNumber("%.2g", e.standard_error);
    }
    if (!e.estimated) text += " (given)";
  }
  return text + " deg/s^1.5";
}

// Output error first (continuation, no multi-start): where it explains the
// motion to the noise level (probable error within
// solver.max_probable_error), the rounds start from its solution, at which
// the first round finds little or no process noise and the rounds settle
// in two or three instead of walking down from a poor start's large
// intensities; elsewhere they start from the config's values, which the
// filter tolerates far better than output error does (the basin study).
void StartFromOutputError(const Case& c,
                          const FitProblem& problem,
                          std::vector<double>* values,
                          FitResult* result) {
  const double limit = c.solver.max_probable_error;
  if (!(limit > 0.0)) return;
  Case plain = c;
  plain.solver.method = FitMethod::kLevenbergMarquardt;
  plain.solver.multi_start = false;
  std::vector<double> trial = *values;
  const PipelineOutcome o = RunPipeline(plain, problem, &trial);
  result->iterations += o.iterations;
  if (o.integrable && o.converged && o.probable_error <= limit) {
    *values = trial;
    result->pipeline.push_back(
        "filter error: started from the output-error solution (probable "
        "error " +
        FormatNumber("%.3g", o.probable_error) + ")");
  }
}

}  // namespace

PipelineOutcome SolveFilterError(const Case& c,
                                 FitProblem* problem,
                                 std::vector<double>* values,
                                 FitResult* result) {
  PipelineOutcome outcome;
  *values = problem->values;
  StartFromOutputError(c, *problem, values, result);
  IntensityScales scales;
  NoiseLevels levels = StartLevels(c, *problem, &scales);
  StageSettings settings;
  settings.tolerance = c.solver.tolerance;
  settings.max_iterations = c.solver.max_iterations;
  double previous = kInfinity;
  std::vector<MotionModel::FilterRun> runs;
  int round = 0;
  StageOutcome stage;
  for (round = 1; round <= kMaxRounds; ++round) {
    if (StopRequested()) throw Interrupted();
    const FilterInputs inputs(*problem, *values);
    EstimateLevels(inputs, round == 1, scales, &levels);
    const double deviance = inputs.Deviance(levels, &runs);
    if (!std::isfinite(deviance)) {
      outcome.integrable = false;
      outcome.failure = "the filter cannot follow the motion";
      return outcome;
    }
    HoldFilter(runs, levels, scales, problem);
    VLOG(1) << c.name << ": filter-error round " << round << ": deviance "
            << deviance;
    if (round > 1 && std::abs(deviance - previous) < kDevianceTolerance &&
        stage.converged) {
      break;
    }
    previous = deviance;
    stage = SolveStage(problem->segments,
                       problem->free,
                       problem->model,
                       problem->names,
                       settings,
                       values);
    if (!stage.integrable) {
      outcome.integrable = false;
      outcome.failure = stage.failure;
      return outcome;
    }
    outcome.iterations += stage.iterations;
    outcome.failed_evaluations += stage.failed_evaluations;
  }
  const bool settled = round <= kMaxRounds;
  if (!settled) {
    // The last round's solve moved the values: the filter at them.
    const double deviance =
        FilterInputs(*problem, *values).Deviance(levels, &runs);
    if (!std::isfinite(deviance)) {
      outcome.integrable = false;
      outcome.failure = "the filter cannot follow the motion";
      return outcome;
    }
    HoldFilter(runs, levels, scales, problem);
  }
  outcome.converged = settled && stage.converged;
  outcome.termination =
      settled ? stage.termination + "; filter error: " + std::to_string(round) +
                    " rounds"
              : "the filter-error rounds did not settle in " +
                    std::to_string(kMaxRounds);
  double normalized = 0.0;
  for (const MotionModel::FilterRun& run : runs) {
    normalized += run.normalized_sum;
  }
  outcome.probable_error =
      std::sqrt(normalized / (3 * problem->points - problem->free.size()));
  const FilterInputs inputs(*problem, *values);
  for (int axis = 0; axis < 3; ++axis) {
    if (levels.estimated[axis] || levels.level[axis] > 0.0) {
      result->process_noise.push_back(
          IntensityEstimate(inputs, levels, scales, axis));
    }
  }
  result->pipeline.push_back("filter error: " + std::to_string(round) +
                             " rounds; process noise " +
                             Describe(result->process_noise));
  return outcome;
}

}  // namespace fit3dof
