// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Process noise for simulation (random_moment.h): the random moments'
// statistics, their seed, their effect on the motion, and the config keys.

#include "fit3dof/random_moment.h"

#include <cmath>
#include <string>
#include <vector>

#include "fit3dof/config.h"
#include "fit3dof/input_error.h"
#include "fit3dof/simulator.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

TEST(RandomMoment, HasTheGivenRmsAndCorrelationTime) {
  ProcessNoiseOptions options;
  options.rms = {0.0, 3e-4, 1e-4};
  options.correlation_time = 0.05;
  options.seed = 3;
  const RandomMoment moment(options, 0.0, 400.0, 0.001);
  const double dt = 0.005;
  const int n = 80000;
  for (int axis : {1, 2}) {
    double sum2 = 0.0, lag = 0.0;
    const int shift = static_cast<int>(options.correlation_time / dt);
    for (int i = 0; i < n; ++i) {
      const double x = moment.At(i * dt)[axis];
      sum2 += x * x;
      if (i + shift < n) lag += x * moment.At((i + shift) * dt)[axis];
    }
    const double rms = std::sqrt(sum2 / n);
    EXPECT_NEAR(rms, options.rms[axis], 0.05 * options.rms[axis]) << axis;
    // Exponentially correlated: exp(-1) one correlation time apart.
    EXPECT_NEAR(lag / (n - shift) / (rms * rms), std::exp(-1.0), 0.05) << axis;
  }
  EXPECT_EQ(moment.At(17.3)[0], 0.0);  // no roll moment asked for
}

TEST(RandomMoment, TheSeedDecides) {
  ProcessNoiseOptions options;
  options.rms = {1e-5, 3e-4, 3e-4};
  const RandomMoment a(options, 0.0, 5.0, 0.001);
  const RandomMoment b(options, 0.0, 5.0, 0.001);
  options.seed = 2;
  const RandomMoment c(options, 0.0, 5.0, 0.001);
  for (double t : {0.0, 0.0123, 2.5, 5.0}) {
    EXPECT_EQ(a.At(t), b.At(t));
    EXPECT_NE(a.At(t)[1], c.At(t)[1]);
  }
}

Case Table6Motion() {
  return LoadConfig(testing::SourcePath("configs/report/table6_motion.yaml"));
}

// The largest difference in theta and psi (deg) between two motions.
double Largest(const TimeHistory& a, const TimeHistory& b) {
  double worst = 0.0;
  for (int i = 0; i < a.size(); ++i) {
    worst = std::max({worst,
                      std::abs(a.theta[i] - b.theta[i]),
                      std::abs(a.psi[i] - b.psi[i])});
  }
  return worst;
}

TEST(RandomMoment, DrivesTheSimulatedMotionInProportion) {
  Case c = Table6Motion();
  c.noise.enabled = false;
  c.simulate.duration = 8.0;
  c.simulate.samples = 0;
  const TimeHistory quiet = Simulate(c);
  c.simulate.process_noise.rms = {0.0, 3e-5, 3e-5};
  c.simulate.process_noise.seed = 5;
  const TimeHistory noisy = Simulate(c);
  c.simulate.process_noise.rms = {0.0, 6e-5, 6e-5};
  const TimeHistory twice = Simulate(c);
  const double moved = Largest(quiet, noisy);
  // Random moments of 3e-5 move the 8-s Table 6 motion by about 0.2 deg
  // (3e-4 by 2 deg, mostly phase), and at this size the motion is linear
  // in them.
  EXPECT_GT(moved, 0.05);
  EXPECT_LT(moved, 1.0);
  EXPECT_NEAR(Largest(quiet, twice) / moved, 2.0, 0.2);
  // The same seed, the same motion; SimulateAt has no process noise.
  EXPECT_EQ(Largest(Simulate(c), twice), 0.0);
  EXPECT_EQ(Largest(SimulateAt(c, c.Values(), quiet.t), quiet), 0.0);
}

TEST(RandomMoment, ConfigKeysRoundTripAndBadOnesAreNamed) {
  const std::string base =
      "name: pn\nmodel: symmetric\n"
      "body: {area: 0.39, diameter: 0.7047, Ix: 0.0372, Iy: 0.244}\n"
      "flow: {velocity: 4774, dynamic_pressure: 150.4}\n"
      "parameters: {Cm_alpha: -0.236, theta0: 5}\n";
  const Case c = ParseConfig(
      base +
          "simulate: {dt: 0.01, duration: 1, process_noise: "
          "{pitch: 3.0e-4, yaw: 2.0e-4, correlation_time: 0.1, seed: 9}}\n",
      "pn.yaml",
      ".");
  const ProcessNoiseOptions& p = c.simulate.process_noise;
  EXPECT_EQ(p.rms[0], 0.0);
  EXPECT_EQ(p.rms[1], 3e-4);
  EXPECT_EQ(p.rms[2], 2e-4);
  EXPECT_EQ(p.correlation_time, 0.1);
  EXPECT_EQ(p.seed, 9u);
  EXPECT_EQ(ParseConfig(CaseToYaml(c), "again.yaml", "."), c);
  try {
    ParseConfig(base +
                    "simulate: {dt: 0.01, duration: 1, process_noise: "
                    "{pich: 3.0e-4}}\n",
                "pn.yaml",
                ".");
    FAIL() << "a misspelt axis was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("simulate.process_noise"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("pich"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(
      ParseConfig(base + "simulate: {dt: 0.01, duration: 1, process_noise: "
                         "{pitch: -1e-4}}\n",
                  "pn.yaml",
                  "."),
      InputError);
  EXPECT_THROW(
      ParseConfig(base + "simulate: {dt: 0.01, duration: 1, process_noise: "
                         "{pitch: 1e-4, correlation_time: 0}}\n",
                  "pn.yaml",
                  "."),
      InputError);
}

}  // namespace
}  // namespace fit3dof
