// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/initial_conditions.h"

#include <cmath>
#include <cstdio>

#include "fit3dof/angles.h"
#include "fit3dof/config.h"
#include "fit3dof/noise.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

TEST(InitialConditions, PolynomialIsExactForACubic) {
  std::vector<double> t, y;
  for (int i = 0; i < 9; ++i) {
    t.push_back(1.0 + 0.06 * i);
    const double x = t.back() - 1.0;
    y.push_back(2.0 - 3.0 * x + 0.5 * x * x + 4.0 * x * x * x);
  }
  const PolynomialEstimate e = LocalPolynomial(t, y, 9, 3);
  EXPECT_NEAR(e.value, 2.0, 1e-12);
  EXPECT_NEAR(e.slope, -3.0, 1e-10);
}

// From the Table 6 record with 0.01 deg noise the estimate is far better
// than the listing's two-point difference, whose rate error is about
// sqrt(2) 0.01 / 0.06 = 0.24 deg/s from the noise alone.
TEST(InitialConditions, EstimatesTheTable6State) {
  const TimeHistory clean = ReadTimeHistory(
      testing::SourcePath("configs/report/data/table6_clean.csv"));
  double angle2 = 0.0, rate2 = 0.0, two_point2 = 0.0;
  const int kSeeds = 20;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    TimeHistory noisy = clean;
    NoiseOptions noise;
    noise.enabled = true;
    noise.sigma = {0.01, 0.01, 0.01};
    noise.seed = seed;
    AddNoise(noise, &noisy);
    const auto x =
        EstimateInitialConditions(ModelKind::kSymmetric, noisy, 0.0, 0.0);
    angle2 += std::pow(x[2] - 5.18, 2) + std::pow(x[4] + 2.589, 2);
    rate2 += std::pow(x[3] + 26.356, 2) + std::pow(x[5] + 7.77, 2);
    // The listing's ICS, for contrast.
    two_point2 +=
        std::pow((noisy.theta[1] - noisy.theta[0]) / 0.06 + 26.356, 2) +
        std::pow((noisy.psi[1] - noisy.psi[0]) / 0.06 + 7.77, 2);
  }
  const double angle = std::sqrt(angle2 / (2 * kSeeds));
  const double rate = std::sqrt(rate2 / (2 * kSeeds));
  const double two_point = std::sqrt(two_point2 / (2 * kSeeds));
  std::printf(
      "rms error: angle %.4f deg, rate %.3f deg/s (two-point %.3f deg/s)\n",
      angle,
      rate,
      two_point);
  EXPECT_LT(angle, 0.02);
  EXPECT_LT(rate, 0.8);
  EXPECT_GT(two_point, 4.0 * rate);
}

TEST(InitialConditions, AsymmetricRatesAreBodyRates) {
  // A record whose Euler rates are constant: phi = 30 + 600 t,
  // theta = 4 - 20 t, psi = -2 + 10 t.
  TimeHistory h;
  for (int i = 0; i < 12; ++i) {
    const double t = 0.01 * i;
    h.Append(t, 30 + 600 * t, 4 - 20 * t, -2 + 10 * t);
  }
  const auto x = EstimateInitialConditions(ModelKind::kAsymmetric, h, 0.0, 0.0);
  const double d = kDegree;
  EXPECT_NEAR(x[0], 30.0, 1e-9);
  EXPECT_NEAR(x[3], 600 - 10 * std::sin(4 * d), 1e-7);
  EXPECT_NEAR(x[4],
              -20 * std::cos(30 * d) + 10 * std::cos(4 * d) * std::sin(30 * d),
              1e-7);
  EXPECT_NEAR(x[5],
              10 * std::cos(4 * d) * std::cos(30 * d) + 20 * std::sin(30 * d),
              1e-7);
}

TEST(InitialConditions, OffsetsAreRemoved) {
  TimeHistory h;
  for (int i = 0; i < 12; ++i) h.Append(0.01 * i, 0.0, 1.0, 2.0);
  const auto x =
      EstimateInitialConditions(ModelKind::kSymmetric, h, 0.25, -0.5);
  EXPECT_NEAR(x[2], 0.75, 1e-12);
  EXPECT_NEAR(x[4], 2.5, 1e-12);
}

}  // namespace
}  // namespace fit3dof
