// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The continuation pipeline of one attempt (continuation.h).

#include "continuation.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "assembly.h"
#include "fit3dof/time_history.h"
#include "stage_solver.h"

namespace fit3dof {
namespace {

std::vector<PreparedSegment> Window(const std::vector<PreparedSegment>& all,
                                    double window) {
  std::vector<PreparedSegment> out = all;
  for (PreparedSegment& p : out) {
    TimeHistory cut;
    for (int i = 0; i < p.data.size(); ++i) {
      if (p.data.t[i] - p.data.t[0] > window) break;
      cut.Append(p.data.t[i], p.data.phi[i], p.data.theta[i], p.data.psi[i]);
    }
    p.data = cut;
  }
  return out;
}

// Whether a fit from a nearby model's solution starts far above the noise
// after all (SolverOptions::far_start): one integration at the start
// values. The probable error of the solution it starts from is that of the
// start when an effect is added (its terms start at zero), not when one is
// taken out: without the body asymmetry a tunnel stiffness needed beside
// it, a 3-s Table 6 record started 200 times the noise off, and 50
// iterations from the trusted Gauss-Newton step crawled back to 2.4, a
// seventh of that diagnosis' time; the windows take it there in 14% less
// time over the whole diagnosis. The Gauss-Newton steps stay trusted (the
// values are a nearby model's): with Ceres' guarded first steps, and with
// windows already from 3 times the noise, the refits of a pair of 3-s runs
// crawled to 50 iterations and that diagnosis took 40% longer.
bool FarStart(const Case& c,
              const FitProblem& problem,
              const std::vector<double>& values) {
  if (!c.solver.from_solution || !(c.solver.far_start > 0.0)) return false;
  const Assembly a = Assemble(problem.segments,
                              problem.free,
                              problem.model,
                              values,
                              std::vector<double>(values.size(), 1.0));
  double ressum = 0.0;
  if (!SumOfSquares(a, &ressum)) return true;
  const int dof = 3 * CountPoints(problem.segments) - problem.free.size();
  return dof <= 0 || std::sqrt(ressum / dof) > c.solver.far_start;
}

}  // namespace

std::vector<double> ContinuationWindows(
    const std::vector<PreparedSegment>& segments, int num_free) {
  double longest = 0.0;
  double period = 0.0;
  for (const PreparedSegment& p : segments) {
    longest = std::max(longest, p.data.t.back() - p.data.t.front());
    // Fewer than 8 crossings (4 cycles): too short for windows.
    period = std::max(period, CrossingPeriod(p.data, 8.0));
  }
  std::vector<double> windows;
  if (period > 0.0) {
    for (double w = 2.0 * period; w < 0.75 * longest; w *= 2.0) {
      // Enough residuals for the free parameters in the window.
      int points = 0;
      for (const PreparedSegment& p : segments) {
        for (double t : p.data.t) points += (t - p.data.t.front() <= w);
      }
      if (3 * points >= 4 * num_free + 30) windows.push_back(w);
    }
  }
  windows.push_back(std::numeric_limits<double>::infinity());
  return windows;
}

PipelineOutcome RunPipeline(const Case& c,
                            const FitProblem& problem,
                            std::vector<double>* values) {
  const std::vector<PreparedSegment>& segments = problem.segments;
  const FreeLayout& free = problem.free;
  PipelineOutcome result;
  const int k = free.size();
  const bool gauss_newton = c.solver.method == FitMethod::kGaussNewton;
  const bool far = FarStart(c, problem, *values);
  // The report's plain method fits the whole record at once.
  const std::vector<double> windows =
      (c.solver.continuation || far) && !gauss_newton
          ? ContinuationWindows(segments, k)
          : std::vector<double>{std::numeric_limits<double>::infinity()};
  const std::vector<double> start = *values;
  // A refit from a solution limits its bearing angle (kBearingAngleStop),
  // the same for every window: found once.
  int limited = -1;
  double limit = 0.0;
  int outgrowing = -1;
  int outgrown = -1;
  if (c.solver.from_solution) {
    const int angle = FreeShared(c, problem.free, "bearing_angle");
    if (angle >= 0) {
      limited = angle;
      limit = kBearingAngleStop * LargestAngle(problem);
    }
    // ... and its Cm_bearing by Cm_alpha (StageSettings::outgrowing).
    outgrowing = FreeShared(c, problem.free, "Cm_bearing");
    outgrown = FreeShared(c, problem.free, "Cm_alpha");
    if (outgrown < 0) outgrowing = -1;
  }
  for (size_t w = 0; w < windows.size(); ++w) {
    const bool last = w + 1 == windows.size();
    const std::vector<PreparedSegment> stage =
        last ? segments : Window(segments, windows[w]);
    StageSettings settings;
    // Shorter windows only bring the values near: a looser rule.
    settings.tolerance = last ? c.solver.tolerance : 0.0;
    settings.relative_tolerance = last ? 0.0 : 1e-4;
    settings.max_iterations = last ? c.solver.max_iterations : 50;
    settings.bic_tolerance = c.solver.bic_tolerance;
    settings.stop_below = c.solver.stop_below;
    settings.out_of_reach = last && c.solver.stop_below > 0.0;
    if (c.solver.from_solution) {
      settings.initial_radius = kFromSolutionRadius;
      settings.coarser_jacobians = true;
      settings.limited = limited;
      settings.limit = limit;
      settings.outgrowing = outgrowing;
      settings.outgrown = outgrown;
    }
    auto solve = [&](std::vector<double>* trial) {
      return gauss_newton
                 ? SolveGaussNewton(stage, free, problem.model, settings, trial)
                 : SolveStage(stage,
                              free,
                              problem.model,
                              problem.names,
                              settings,
                              trial);
    };
    std::vector<double> trial = *values;
    StageOutcome outcome = solve(&trial);
    if (!outcome.integrable && w > 0) {
      // The shorter window's answer blows up over this longer one: start
      // this window again from the original values.
      VLOG(1) << c.name << ": stage " << w + 1
              << " cannot start from the previous stage (" << outcome.failure
              << "); restarting it from the starting values";
      trial = start;
      outcome = solve(&trial);
    }
    if (!outcome.integrable) {
      result.integrable = false;
      result.failure = outcome.failure;
      return result;
    }
    *values = trial;
    result.iterations += outcome.iterations;
    result.failed_evaluations += outcome.failed_evaluations;
    const int stage_points = CountPoints(stage);
    result.stages.push_back({stage_points, outcome.iterations});
    VLOG(1) << c.name << ": stage " << w + 1 << "/" << windows.size() << " ("
            << stage_points << " samples): " << outcome.iterations
            << " iterations, " << outcome.termination;
    if (last) {
      result.converged = outcome.converged;
      result.termination = outcome.termination;
      result.probable_error =
          std::sqrt(outcome.ressum / (3 * stage_points - k));
    }
  }
  return result;
}

}  // namespace fit3dof
