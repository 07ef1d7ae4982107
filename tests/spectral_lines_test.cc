// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Spectral lines: a reading error at the spin rate and twice it is found at
// the right frequencies; white noise shows no line; a strong line of a short
// record stands out of its own neighbourhood, while smooth colored noise
// does not.

#include "spectral_lines.h"

#include <cmath>
#include <complex>
#include <cstdio>
#include <random>

#include "gtest/gtest.h"

namespace fit3dof {
namespace {

std::vector<double> Noise(int n, double sigma, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<double> x(n);
  for (double& v : x) v = normal(rng);
  return x;
}

TEST(SpectralLines, FindsTheSpinAndItsHarmonic) {
  const double dt = 0.01, spin = 1.72;
  std::vector<double> x = Noise(800, 0.01, 1);
  for (int i = 0; i < 800; ++i) {
    const double t = i * dt;
    x[i] += 0.04 * std::cos(2 * M_PI * spin * t + 0.3) +
            0.02 * std::cos(4 * M_PI * spin * t + 1.1);
  }
  const std::vector<SpectralLine> lines = SpectralLines(x, dt);
  ASSERT_GE(lines.size(), 2u);
  // The strongest, standing out of its neighbourhood too, is not repeated.
  EXPECT_EQ(ResidualLines(x, dt).size(), lines.size());
  const double resolution = 1.0 / (800 * dt);
  EXPECT_NEAR(lines[0].frequency_hz, spin, resolution);
  EXPECT_NEAR(lines[1].frequency_hz, 2 * spin, resolution);
  EXPECT_GT(lines[0].power_ratio, lines[1].power_ratio);
}

TEST(SpectralLines, WhiteNoiseHasNone) {
  int quiet = 0;
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    quiet += SpectralLines(Noise(800, 0.01, seed), 0.01).empty();
  }
  EXPECT_GE(quiet, 48);
  EXPECT_TRUE(SpectralLines(std::vector<double>(10, 1.0), 0.01).empty());
}

// A 38-sample record: white noise of 0.01 deg plus `amplitude` (deg) at
// `cycles` cycles over the record (8.5: halfway between two bins), and an
// AR(1) part of lag-1 autocorrelation `rho` (its size the white's).
std::vector<double> ShortRecord(double amplitude,
                                double cycles,
                                double rho,
                                std::uint64_t seed) {
  const int n = 38;
  std::vector<double> x = Noise(n, 0.01, seed);
  const std::vector<double> innovation =
      Noise(n, 0.01 * std::sqrt(1.0 - rho * rho), seed + 1000000);
  double ar = Noise(1, 0.01, seed + 2000000)[0];
  for (int i = 0; i < n; ++i) {
    ar = rho * ar + innovation[i];
    x[i] += amplitude * std::sin(2.0 * M_PI * cycles * i / n) +
            (rho > 0.0 ? ar : 0.0);
  }
  return x;
}

TEST(LocalSpectralLine, FindsAStrongLineOfAShortRecordNotColoredNoise) {
  // A buzz 4.8 times the noise between two bins (draw 165's tunnel buzz of
  // the pitch reading): the mean of all bins is mostly the line's own, and
  // the global test (4 ln N) finds it in none of these records; against
  // its neighbourhood it is found in most. Noise, white or colored (lag-1
  // 0.6, a spectrum rising fourfold toward low frequencies), stays under
  // the limit's chance of 1e-3.
  const double dt = 0.08;
  int global = 0, local = 0, white = 0, colored = 0;
  const int kSeeds = 1000;
  SpectralLine line;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const std::vector<double> buzz = ShortRecord(0.048, 8.5, 0.0, seed);
    global += !SpectralLines(buzz, dt).empty();
    if (LocalSpectralLine(buzz, dt, &line)) {
      ++local;
      EXPECT_NEAR(line.frequency_hz, 8.5 / (38 * dt), 0.5 / (38 * dt));
      // The description's and the fit report's lines carry it.
      const std::vector<SpectralLine> lines = ResidualLines(buzz, dt);
      ASSERT_EQ(lines.size(), 1u);
      EXPECT_EQ(lines[0].frequency_hz, line.frequency_hz);
    }
    white += LocalSpectralLine(ShortRecord(0.0, 0.0, 0.0, seed), dt, &line);
    colored += LocalSpectralLine(ShortRecord(0.0, 0.0, 0.6, seed), dt, &line);
  }
  std::printf("buzz: global %d, local %d; noise: white %d, colored %d of %d\n",
              global,
              local,
              white,
              colored,
              kSeeds);
  EXPECT_LE(global, 10);
  EXPECT_GE(local, 500);
  EXPECT_LE(white, 3);
  EXPECT_LE(colored, 3);
  EXPECT_FALSE(LocalSpectralLine(std::vector<double>(10, 1.0), dt, &line));
}

// theta + i psi whirling forward (counter-clockwise) at bin 7 and backward
// at bin 3 of 100, on an offset: the two-sided periodogram puts the first
// at bin 7, the second at bin 100 - 3, and nothing at bin 0.
TEST(SpectralLines, AComplexSeriesKeepsTheWhirlsSense) {
  const int n = 100;
  std::vector<std::complex<double>> z(n);
  for (int i = 0; i < n; ++i) {
    z[i] = std::complex<double>(0.3, -0.2) +
           2.0 * std::polar(1.0, 2.0 * M_PI * 7 * i / n) +
           1.0 * std::polar(1.0, -2.0 * M_PI * 3 * i / n);
  }
  const std::vector<double> power = Periodogram(z);
  ASSERT_EQ(power.size(), static_cast<size_t>(n));
  EXPECT_NEAR(power[0], 0.0, 1e-18);
  EXPECT_NEAR(power[7], 4.0 * n * n, 1e-8 * n * n);
  EXPECT_NEAR(power[n - 3], 1.0 * n * n, 1e-8 * n * n);
  EXPECT_NEAR(power[3], 0.0, 1e-8 * n * n);
  EXPECT_NEAR(power[n - 7], 0.0, 1e-8 * n * n);
}

}  // namespace
}  // namespace fit3dof
