// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Measurement noise for simulated (or real) records, the report's NOISE
// subroutine (switch NSESWH): Gaussian noise of a given standard deviation
// plus a constant bias, per channel.
//
// The report seeded RANDU from the clock; here the seed is part of the
// config so a run can be repeated exactly. The generator is std::mt19937_64,
// whose output sequence the C++ standard fixes, and the normal deviates come
// from our own Box-Muller transform (std::normal_distribution differs
// between standard libraries), so the same seed gives the same noise on
// every platform.

#ifndef FIT3DOF_NOISE_H_
#define FIT3DOF_NOISE_H_

#include <cstdint>
#include <random>

#include "fit3dof/case.h"
#include "fit3dof/time_history.h"

namespace fit3dof {

// Standard normal deviates from a seeded std::mt19937_64.
class GaussianSource {
 public:
  explicit GaussianSource(std::uint64_t seed) : engine_(seed) {}
  double Next();

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

// Adds noise and bias to every sample; draws phi, theta, psi in that order
// for each sample. Does nothing when options.enabled is false.
void AddNoise(const NoiseOptions& options, TimeHistory* history);

}  // namespace fit3dof

#endif  // FIT3DOF_NOISE_H_
