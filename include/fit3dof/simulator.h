// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// `fit3dof simulate` (the report's NSWTCH = 1, 2): the motion a config's
// parameters produce, sampled at simulate.dt, with optional noise.

#ifndef FIT3DOF_SIMULATOR_H_
#define FIT3DOF_SIMULATOR_H_

#include <vector>

#include "fit3dof/case.h"
#include "fit3dof/time_history.h"

namespace fit3dof {

// The measured angles (theta_T and psi_T included) for full parameter values
// `values` at `times`; the initial conditions hold at times[0]. Throws
// InputError naming the case when the motion cannot be integrated (theta
// near 90 deg, NaN).
TimeHistory SimulateAt(const Case& c,
                       const std::vector<double>& values,
                       const std::vector<double>& times);

// The case's own motion: its parameter values at t = 0, dt, 2 dt, ... per
// its simulate options, driven by their process noise (random moments,
// random_moment.h) and with the measurement noise (noise:) added, each
// if enabled. SimulateAt has neither.
TimeHistory Simulate(const Case& c);

}  // namespace fit3dof

#endif  // FIT3DOF_SIMULATOR_H_
