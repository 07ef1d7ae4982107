// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/noise.h"

#include <cmath>

#include "gtest/gtest.h"

namespace fit3dof {
namespace {

TimeHistory Zeros(int n) {
  TimeHistory h;
  for (int i = 0; i < n; ++i) h.Append(0.01 * i, 0.0, 0.0, 0.0);
  return h;
}

TEST(Noise, SameSeedSameNoiseOtherSeedOtherNoise) {
  NoiseOptions options;
  options.enabled = true;
  options.sigma = {1.0, 0.01, 0.02};
  options.seed = 42;
  TimeHistory a = Zeros(100), b = Zeros(100), c = Zeros(100);
  AddNoise(options, &a);
  AddNoise(options, &b);
  options.seed = 43;
  AddNoise(options, &c);
  EXPECT_EQ(a.theta, b.theta);
  EXPECT_NE(a.theta, c.theta);
}

TEST(Noise, HasTheRequestedMeanAndSpread) {
  NoiseOptions options;
  options.enabled = true;
  options.sigma = {1.0, 0.01, 0.05};
  options.bias = {0.0, 0.2, -0.1};
  const int n = 200000;
  TimeHistory h = Zeros(n);
  AddNoise(options, &h);
  auto stats = [&](const std::vector<double>& v, double* mean, double* sd) {
    double s = 0, s2 = 0;
    for (double x : v) s += x;
    *mean = s / n;
    for (double x : v) s2 += (x - *mean) * (x - *mean);
    *sd = std::sqrt(s2 / (n - 1));
  };
  double mean, sd;
  stats(h.theta, &mean, &sd);
  EXPECT_NEAR(mean, 0.2, 4 * 0.01 / std::sqrt(n));
  EXPECT_NEAR(sd, 0.01, 0.01 * 0.01);
  stats(h.psi, &mean, &sd);
  EXPECT_NEAR(mean, -0.1, 4 * 0.05 / std::sqrt(n));
  EXPECT_NEAR(sd, 0.05, 0.05 * 0.01);
  stats(h.phi, &mean, &sd);
  EXPECT_NEAR(sd, 1.0, 0.01);
  // Gaussian tails: about 4.55% beyond two sigma.
  int beyond = 0;
  for (double x : h.phi) beyond += std::abs(x) > 2.0;
  EXPECT_NEAR(beyond / static_cast<double>(n), 0.0455, 0.003);
}

TEST(Noise, DisabledDoesNothing) {
  NoiseOptions options;
  options.sigma = {1.0, 1.0, 1.0};
  TimeHistory h = Zeros(10);
  AddNoise(options, &h);
  for (double x : h.theta) EXPECT_EQ(x, 0.0);
}

}  // namespace
}  // namespace fit3dof
