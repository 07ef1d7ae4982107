// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/start_values.h"

#include <cmath>
#include <complex>

#include "fit3dof/angles.h"
#include "fit3dof/config.h"
#include "fit3dof/noise.h"
#include "fit3dof/simulator.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

// Two exact damped arms and a trim point are found exactly.
TEST(StartValues, MatrixPencilFindsTwoArms) {
  const std::complex<double> s1(-0.05, 7.2), s2(-0.08, -5.5);
  TimeHistory h;
  for (int i = 0; i < 200; ++i) {
    const double t = 0.06 * i;
    const std::complex<double> z =
        3.0 * std::exp(s1 * t) +
        std::complex<double>(1.0, 2.0) * std::exp(s2 * t) +
        std::complex<double>(0.3, -0.2);
    h.Append(t, 0.0, z.real(), z.imag());
  }
  const EpicyclicFit fit = FitEpicycle(h);
  ASSERT_TRUE(fit.ok) << fit.message;
  EXPECT_NEAR(fit.s1.real(), s1.real(), 1e-6);
  EXPECT_NEAR(fit.s1.imag(), s1.imag(), 1e-6);
  EXPECT_NEAR(fit.s2.real(), s2.real(), 1e-6);
  EXPECT_NEAR(fit.s2.imag(), s2.imag(), 1e-6);
}

// From the Table 6 record with 0.02 deg noise, the linear-theory estimates
// land near the truth (the nonlinear terms shift them a little).
TEST(StartValues, Table6LinearAerodynamicsFromTheMotion) {
  Case c =
      LoadConfig(testing::SourcePath("configs/report/table6_sigma0.02.yaml"));
  TimeHistory data = ReadTimeHistory(c.segments[0].data_file);
  AddNoise(c.noise, &data);
  std::vector<bool> wanted(c.parameters.size(), false);
  for (const char* p : {"Cm_alpha", "Cm_q", "Cm_alpha_delta2", "Cm_q_delta2"}) {
    wanted[FindParameter(c.model, p)] = true;
  }
  std::vector<double> values = c.Values();
  const auto log = EstimateStartValues(c, data, wanted, &values);
  for (const std::string& line : log) std::printf("%s\n", line.c_str());
  // Linear theory sees the stiffness at the motion's amplitude:
  // Cm_alpha + Cm_alpha_delta2 delta^2 with delta^2 averaged over the first
  // cycles (delta about 5 deg: -0.236 + 5.81 * 0.013).
  double delta2 = 0.0;
  int count = 0;
  for (int i = 0; i < data.size() && data.t[i] < 4.5; ++i, ++count) {
    delta2 += (std::pow(data.theta[i], 2) + std::pow(data.psi[i], 2)) *
              std::pow(kDegree, 2);
  }
  delta2 /= count;
  const double effective = -0.236 + 5.81 * delta2;
  EXPECT_NEAR(values[FindParameter(c.model, "Cm_alpha")],
              effective,
              0.25 * std::abs(effective));
  EXPECT_LT(values[FindParameter(c.model, "Cm_q")], 0.0);
  EXPECT_GT(values[FindParameter(c.model, "Cm_q")], -10.0);
  EXPECT_EQ(values[FindParameter(c.model, "Cm_q_delta2")], 0.0);
}

// Magnus and roll damping on a linear motion with spin.
TEST(StartValues, MagnusAndRollDamping) {
  Case c = LoadConfig(testing::SourcePath("configs/report/table6_motion.yaml"));
  auto set = [&](const char* p, double v) {
    c.parameters[FindParameter(c.model, p)].value = v;
  };
  set("Cm_alpha_delta2", 0.0);
  set("Cm_q_delta2", 0.0);
  set("Cm_p_alpha", 0.8);
  set("Cl_p", -0.05);
  std::vector<double> times;
  for (int i = 0; i < 800; ++i) times.push_back(0.06 * i);
  const TimeHistory data = SimulateAt(c, c.Values(), times);
  std::vector<bool> wanted(c.parameters.size(), false);
  for (const char* p : {"Cm_alpha", "Cm_q", "Cm_p_alpha", "Cl_p"}) {
    wanted[FindParameter(c.model, p)] = true;
  }
  std::vector<double> values(c.parameters.size(), 0.0);
  EstimateStartValues(c, data, wanted, &values);
  EXPECT_NEAR(values[FindParameter(c.model, "Cm_alpha")], -0.236, 0.01);
  EXPECT_NEAR(values[FindParameter(c.model, "Cm_q")], -4.0, 0.5);
  EXPECT_NEAR(values[FindParameter(c.model, "Cm_p_alpha")], 0.8, 0.3);
  EXPECT_NEAR(values[FindParameter(c.model, "Cl_p")], -0.05, 0.01);
}

}  // namespace
}  // namespace fit3dof
