// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Convergence-basin study (`fit3dof basin CONFIG`): how often does a fit
// reach the global minimum from poor starting guesses?
//
// A reference fit of the config (the full pipeline, from its own values)
// defines the global minimum. Then `starts` starting guesses are drawn from
// a wide box around it:
//   stiffness (Cm_alpha, Cn_beta) and roll damping (Cl_p): 1/5 to 5 times
//     the reference (log-uniform);
//   pitch and yaw damping (Cm_q, Cn_r): -20 to +5;
//   every other free coefficient (nonlinear, Magnus, tunnel, I_zx): -10 to
//     +10 times the reference;
//   initial rates: 0.5 to 1.5 times the reference (angles as fitted);
// and each is fitted by every method:
//   gauss_newton          the 1978 program: undamped full steps, whole record;
//   levenberg_marquardt   plain LM on the whole record;
//   continuation          LM on growing windows, no multi-start;
//   robust                the default pipeline (continuation, multi-start);
//   filter_error          the filter-error fit (filter_error.h), with the
//                         config's process_noise or every axis auto.
// A start reaches the global minimum when the fit converges to a probable
// error within 1% of the reference (for filter_error, of a filter-error
// fit from the config's values).

#ifndef FIT3DOF_BASIN_H_
#define FIT3DOF_BASIN_H_

#include <cstdint>
#include <string>
#include <vector>

#include "fit3dof/case.h"

namespace fit3dof {

struct BasinOptions {
  int starts = 200;
  std::uint64_t seed = 1;
  // Starts run in parallel on the process's thread budget
  // (thread_budget.h; --jobs sets it).
  std::vector<std::string> methods = {
      "gauss_newton", "levenberg_marquardt", "robust"};
};

struct BasinMethod {
  std::string method;
  int tried = 0;
  int reached = 0;  // global minimum reached
  double seconds = 0.0;
};

struct BasinResult {
  std::string name;
  double reference_probable_error = 0.0;
  std::vector<BasinMethod> methods;
};

// Throws InputError when the reference fit itself fails.
BasinResult RunBasinStudy(const Case& c, const BasinOptions& options);

std::string FormatBasin(const BasinResult& result);
std::string BasinJson(const BasinResult& result);

}  // namespace fit3dof

#endif  // FIT3DOF_BASIN_H_
