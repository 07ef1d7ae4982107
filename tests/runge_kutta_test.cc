// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/runge_kutta.h"

#include <cmath>
#include <vector>

#include "fit3dof/config.h"
#include "fit3dof/motion_model.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

TEST(RungeKutta, SubstepsNeverExceedTheStep) {
  EXPECT_EQ(NumSubsteps(0.06, 0.001), 60);
  EXPECT_EQ(NumSubsteps(0.06, 0.025), 3);
  EXPECT_EQ(NumSubsteps(0.1, 0.01), 10);  // 0.1 / 0.01 is 10.000000000000002
  EXPECT_EQ(NumSubsteps(0.001, 0.01), 1);
}

// x'' = -x from (1, 0): exact solution cos t.
double OscillatorError(double step) {
  auto rhs = [](const double* x, double* dx) {
    dx[0] = x[1];
    dx[1] = -x[0];
  };
  double x[2] = {1.0, 0.0};
  const double times[2] = {0.0, 10.0};
  IntegrationFailure failure;
  StateGuard guard;
  guard.theta_index = 0;
  guard.max_abs_theta = 10.0;
  const bool ok = IntegrateSamples<double, 2>(
      rhs, times, 2, step, guard, x, [](int, const double*) {}, &failure);
  EXPECT_TRUE(ok);
  return std::abs(x[0] - std::cos(10.0));
}

TEST(RungeKutta, FourthOrderOnAnOscillator) {
  const double e1 = OscillatorError(0.02);
  const double e2 = OscillatorError(0.01);
  EXPECT_NEAR(e1 / e2, 16.0, 0.5);
}

// Against a reference at a much finer step: halving the step cuts the error
// of the full 3DOF motion about 16 times.
TEST(RungeKutta, FourthOrderOnThe3dofMotion) {
  Case c = LoadConfig(testing::SourcePath("configs/report/table6_motion.yaml"));
  const std::vector<double> values = c.Values();
  const std::vector<double> times = {0.0, 10.0};
  auto end_state = [&](double step) {
    ModelSpec spec = c.Spec();
    spec.max_step = step;
    MotionModel model(spec, ActiveParameters(values, c.FreeFlags()));
    std::vector<double> states(12);
    EXPECT_TRUE(model.EvaluateStates(
        values.data(), times.data(), 2, states.data(), nullptr));
    return std::vector<double>(states.begin() + 6, states.end());
  };
  const std::vector<double> reference = end_state(0.0002);
  auto error = [&](double step) {
    const std::vector<double> x = end_state(step);
    double worst = 0.0;
    // Angles only (phi, theta, psi): rates scale differently.
    for (int j : {0, 2, 4})
      worst = std::max(worst, std::abs(x[j] - reference[j]));
    return worst;
  };
  const double e1 = error(0.02);
  const double e2 = error(0.01);
  const double e3 = error(0.005);
  EXPECT_NEAR(e1 / e2, 16.0, 3.0) << e1 << " " << e2;
  EXPECT_NEAR(e2 / e3, 16.0, 3.0) << e2 << " " << e3;
}

TEST(RungeKutta, GuardStopsAtNinetyDegrees) {
  // theta grows linearly through 85 deg.
  auto rhs = [](const double* x, double* dx) {
    for (int j = 0; j < 6; ++j) dx[j] = 0.0;
    dx[2] = 1.0;
  };
  double x[6] = {0, 0, 0, 0, 0, 0};
  std::vector<double> times;
  for (int i = 0; i <= 20; ++i) times.push_back(0.1 * i);
  IntegrationFailure failure;
  int observed = 0;
  const bool ok = IntegrateSamples<double, 6>(
      rhs,
      times.data(),
      21,
      0.01,
      StateGuard(),
      x,
      [&](int, const double*) { ++observed; },
      &failure);
  EXPECT_FALSE(ok);
  EXPECT_NEAR(failure.time, 1.5, 1e-9);  // first sample past 1.4835 rad
  EXPECT_EQ(observed, 15);
  EXPECT_NE(failure.reason.find("90 deg"), std::string::npos);
}

}  // namespace
}  // namespace fit3dof
