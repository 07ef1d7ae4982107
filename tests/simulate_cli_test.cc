// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// `fit3dof simulate` end to end: the built command, real files.

#include <filesystem>
#include <string>

#include "fit3dof/config.h"
#include "fit3dof/time_history.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

namespace fs = std::filesystem;

TEST(SimulateCli, WritesTheTable6Motion) {
  const std::string dir = testing::ScratchDirectory("simulate_table6");
  const auto result = testing::RunFit3dof(
      "simulate " + testing::SourcePath("configs/report/table6_motion.yaml") +
      " --out=" + dir + "/table6.csv");
  ASSERT_EQ(result.exit_status, 0) << result.output;
  const TimeHistory h = ReadTimeHistory(dir + "/table6.csv");
  ASSERT_EQ(h.size(), 800);
  EXPECT_NEAR(h.t.back(), 799 * 0.06, 1e-9);
  EXPECT_DOUBLE_EQ(h.theta[0], 5.18);
  // The bundled report data is this command's output.
  const TimeHistory bundled = ReadTimeHistory(
      testing::SourcePath("configs/report/data/table6_clean.csv"));
  ASSERT_EQ(bundled.size(), h.size());
  for (int i = 0; i < h.size(); i += 97) {
    EXPECT_NEAR(bundled.theta[i], h.theta[i], 1e-9);
    EXPECT_NEAR(bundled.psi[i], h.psi[i], 1e-9);
  }
}

TEST(SimulateCli, AddsSeededNoise) {
  const std::string dir = testing::ScratchDirectory("simulate_noise");
  std::string config = testing::ReadText(
      testing::SourcePath("configs/report/table6_motion.yaml"));
  config += "noise: {sigma: {theta: 0.05}, bias: {psi: 0.5}, seed: 3}\n";
  testing::WriteText(dir + "/noisy.yaml", config);
  for (const char* out : {"a.csv", "b.csv"}) {
    const auto result = testing::RunFit3dof(
        "simulate " + dir + "/noisy.yaml --out=" + dir + "/" + out);
    ASSERT_EQ(result.exit_status, 0) << result.output;
  }
  const TimeHistory a = ReadTimeHistory(dir + "/a.csv");
  const TimeHistory b = ReadTimeHistory(dir + "/b.csv");
  EXPECT_EQ(a.theta, b.theta);  // same seed, same noise
  EXPECT_NE(a.theta[0], 5.18);
  EXPECT_NEAR(a.theta[0], 5.18, 0.25);
  EXPECT_NEAR(a.psi[0], -2.589 + 0.5, 1e-9);  // bias only
  EXPECT_DOUBLE_EQ(a.phi[0], 0.0);            // no phi noise
}

TEST(SimulateCli, BadConfigExitsTwoAndWritesNothing) {
  const std::string dir = testing::ScratchDirectory("simulate_bad");
  testing::WriteText(dir + "/bad.yaml",
                     "model: symmetric\n"
                     "body: {area: 0.39, diameter: 0.7, Ix: -0.03, Iy: 0.24}\n"
                     "flow: {velocity: 4774, dynamic_pressure: 150}\n"
                     "simulate: {dt: 0.01, duration: 1}\n");
  const auto result = testing::RunFit3dof(
      "simulate " + dir + "/bad.yaml --out=" + dir + "/out.csv");
  EXPECT_EQ(result.exit_status, 2) << result.output;
  EXPECT_NE(result.output.find("bad.yaml:2: body.Ix: must be positive"),
            std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(dir + "/out.csv"));
}

TEST(SimulateCli, DivergingMotionExitsTwoAndWritesNothing) {
  const std::string dir = testing::ScratchDirectory("simulate_diverge");
  testing::WriteText(dir + "/unstable.yaml",
                     "model: symmetric\n"
                     "body: {area: 0.39, diameter: 0.7, Ix: 0.03, Iy: 0.24}\n"
                     "flow: {velocity: 4774, dynamic_pressure: 150}\n"
                     "parameters: {Cm_alpha: 16.0, theta0: 5.0}\n"
                     "simulate: {dt: 0.01, duration: 5}\n");
  const auto result = testing::RunFit3dof(
      "simulate " + dir + "/unstable.yaml --out=" + dir + "/out.csv");
  EXPECT_EQ(result.exit_status, 2) << result.output;
  EXPECT_NE(result.output.find("singular at 90 deg"), std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(dir + "/out.csv"));
}

TEST(SimulateCli, UsageErrorsExitTwo) {
  EXPECT_EQ(testing::RunFit3dof("").exit_status, 2);
  EXPECT_EQ(testing::RunFit3dof("frobnicate x").exit_status, 2);
  EXPECT_EQ(testing::RunFit3dof("simulate").exit_status, 2);
  const auto flag = testing::RunFit3dof("simulate x.yaml --outt=y.csv");
  EXPECT_EQ(flag.exit_status, 2);
  EXPECT_NE(flag.output.find("unknown flag '--outt=y.csv'"), std::string::npos)
      << flag.output;
  EXPECT_NE(testing::RunFit3dof("simulate /nonexistent.yaml --out=/tmp/x.csv")
                .output.find("/nonexistent.yaml"),
            std::string::npos);
  const auto missing =
      testing::RunFit3dof("simulate /nonexistent.yaml --out=/tmp/x.csv");
  EXPECT_EQ(missing.exit_status, 2);
  EXPECT_NE(missing.output.find("/nonexistent.yaml"), std::string::npos);
}

}  // namespace
}  // namespace fit3dof
