// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The random moments of simulated process noise (random_moment.h).

#include "fit3dof/random_moment.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace fit3dof {

bool operator==(const ProcessNoiseOptions& a, const ProcessNoiseOptions& b) {
  return a.rms == b.rms && a.correlation_time == b.correlation_time &&
         a.seed == b.seed;
}

RandomMoment::RandomMoment(const ProcessNoiseOptions& options,
                           double t0,
                           double t1,
                           double max_step)
    : t0_(t0) {
  CHECK_GT(options.correlation_time, 0.0);
  CHECK_GT(max_step, 0.0);
  CHECK_GE(t1, t0);
  grid_ = std::min(options.correlation_time / 20.0, max_step);
  const long n = static_cast<long>(std::ceil((t1 - t0) / grid_)) + 2;
  values_.resize(n);
  std::mt19937_64 generator(options.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double a = std::exp(-grid_ / options.correlation_time);
  const double b = std::sqrt(1.0 - a * a);
  for (int axis = 0; axis < 3; ++axis) {
    const double rms = options.rms[axis];
    double x = rms * normal(generator);  // stationary at t0
    for (long i = 0; i < n; ++i) {
      if (i > 0) x = a * x + b * rms * normal(generator);
      values_[i][axis] = x;
    }
  }
}

std::array<double, 3> RandomMoment::At(double t) const {
  const double u = std::max(0.0, (t - t0_) / grid_);
  const long i =
      std::min(static_cast<long>(u), static_cast<long>(values_.size()) - 2);
  const double w = std::min(1.0, u - i);
  std::array<double, 3> out;
  for (int axis = 0; axis < 3; ++axis) {
    out[axis] = (1.0 - w) * values_[i][axis] + w * values_[i + 1][axis];
  }
  return out;
}

}  // namespace fit3dof
