// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "noise_relaxation.h"

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "gtest/gtest.h"

namespace fit3dof {
namespace {

// Table 6's sampling (0.06 s) of its motion: roll spinning up from
// 641 deg/s, pitch a coning motion of 5 deg at 0.85 Hz (20 samples per
// cycle), each with the given error added.
struct Record {
  std::vector<double> roll, pitch;
};

Record Table6Like(const std::function<double(int)>& error) {
  Record r;
  for (int i = 0; i < 800; ++i) {
    const double t = 0.06 * i;
    r.roll.push_back(641.0 * t - 2.0 * t * t + error(i));
    r.pitch.push_back(5.0 * std::exp(-0.02 * t) *
                          std::cos(2.0 * M_PI * 0.85 * t + 0.3) +
                      error(i));
  }
  return r;
}

TEST(DataNoise, FindsWhiteNoiseUnderTheMotion) {
  for (double sigma : {0.003, 0.01, 0.1}) {
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0.0, sigma);
    std::vector<double> draws(800);
    for (double& x : draws) x = noise(rng);
    const Record r = Table6Like([&](int i) { return draws[i]; });
    EXPECT_NEAR(DataNoiseDeg(r.roll) / sigma, 1.0, 0.1) << sigma;
    EXPECT_NEAR(DataNoiseDeg(r.pitch) / sigma, 1.0, 0.1) << sigma;
  }
}

// On short records the level is unbiased and seldom far low: a spin's
// roll readings, 60 samples of a ramp with white noise, 400 draws. The
// least over the difference orders, the rule until the fiftieth session,
// held them at 0.946 of the noise on average and 10.5% of them under 0.75
// (a noise draw short of power at the highest frequencies, which the high
// orders weigh most); the first flat order holds 0.989 and 3.0%.
TEST(DataNoise, IsUnbiasedOnShortRecords) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.01);
  double sum = 0.0;
  int low = 0;
  constexpr int kDraws = 400;
  for (int k = 0; k < kDraws; ++k) {
    std::vector<double> roll(60);
    for (size_t i = 0; i < roll.size(); ++i) roll[i] = 2.3 * i + noise(rng);
    const double ratio = DataNoiseDeg(roll) / 0.01;
    sum += ratio;
    low += ratio < 0.75;
  }
  EXPECT_NEAR(sum / kDraws, 1.0, 0.03);
  EXPECT_LT(low, 0.06 * kDraws);
}

// Roll sensed in 2-deg steps: the error is uniform over a step, RMS
// 2 / sqrt(12) = 0.577 deg.
TEST(DataNoise, FindsQuantization) {
  Record r = Table6Like([](int) { return 0.0; });
  for (double& phi : r.roll) phi = 2.0 * std::round(phi / 2.0);
  EXPECT_NEAR(DataNoiseDeg(r.roll) / (2.0 / std::sqrt(12.0)), 1.0, 0.15);
}

// Without noise the motion itself is all that is left: a small level,
// never below the floor that keeps the weights finite.
TEST(DataNoise, NoiseFreeMotionGivesTheFloor) {
  const Record r = Table6Like([](int) { return 0.0; });
  EXPECT_LT(DataNoiseDeg(r.pitch), 2e-3);
  EXPECT_GE(DataNoiseDeg(r.pitch), 1e-4);
  EXPECT_EQ(DataNoiseDeg(std::vector<double>(50, 3.0)), 1e-4);
  EXPECT_EQ(DataNoiseDeg({1.0}), 1e-4);
  EXPECT_EQ(DataNoiseDeg({}), 1e-4);
}

}  // namespace
}  // namespace fit3dof
