// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Simulated measurement noise (noise.h): seeded Gaussian noise and biases
// added to a record (NSESWH = 1).

#include "fit3dof/noise.h"

#include <cmath>

namespace fit3dof {

double GaussianSource::Next() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  // Uniform deviates in (0, 1] from the top 53 bits.
  auto uniform = [this]() {
    return (static_cast<double>(engine_() >> 11) + 1.0) * 0x1.0p-53;
  };
  const double u1 = uniform();
  const double u2 = uniform();
  const double radius = std::sqrt(-2.0 * std::log(u1));
  const double angle = 2.0 * M_PI * u2;
  spare_ = radius * std::sin(angle);
  has_spare_ = true;
  return radius * std::cos(angle);
}

void AddNoise(const NoiseOptions& options, TimeHistory* history) {
  if (!options.enabled) return;
  GaussianSource source(options.seed);
  for (int i = 0; i < history->size(); ++i) {
    history->phi[i] += options.bias.phi + options.sigma.phi * source.Next();
    history->theta[i] +=
        options.bias.theta + options.sigma.theta * source.Next();
    history->psi[i] += options.bias.psi + options.sigma.psi * source.Next();
  }
}

}  // namespace fit3dof
