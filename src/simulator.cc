// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The motion from a case's parameters (simulator.h), NSWTCH = 1/2.

#include "fit3dof/simulator.h"

#include <cstdio>
#include <memory>

#include "fit3dof/input_error.h"
#include "fit3dof/motion_model.h"
#include "fit3dof/noise.h"

namespace fit3dof {

namespace {

// The motion at `times`, with the random moments if given.
TimeHistory Motion(const Case& c,
                   const std::vector<double>& values,
                   const std::vector<double>& times,
                   std::shared_ptr<const RandomMoment> random_moment) {
  const int n = static_cast<int>(times.size());
  if (n > 1) {
    CheckIntegrationSteps(TotalSubsteps(times.data(), n, c.solver.step),
                          times.back() - times.front(),
                          c.solver.step,
                          c.source);
  }
  MotionModel model(c.Spec(), ActiveParameters(values, c.VaryingFlags()));
  model.set_random_moment(std::move(random_moment));
  std::vector<double> angles(3 * n);
  IntegrationFailure failure;
  if (!model.Evaluate(
          values.data(), times.data(), n, angles.data(), &failure)) {
    char when[64];
    std::snprintf(when, sizeof(when), " at t = %.4g s", failure.time);
    throw InputError(c.source + ": the motion cannot be integrated: " +
                     failure.reason + when + "; check the parameters");
  }
  TimeHistory history;
  for (int i = 0; i < n; ++i) {
    history.Append(
        times[i], angles[3 * i], angles[3 * i + 1], angles[3 * i + 2]);
  }
  return history;
}

}  // namespace

TimeHistory SimulateAt(const Case& c,
                       const std::vector<double>& values,
                       const std::vector<double>& times) {
  return Motion(c, values, times, nullptr);
}

TimeHistory Simulate(const Case& c) {
  const int n = c.simulate.NumSamples();
  if (n < 2) {
    throw InputError(c.source +
                     ": simulate: missing (give simulate.dt and "
                     "simulate.duration or simulate.samples)");
  }
  std::vector<double> times(n);
  for (int i = 0; i < n; ++i) times[i] = i * c.simulate.dt;
  std::shared_ptr<const RandomMoment> random_moment;
  const ProcessNoiseOptions& process = c.simulate.process_noise;
  if (process.enabled()) {
    random_moment = std::make_shared<RandomMoment>(
        process, times.front(), times.back(), c.solver.step);
  }
  TimeHistory history = Motion(c, c.Values(), times, random_moment);
  AddNoise(c.noise, &history);
  return history;
}

}  // namespace fit3dof
