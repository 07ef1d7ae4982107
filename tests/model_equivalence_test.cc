// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// An axisymmetric body (I_y = I_z, I_zx = 0) flown by both programs: the
// symmetric case in aeroballistic axes and its ToAsymmetric image
// (model_conversion.h) in body axes must give the same phi, theta, psi.
// Every symmetric term with an exact image in the asymmetric expansion is
// switched on; this checks the conversion against the physics and
// cross-checks both sets of equations of motion, both moment models, both
// tunnel-term transformations and both initial-state definitions.

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "fit3dof/input_error.h"
#include "fit3dof/model_conversion.h"
#include "fit3dof/motion_model.h"
#include "fit3dof/parameters.h"
#include "gtest/gtest.h"

namespace fit3dof {
namespace {

// Every symmetric term with an image in the asymmetric expansion, at a
// realistic size, and a spinning, coning initial state.
Case SymmetricCase(Incidence incidence, double step) {
  Case c;
  c.model = ModelKind::kSymmetric;
  c.incidence = incidence;
  c.body = {0.39, 0.7047, 0.0372, 0.244, 0.244};
  c.flow = {4774.0, 150.4};
  c.solver.step = step;
  c.parameters.assign(NumParameters(ModelKind::kSymmetric), ParameterSetting{});
  const std::vector<std::pair<const char*, double>> values = {
      {"Cm_alpha", -0.236},
      {"Cm_q", -4.0},
      {"Cm_alpha_delta2", 5.81},
      {"Cm_q_delta2", 98.5},
      {"Cm_p_alpha", 0.8},
      {"Cl_0", -1e-4},
      {"Cl_p", -0.0081},
      {"Cl_p_delta2", -0.05},
      {"t1", 0.016},
      {"t2", -1.6},
      {"t3", -0.0055},
      {"t4", 2.2},
      {"theta_T", -0.13},
      {"psi_T", 0.15},
      {"phi0", 30.0},
      {"phidot0", 641.0},
      {"theta0", 5.18},
      {"thetadot0", -26.356},
      {"psi0", -2.589},
      {"psidot0", -7.77},
      {"theta_cos_phi", 0.05},
      {"theta_sin_phi", -0.03},
      {"psi_cos_phi", 0.04},
      {"psi_sin_phi", 0.02},
      {"Cm_0", 0.002},
      {"Cn_0", -0.0015},
      {"Cm_bearing", -0.02},
      {"bearing_angle", 1.0},
      {"theta_cal3", 0.02},
      {"psi_cal3", -0.015},
      {"Cn_beta_flow", -0.008},
      {"theta_lag", 0.006},
      {"psi_lag", -0.003},
      {"theta_gain", 0.02},
      {"Cm_friction", 0.0005},
      {"Cm_axis_friction", 0.0004},
      {"Cm_pitch_friction", 0.0003},
      {"Cn_yaw_friction", 0.0002},
      {"theta_cos_2phi", 0.03},
      {"theta_sin_2phi", -0.02},
      {"psi_cos_2phi", 0.01},
      {"psi_sin_2phi", 0.025},
      {"theta_cal2", 0.02},
      {"psi_cal2", -0.015},
      {"cal_range", 6.0}};
  for (const auto& [name, value] : values) {
    c.parameters[FindParameter(ModelKind::kSymmetric, name)].value = value;
  }
  return c;
}

// Largest difference (deg) over 10 s between the symmetric case and its
// ToAsymmetric image, each integrated by its own program.
double LargestDifference(
    Incidence incidence,
    double step,
    std::shared_ptr<const RandomMoment> random_moment = nullptr) {
  const Case symmetric_case = SymmetricCase(incidence, step);
  const Case asymmetric_case = ToAsymmetric(symmetric_case);
  std::vector<double> times;
  for (int i = 0; i <= 200; ++i) times.push_back(0.05 * i);
  const int n = static_cast<int>(times.size());
  const std::vector<double> sv = symmetric_case.Values();
  const std::vector<double> av = asymmetric_case.Values();
  MotionModel symmetric(symmetric_case.Spec(), ActiveParameters(sv, {}));
  MotionModel asymmetric(asymmetric_case.Spec(), ActiveParameters(av, {}));
  symmetric.set_random_moment(random_moment);
  asymmetric.set_random_moment(random_moment);
  std::vector<double> s(3 * n), a(3 * n);
  EXPECT_TRUE(
      symmetric.Evaluate(sv.data(), times.data(), n, s.data(), nullptr));
  EXPECT_TRUE(
      asymmetric.Evaluate(av.data(), times.data(), n, a.data(), nullptr));
  double worst = 0.0;
  for (int i = 0; i < 3 * n; ++i)
    worst = std::max(worst, std::abs(s[i] - a[i]));
  // The motion must be a real one: degrees of coning, hundreds of spin.
  EXPECT_GT(std::abs(s[3 * (n - 1)] - s[0]), 1000.0);
  return worst;
}

TEST(ModelEquivalence, AxisymmetricBodyGivesTheSameMotionInBothPrograms) {
  const double difference =
      LargestDifference(Incidence::kVelocityRatio, 0.0001);
  std::printf("velocity_ratio: largest difference %.3g deg over 10 s\n",
              difference);
  EXPECT_LT(difference, 1e-9);
}

// The comparison is not vacuous: each extension term moves the motion by
// more than 1e-3 deg (ten million times the agreement above).
// Process noise (random_moment.h) enters both programs' equations the same
// way: random tunnel-fixed pitch and yaw moments and a roll moment.
TEST(ModelEquivalence, ProcessNoiseGivesTheSameMotionInBothPrograms) {
  ProcessNoiseOptions options;
  options.rms = {2e-5, 3e-4, 3e-4};
  options.seed = 11;
  const auto moment = std::make_shared<RandomMoment>(options, 0.0, 10.0, 1e-4);
  const double difference =
      LargestDifference(Incidence::kVelocityRatio, 0.0001, moment);
  std::printf("with process noise: largest difference %.3g deg over 10 s\n",
              difference);
  EXPECT_LT(difference, 1e-9);
}

TEST(ModelEquivalence, TheExtensionTermsMoveTheMotion) {
  const Case all = SymmetricCase(Incidence::kVelocityRatio, 0.001);
  std::vector<double> times;
  for (int i = 0; i <= 200; ++i) times.push_back(0.05 * i);
  const int n = static_cast<int>(times.size());
  auto motion = [&](const Case& c) {
    const std::vector<double> v = c.Values();
    MotionModel model(c.Spec(), ActiveParameters(v, {}));
    std::vector<double> angles(3 * n);
    EXPECT_TRUE(
        model.Evaluate(v.data(), times.data(), n, angles.data(), nullptr));
    return angles;
  };
  const std::vector<double> reference = motion(all);
  for (const char* name : {"Cm_0",
                           "Cn_0",
                           "Cm_bearing",
                           "theta_cal3",
                           "psi_cal3",
                           "Cn_beta_flow",
                           "theta_lag",
                           "psi_lag",
                           "theta_gain",
                           "Cm_friction",
                           "Cm_axis_friction",
                           "Cm_pitch_friction",
                           "Cn_yaw_friction",
                           "theta_cos_2phi",
                           "theta_sin_2phi",
                           "psi_cos_2phi",
                           "psi_sin_2phi",
                           "theta_cal2",
                           "psi_cal2",
                           "cal_range"}) {
    Case without = all;
    without.parameters[FindParameter(ModelKind::kSymmetric, name)].value = 0.0;
    const std::vector<double> other = motion(without);
    double worst = 0.0;
    for (int i = 0; i < 3 * n; ++i)
      worst = std::max(worst, std::abs(other[i] - reference[i]));
    EXPECT_GT(worst, 1e-3) << name;
  }
}

// A term without an image is refused, not dropped.
TEST(ModelEquivalence, ATermWithoutAnImageIsRefused) {
  for (const char* name : SymmetricWithoutImage()) {
    Case c = SymmetricCase(Incidence::kVelocityRatio, 0.001);
    c.parameters[FindParameter(ModelKind::kSymmetric, name)].value = 0.1;
    EXPECT_THROW(ToAsymmetric(c), InputError) << name;
  }
}

// ToSymmetric undoes ToAsymmetric: every term's value and flags, the
// initial Euler rates of the defaults and of a segment (through body
// rates and back).
TEST(ModelEquivalence, ToSymmetricUndoesToAsymmetric) {
  Case c = SymmetricCase(Incidence::kVelocityRatio, 0.001);
  c.parameters[FindParameter(ModelKind::kSymmetric, "Cm_p_alpha")].free = true;
  c.parameters[FindParameter(ModelKind::kSymmetric, "Cm_q")].free = true;
  Segment segment;
  segment.name = "run1";
  for (int j = 0; j < 6; ++j) {
    segment.initial[j] = {10.0 * (j + 1), j % 2 == 0, false};
  }
  c.segments = {segment};
  const Case back = ToSymmetric(ToAsymmetric(c));
  ASSERT_EQ(back.model, ModelKind::kSymmetric);
  ASSERT_EQ(back.parameters.size(), c.parameters.size());
  const auto& table = ParameterTable(ModelKind::kSymmetric);
  for (size_t i = 0; i < c.parameters.size(); ++i) {
    EXPECT_NEAR(back.parameters[i].value, c.parameters[i].value, 1e-9)
        << table[i].name;
    EXPECT_EQ(back.parameters[i].free, c.parameters[i].free) << table[i].name;
  }
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR(
        back.segments[0].initial[j].value, segment.initial[j].value, 1e-9)
        << j;
    EXPECT_EQ(back.segments[0].initial[j].free, segment.initial[j].free) << j;
  }
}

// ImagesIn carries a term between the programs as ToAsymmetric and
// ToSymmetric do: each term of a case through its images gives the other
// program's case value for value.
TEST(ModelEquivalence, ImagesInCarryEachTermAsTheConversionsDo) {
  Case c = SymmetricCase(Incidence::kVelocityRatio, 0.001);
  const auto& sym = ParameterTable(ModelKind::kSymmetric);
  for (int i = 0; i < NumParameters(ModelKind::kSymmetric); ++i) {
    if (IsInitialCondition(ModelKind::kSymmetric, i)) continue;
    if (sym[i].scaling == Scaling::kUnused) continue;
    c.parameters[i].value = 0.01 * (i + 1);
  }
  for (const char* name : SymmetricWithoutImage()) {
    c.parameters[FindParameter(ModelKind::kSymmetric, name)].value = 0.0;
  }
  const Case a = ToAsymmetric(c);
  std::vector<double> carried(a.parameters.size(), 0.0);
  std::vector<double> back(c.parameters.size(), 0.0);
  for (int i = 0; i < NumParameters(ModelKind::kSymmetric); ++i) {
    if (IsInitialCondition(ModelKind::kSymmetric, i)) continue;
    for (const ImagePosition& image :
         ImagesIn(ModelKind::kAsymmetric, ModelKind::kSymmetric, sym[i].name)) {
      carried[image.position] = image.factor * c.parameters[i].value;
    }
  }
  const auto& asym = ParameterTable(ModelKind::kAsymmetric);
  for (int i = 0; i < NumParameters(ModelKind::kAsymmetric); ++i) {
    if (IsInitialCondition(ModelKind::kAsymmetric, i)) continue;
    EXPECT_NEAR(carried[i], a.parameters[i].value, 1e-12) << asym[i].name;
    for (const ImagePosition& image : ImagesIn(
             ModelKind::kSymmetric, ModelKind::kAsymmetric, asym[i].name)) {
      back[image.position] += image.factor * a.parameters[i].value;
    }
  }
  for (int i = 0; i < NumParameters(ModelKind::kSymmetric); ++i) {
    if (IsInitialCondition(ModelKind::kSymmetric, i)) continue;
    EXPECT_NEAR(back[i], c.parameters[i].value, 1e-12) << sym[i].name;
  }
  const std::vector<ImagePosition> same =
      ImagesIn(ModelKind::kSymmetric, ModelKind::kSymmetric, "Cm_q");
  ASSERT_EQ(same.size(), 1u);
  EXPECT_EQ(same[0].position, FindParameter(ModelKind::kSymmetric, "Cm_q"));
  EXPECT_TRUE(
      ImagesIn(ModelKind::kSymmetric, ModelKind::kAsymmetric, "Izx").empty());
  EXPECT_TRUE(ImagesIn(ModelKind::kSymmetric, ModelKind::kAsymmetric, "Cn_beta")
                  .empty());
  EXPECT_TRUE(
      ImagesIn(ModelKind::kAsymmetric, ModelKind::kSymmetric, "Cm_q_beta2")
          .empty());
  EXPECT_TRUE(
      ImagesIn(ModelKind::kAsymmetric, ModelKind::kSymmetric, "nonsense")
          .empty());
}

// A body asymmetry, a product of inertia or I_z apart from I_y has no
// place in the symmetric program: refused, each naming what it found.
TEST(ModelEquivalence, ToSymmetricRefusesAnAsymmetricBody) {
  const Case a = ToAsymmetric(SymmetricCase(Incidence::kVelocityRatio, 0.001));
  auto message = [](const Case& c) {
    try {
      ToSymmetric(c);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  Case untied = a;
  ParameterSetting& cn_beta =
      untied.parameters[FindParameter(ModelKind::kAsymmetric, "Cn_beta")];
  cn_beta = {0.25, true, false};
  EXPECT_NE(message(untied).find("Cn_beta"), std::string::npos)
      << message(untied);
  Case inertia = a;
  inertia.parameters[FindParameter(ModelKind::kAsymmetric, "Izx")].value = 1e-3;
  EXPECT_NE(message(inertia).find("Izx"), std::string::npos)
      << message(inertia);
  Case yaw = a;
  yaw.body.Iz = 1.1 * a.body.Iy;
  EXPECT_NE(message(yaw).find("I_z"), std::string::npos) << message(yaw);
}

// With angle of attack and sideslip the arctangent definitions do not rotate
// with roll, so the two programs describe slightly different aerodynamics.
TEST(ModelEquivalence, AngleOfAttackDefinitionsDifferSlightly) {
  const double difference =
      LargestDifference(Incidence::kAngleOfAttack, 0.0002);
  std::printf("angle_of_attack: largest difference %.3g deg over 10 s\n",
              difference);
  EXPECT_GT(difference, 1e-6);
  EXPECT_LT(difference, 0.5);
}

}  // namespace
}  // namespace fit3dof
