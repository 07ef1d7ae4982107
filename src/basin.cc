// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The convergence-basin study (basin.h): fits from a box of poor guesses
// by each method, counted by whether they reach the reference solution.

#include "fit3dof/basin.h"

#include <glog/logging.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <nlohmann/json.hpp>
#include <random>

#include "fit3dof/fit.h"
#include "fit3dof/input_error.h"
#include "fit3dof/thread_budget.h"

namespace fit3dof {
namespace {

// One starting guess from the box around the reference.
Case DrawStart(const Case& ref, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto uniform = [&](double a, double b) { return a + (b - a) * unit(*rng); };
  Case start = ref;
  const auto& table = ParameterTable(ref.model);
  for (int i = 0; i < NumParameters(ref.model); ++i) {
    ParameterSetting& p = start.parameters[i];
    if (!p.free || IsInitialCondition(ref.model, i)) continue;
    const std::string& name = table[i].name;
    if (name == "Cm_alpha" || name == "Cn_beta" || name == "Cl_p") {
      p.value *= std::exp(uniform(std::log(0.2), std::log(5.0)));
    } else if (name == "Cm_q" || name == "Cn_r") {
      p.value = uniform(-20.0, 5.0);
    } else {
      p.value *= uniform(-10.0, 10.0);
    }
  }
  // Initial rates off by up to 50%: the rate entries of each program.
  const bool symmetric = ref.model == ModelKind::kSymmetric;
  for (Segment& s : start.segments) {
    for (int j = 0; j < 6; ++j) {
      const bool rate = symmetric ? (j % 2 == 1) : (j >= 3);
      if (rate && s.initial[j].free) s.initial[j].value *= uniform(0.5, 1.5);
    }
  }
  return start;
}

void ApplyMethod(const std::string& method, Case* c) {
  if (method == "gauss_newton") {
    c->solver.method = FitMethod::kGaussNewton;
    c->solver.multi_start = false;
  } else if (method == "levenberg_marquardt") {
    c->solver.method = FitMethod::kLevenbergMarquardt;
    c->solver.continuation = false;
    c->solver.multi_start = false;
  } else if (method == "continuation") {
    c->solver.method = FitMethod::kLevenbergMarquardt;
    c->solver.continuation = true;
    c->solver.multi_start = false;
  } else if (method == "robust") {
    c->solver.method = FitMethod::kLevenbergMarquardt;
    c->solver.continuation = true;
    c->solver.multi_start = true;
  } else if (method == "filter_error") {
    // The config's process_noise block, or every axis estimated.
    c->solver.method = FitMethod::kFilterError;
    if (!c->process_noise.enabled()) {
      c->process_noise.estimated = {true, true, true};
    }
  } else {
    throw InputError("basin: unknown method '" + method +
                     "' (gauss_newton, levenberg_marquardt, continuation, "
                     "robust, filter_error)");
  }
}

// The probable error a start must reach with `method`: 1% above that of
// the reference fit by the same kind of fit (the filter-error fit's
// residuals are its whitened innovations, output error's its weighted
// residuals).
double Target(const Case& c, const std::string& method) {
  Case reference_case = c;
  ApplyMethod(method == "filter_error" ? method : "robust", &reference_case);
  const FitResult reference = Fit(reference_case);
  if (!reference.converged) {
    throw InputError(c.source + ": the reference fit does not converge (" +
                     reference.termination + "); a basin study needs one");
  }
  return reference.probable_error * 1.01 + 1e-12;
}

}  // namespace

BasinResult RunBasinStudy(const Case& c, const BasinOptions& options) {
  Case robust = c;
  ApplyMethod("robust", &robust);
  const FitResult reference = Fit(robust);
  if (!reference.converged) {
    throw InputError(c.source + ": the reference fit does not converge (" +
                     reference.termination + "); a basin study needs one");
  }
  BasinResult result;
  result.name = c.name;
  result.reference_probable_error = reference.probable_error;
  const Case ref = CaseAtSolution(c, reference);
  const double output_error_target = reference.probable_error * 1.01 + 1e-12;
  for (const std::string& method : options.methods) {
    BasinMethod m;
    m.method = method;
    m.tried = options.starts;
    Case probe = c;
    ApplyMethod(method, &probe);  // validates the name up front
    const double target =
        method == "filter_error" ? Target(c, method) : output_error_target;
    // Every method sees the same starts: the same seeded sequence, drawn
    // as the fits need them (start i is the i-th draw), never all held.
    std::mt19937_64 rng(options.seed);
    std::mutex draw;
    int drawn = 0;
    std::atomic<int> reached{0};
    const auto began = std::chrono::steady_clock::now();
    ParallelFor(options.starts, [&](int) {
      Case start;
      {
        std::lock_guard<std::mutex> lock(draw);
        CHECK_LT(drawn++, options.starts);
        start = DrawStart(ref, &rng);
      }
      ApplyMethod(method, &start);
      try {
        const FitResult r = Fit(start);
        if (r.converged && r.probable_error <= target) ++reached;
      } catch (const std::exception&) {
        // A start the motion cannot be integrated from: not reached.
      }
    });
    m.reached = reached;
    m.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - began)
            .count();
    result.methods.push_back(m);
  }
  return result;
}

std::string FormatBasin(const BasinResult& r) {
  std::string out = r.name + ": convergence basin (reference probable error " +
                    std::to_string(r.reference_probable_error) + ")\n";
  char line[160];
  std::snprintf(line,
                sizeof(line),
                "  %-22s %24s %10s\n",
                "method",
                "reached global minimum",
                "time");
  out += line;
  for (const BasinMethod& m : r.methods) {
    std::snprintf(line,
                  sizeof(line),
                  "  %-22s %10d/%-4d (%5.1f%%) %9.1f s\n",
                  m.method.c_str(),
                  m.reached,
                  m.tried,
                  100.0 * m.reached / std::max(1, m.tried),
                  m.seconds);
    out += line;
  }
  return out;
}

std::string BasinJson(const BasinResult& r) {
  nlohmann::json out;
  out["name"] = r.name;
  out["reference_probable_error"] = r.reference_probable_error;
  for (const BasinMethod& m : r.methods) {
    out["methods"].push_back(
        {{"method", m.method},
         {"tried", m.tried},
         {"reached", m.reached},
         {"rate", static_cast<double>(m.reached) / std::max(1, m.tried)},
         {"seconds", m.seconds}});
  }
  return out.dump(2) + "\n";
}

}  // namespace fit3dof
