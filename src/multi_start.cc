// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Restarts from the data and a spread around it (multi_start.h).

#include "multi_start.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <string>

#include "fit3dof/initial_conditions.h"
#include "fit3dof/parameters.h"
#include "fit3dof/start_values.h"
#include "fit3dof/thread_budget.h"

namespace fit3dof {
namespace {

// Every free coordinate from the data: linear-theory estimates of the
// coefficients (start_values.h), initial conditions fitted to each
// segment's first samples (initial_conditions.h). The given values play no
// part: they may be what led to the local minimum.
std::vector<double> DataStart(const Case& c, const FitProblem& problem) {
  const FreeLayout& free = problem.free;
  const int k = free.size();
  std::vector<bool> all(c.parameters.size(), false);
  for (int g = 0; g < k; ++g) {
    if (free.segment[g] < 0) all[free.position[g]] = true;
  }
  std::vector<double> full = c.Values();
  EstimateStartValues(c, problem.segments[0].data, all, &full);
  const ParameterLayout& layout = Layout(c.model);
  std::vector<double> start(k);
  for (int g = 0; g < k; ++g) {
    if (free.segment[g] < 0) {
      start[g] = full[free.position[g]];
      continue;
    }
    const PreparedSegment& p = problem.segments[free.segment[g]];
    const std::array<double, 6> estimate = EstimateInitialConditions(
        c.model, p.data, full[layout.theta_offset], full[layout.psi_offset]);
    start[g] = estimate[free.position[g] - layout.first_initial];
  }
  return start;
}

// Starting points for the multi-start: the stiffness scaled, the damping
// moved across its plausible range, the other terms zeroed or kept.
std::vector<std::vector<double>> SpreadStarts(const Case& c,
                                              const FreeLayout& free,
                                              const std::vector<double>& base,
                                              int count) {
  static const double kStiffness[] = {0.5, 2.0, 0.7, 1.4, 0.3, 3.0, 0.85, 1.2};
  static const double kDamping[] = {
      -5.0, 0.0, -15.0, -2.0, -10.0, 2.0, -25.0, -8.0};
  const auto& table = ParameterTable(c.model);
  std::vector<std::vector<double>> starts;
  for (int j = 0; j < count; ++j) {
    std::vector<double> s = base;
    for (int g = 0; g < free.size(); ++g) {
      if (free.segment[g] >= 0) continue;  // initial conditions: from data
      const std::string& name = table[free.position[g]].name;
      if (name == "Cm_alpha" || name == "Cn_beta") {
        s[g] = base[g] * kStiffness[j % 8];
        if (s[g] == 0.0)
          s[g] = (name == "Cm_alpha" ? -0.1 : 0.1) * kStiffness[j % 8];
      } else if (name == "Cm_q" || name == "Cn_r") {
        s[g] = kDamping[j % 8];
      } else if (j % 2 == 0) {
        s[g] = 0.0;
      }
    }
    starts.push_back(s);
  }
  return starts;
}

// Each of `starts` through the whole pipeline, in parallel, against
// `first`: the best, when one beats it.
MultiStartOutcome BestOf(const Case& c,
                         const FitProblem& problem,
                         const std::vector<std::vector<double>>& starts,
                         const PipelineOutcome& first) {
  std::vector<PipelineOutcome> outcomes(starts.size());
  std::vector<std::vector<double>> finals = starts;
  // Threads from the process's budget: inside a busy batch the starts run
  // one after the other.
  ParallelFor(static_cast<int>(starts.size()), [&](int j) {
    try {
      outcomes[j] = RunPipeline(c, problem, &finals[j]);
    } catch (const std::exception& e) {
      outcomes[j].integrable = false;
      outcomes[j].failure = e.what();
    }
  });
  MultiStartOutcome m;
  double best = first.probable_error;
  int best_index = -1;
  for (size_t j = 0; j < starts.size(); ++j) {
    if (outcomes[j].integrable && outcomes[j].probable_error < best) {
      best = outcomes[j].probable_error;
      best_index = static_cast<int>(j);
    }
    m.iterations += outcomes[j].iterations;
  }
  m.reached = std::abs(first.probable_error - best) <= 0.01 * best ? 1 : 0;
  for (const PipelineOutcome& o : outcomes) {
    m.reached +=
        o.integrable && std::abs(o.probable_error - best) <= 0.01 * best;
  }
  m.tried = static_cast<int>(starts.size()) + 1;
  if (best_index >= 0) {
    m.improved = true;
    m.best = outcomes[best_index];
    m.values = finals[best_index];
  }
  return m;
}

}  // namespace

MultiStartOutcome RunMultiStart(const Case& c,
                                const FitProblem& problem,
                                const PipelineOutcome& first) {
  const std::vector<double> data_start = DataStart(c, problem);
  std::vector<std::vector<double>> starts = {data_start};
  for (const auto& s :
       SpreadStarts(c, problem.free, data_start, c.solver.starts - 1)) {
    starts.push_back(s);
  }
  return BestOf(c, problem, starts, first);
}

MultiStartOutcome RunBearingRestarts(const Case& c,
                                     const FitProblem& problem,
                                     const std::vector<double>& solution,
                                     const PipelineOutcome& first) {
  const int angle = FreeShared(c, problem.free, "bearing_angle");
  const int moment = FreeShared(c, problem.free, "Cm_bearing");
  if (angle < 0 || moment < 0) return {};
  const double largest = LargestAngle(problem);
  if (!(std::abs(solution[angle]) > largest)) return {};
  // The solution's stiffness kept (Cm_alpha + Cm_bearing, the unfaded
  // moment's), the bearing moment back at its configured start.
  const int stiffness = FreeShared(c, problem.free, "Cm_alpha");
  std::vector<std::vector<double>> starts;
  for (const double fraction : {0.06, 0.15, 0.4}) {
    std::vector<double> s = solution;
    s[angle] = fraction * largest;
    s[moment] = problem.values[moment];
    if (stiffness >= 0) {
      s[stiffness] += solution[moment] - problem.values[moment];
    }
    starts.push_back(s);
  }
  return BestOf(c, problem, starts, first);
}

}  // namespace fit3dof
