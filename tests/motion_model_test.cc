// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/motion_model.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "ceres/jet.h"
#include "fit3dof/random_moment.h"
#include "fit3dof/symmetric_dynamics.h"
#include "gtest/gtest.h"

namespace fit3dof {
namespace {

ModelSpec SymmetricSpec(Incidence incidence) {
  ModelSpec spec;
  spec.model = ModelKind::kSymmetric;
  spec.incidence = incidence;
  spec.body = {0.39, 0.7047, 0.0372, 0.244, 0.244};
  spec.flow = {4774.0, 150.4};
  spec.max_step = 0.002;
  return spec;
}

std::vector<double> SymmetricValues() {
  std::vector<double> v(NumParameters(ModelKind::kSymmetric), 0.0);
  auto set = [&](const char* name, double value) {
    v[FindParameter(ModelKind::kSymmetric, name)] = value;
  };
  set("Cm_alpha", -0.236);
  set("Cm_q", -4.0);
  set("Cm_alpha_delta", 0.3);
  set("Cm_p_alpha", 0.5);
  set("Cm_alpha_delta2", 5.81);
  set("Cm_q_delta2", 98.5);
  set("Cm_q_beta2", 10.0);
  set("Cm_r_alpha_beta", 5.0);
  set("Cm_q_delta", 3.0);
  set("Cl_0", -1e-4);
  set("Cl_p_delta", -0.01);
  set("Cm_p_alpha_delta2", 2.0);
  set("Cl_p", -0.0081);
  set("Cl_p_delta2", -0.05);
  set("Cm_alphadot", -0.5);
  set("t4", 1.3);
  set("t2", -0.5);
  set("t1", 0.015);
  set("t3", -0.005);
  set("theta_T", -0.1);
  set("psi_T", 0.15);
  set("phidot0", 641.0);
  set("theta0", 5.18);
  set("thetadot0", -26.356);
  set("psi0", -2.589);
  set("psidot0", -7.77);
  set("theta_cos_phi", 0.05);
  set("theta_sin_phi", -0.03);
  set("psi_cos_phi", 0.04);
  set("psi_sin_phi", 0.02);
  return v;
}

std::vector<double> AsymmetricValues() {
  std::vector<double> v(NumParameters(ModelKind::kAsymmetric), 0.0);
  for (int i = 0; i < 57; ++i) v[i] = 0.02 * ((i * 7) % 11 - 5);  // all terms
  v[FindParameter(ModelKind::kAsymmetric, "Cm_alpha")] = -0.23;
  v[FindParameter(ModelKind::kAsymmetric, "Cn_beta")] = 0.22;
  v[FindParameter(ModelKind::kAsymmetric, "Cm_q")] = -5.0;
  v[FindParameter(ModelKind::kAsymmetric, "Cn_r")] = -5.5;
  v[FindParameter(ModelKind::kAsymmetric, "Cl_p")] = -0.008;
  v[FindParameter(ModelKind::kAsymmetric, "Izx")] = 0.002;
  for (int i = 60; i < 64; ++i) v[i] = 0.01 * (i - 61);
  v[64] = -0.1;
  v[65] = 0.15;
  v[66] = 20.0;
  v[67] = 5.0;
  v[68] = -3.0;
  v[69] = 600.0;
  v[70] = -20.0;
  v[71] = 10.0;
  return v;
}

// Derivatives of the simulated angles carried by Jets through scaling,
// moments, equations of motion, RK4 and the measurement model agree with
// central differences.
template <int N>
void CheckJetDerivatives(const ModelSpec& spec,
                         const std::vector<double>& values,
                         const std::vector<int>& wrt) {
  ASSERT_EQ(static_cast<int>(wrt.size()), N);
  using J = ceres::Jet<double, N>;
  std::vector<double> times;
  for (int i = 0; i <= 40; ++i) times.push_back(0.05 * i);
  const int n = static_cast<int>(times.size());
  std::vector<bool> free(values.size(), false);
  for (int i : wrt) free[i] = true;
  const MotionModel model(spec, ActiveParameters(values, free));
  std::vector<J> jet_values(values.size());
  for (size_t i = 0; i < values.size(); ++i) jet_values[i] = J(values[i]);
  for (int d = 0; d < N; ++d) jet_values[wrt[d]].v[d] = 1.0;
  std::vector<J> angles(3 * n);
  ASSERT_TRUE(model.Evaluate(
      jet_values.data(), times.data(), n, angles.data(), nullptr));
  for (int d = 0; d < N; ++d) {
    double scale = 0.0;  // deg per unit of the parameter
    for (int i = 0; i < 3 * n; ++i)
      scale = std::max(scale, std::abs(angles[i].v[d]));
    ASSERT_GT(scale, 0.0) << "parameter " << wrt[d] << " has no effect";
    // A step that moves the angles by about 1e-3 deg: well above the
    // roundoff in phi (thousands of degrees), well inside the linear range.
    const double h = 1e-3 / scale;
    std::vector<double> plus = values, minus = values;
    plus[wrt[d]] += h;
    minus[wrt[d]] -= h;
    std::vector<double> ap(3 * n), am(3 * n);
    ASSERT_TRUE(
        model.Evaluate(plus.data(), times.data(), n, ap.data(), nullptr));
    ASSERT_TRUE(
        model.Evaluate(minus.data(), times.data(), n, am.data(), nullptr));
    for (int i = 0; i < 3 * n; ++i) {
      const double numeric = (ap[i] - am[i]) / (2.0 * h);
      EXPECT_NEAR(angles[i].v[d], numeric, 1e-5 * scale)
          << "parameter " << ParameterTable(spec.model)[wrt[d]].name
          << " sample " << i / 3 << " channel " << i % 3;
    }
  }
}

TEST(MotionModel, SymmetricJetDerivativesMatchCentralDifferences) {
  std::vector<int> all;
  for (int i = 0; i < 30; ++i) {
    if (i < 15 || (i >= 18 && i < 30)) all.push_back(i);
  }
  ASSERT_EQ(all.size(), 27u);
  const std::vector<double> values = SymmetricValues();
  CheckJetDerivatives<27>(
      SymmetricSpec(Incidence::kVelocityRatio), values, all);
  CheckJetDerivatives<27>(
      SymmetricSpec(Incidence::kAngleOfAttack), values, all);
}

TEST(MotionModel, AsymmetricJetDerivativesMatchCentralDifferences) {
  ModelSpec spec;
  spec.model = ModelKind::kAsymmetric;
  spec.body = {0.3491, 0.6667, 0.0301, 0.2583, 0.2465};
  spec.flow = {2000.0, 300.0};
  spec.max_step = 0.002;
  const std::vector<double> values = AsymmetricValues();
  // A spread of terms: static, absolute-value, rate, roll, Izx, tunnel,
  // offsets and every initial condition.
  const std::vector<int> wrt = {0,  1,  2,  5,  11, 13, 16, 18, 24, 26, 28,
                                30, 34, 35, 40, 45, 47, 52, 56, 59, 60, 61,
                                62, 63, 64, 65, 66, 67, 68, 69, 70, 71};
  for (Incidence incidence :
       {Incidence::kVelocityRatio, Incidence::kAngleOfAttack}) {
    spec.incidence = incidence;
    CheckJetDerivatives<32>(spec, values, wrt);
  }
}

// Skipping the terms of frozen zero parameters changes nothing.
TEST(MotionModel, InactiveTermsAreExactlyZero) {
  const ModelSpec spec = SymmetricSpec(Incidence::kVelocityRatio);
  std::vector<double> values(NumParameters(ModelKind::kSymmetric), 0.0);
  values[0] = -0.236;
  values[1] = -4.0;
  values[25] = 641.0;
  values[26] = 5.18;
  const std::vector<double> times = {0.0, 1.0, 2.0};
  ActiveSet all;
  all.set();
  std::vector<double> a(9), b(9);
  ASSERT_TRUE(MotionModel(spec, all).Evaluate(
      values.data(), times.data(), 3, a.data(), nullptr));
  ASSERT_TRUE(MotionModel(spec, ActiveParameters(values, {}))
                  .Evaluate(values.data(), times.data(), 3, b.data(), nullptr));
  for (int i = 0; i < 9; ++i) EXPECT_EQ(a[i], b[i]);
}

// theta_T and psi_T shift the measured angles and nothing else.
TEST(MotionModel, FlowOffsetsShiftTheMeasurement) {
  const ModelSpec spec = SymmetricSpec(Incidence::kVelocityRatio);
  std::vector<double> values(NumParameters(ModelKind::kSymmetric), 0.0);
  values[0] = -0.236;
  values[26] = 5.0;
  const std::vector<double> times = {0.0, 0.5, 1.0};
  std::vector<double> shifted = values;
  shifted[22] = 0.25;
  shifted[23] = -0.5;
  std::vector<double> a(9), b(9);
  const MotionModel model(spec, ActiveParameters(shifted, {}));
  ASSERT_TRUE(
      model.Evaluate(values.data(), times.data(), 3, a.data(), nullptr));
  ASSERT_TRUE(
      model.Evaluate(shifted.data(), times.data(), 3, b.data(), nullptr));
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(b[3 * i], a[3 * i]);
    EXPECT_NEAR(b[3 * i + 1] - a[3 * i + 1], 0.25, 1e-12);
    EXPECT_NEAR(b[3 * i + 2] - a[3 * i + 2], -0.5, 1e-12);
  }
}

// theta_drift and psi_drift add a reading error growing from the
// record's first sample (not from t = 0), and their sensitivities are that
// elapsed time.
TEST(MotionModel, ReadingDriftGrowsFromTheFirstSample) {
  const ModelSpec spec = SymmetricSpec(Incidence::kVelocityRatio);
  std::vector<double> values(NumParameters(ModelKind::kSymmetric), 0.0);
  values[0] = -0.236;
  values[26] = 5.0;
  const int drift = Layout(ModelKind::kSymmetric).drift;
  EXPECT_EQ(ParameterTable(ModelKind::kSymmetric)[drift].name, "theta_drift");
  const std::vector<double> times = {2.0, 2.5, 4.0};
  std::vector<double> drifting = values;
  drifting[drift] = 0.01;
  drifting[drift + 1] = -0.02;
  const MotionModel model(spec, ActiveParameters(drifting, {}));
  std::vector<double> a(9), b(9), jacobian(18);
  ASSERT_TRUE(
      model.Evaluate(values.data(), times.data(), 3, a.data(), nullptr));
  const int wrt[2] = {drift, drift + 1};
  ASSERT_TRUE(model.EvaluateWithSensitivities(drifting.data(),
                                              wrt,
                                              2,
                                              times.data(),
                                              3,
                                              b.data(),
                                              jacobian.data(),
                                              nullptr));
  for (int i = 0; i < 3; ++i) {
    const double elapsed = times[i] - times[0];
    EXPECT_DOUBLE_EQ(b[3 * i], a[3 * i]);
    EXPECT_NEAR(b[3 * i + 1] - a[3 * i + 1], 0.01 * elapsed, 1e-12);
    EXPECT_NEAR(b[3 * i + 2] - a[3 * i + 2], -0.02 * elapsed, 1e-12);
    // Rows phi, theta, psi of sample i; columns theta_drift, psi_drift.
    EXPECT_NEAR(jacobian[6 * i + 2], elapsed, 1e-12);
    EXPECT_NEAR(jacobian[6 * i + 3], 0.0, 1e-12);
    EXPECT_NEAR(jacobian[6 * i + 5], elapsed, 1e-12);
  }
}

// q_drift scales every moment by 1 + q_drift (t - t_0): the model's
// midpoint-held factor (Integrate) against RK4 at a tenth of the step
// with the factor at each stage's own time, through the same equations.
TEST(MotionModel, DynamicPressureDriftScalesEveryMomentInTime) {
  ModelSpec spec = SymmetricSpec(Incidence::kVelocityRatio);
  // The hold errs at second order in the step (1e-7 rad at 2 ms), RK4 at
  // fourth: at 0.2 ms both are far below the comparison's tolerance.
  spec.max_step = 2e-4;
  const ModelKind kind = ModelKind::kSymmetric;
  std::vector<double> values = SymmetricValues();
  const int drift = Layout(kind).q_drift;
  EXPECT_EQ(ParameterTable(kind)[drift].name, "q_drift");
  values[drift] = 0.05;
  std::vector<double> times;
  for (int i = 0; i < 41; ++i) times.push_back(3.0 + 0.05 * i);
  const MotionModel model(spec, ActiveParameters(values, {}));
  std::vector<double> states(6 * times.size());
  ASSERT_TRUE(model.EvaluateStates(
      values.data(), times.data(), times.size(), states.data(), nullptr));

  const std::vector<double> scale =
      InternalScaleFactors(kind, spec.body, spec.flow);
  std::vector<double> internal(kMaxParameters, 0.0), at(kMaxParameters);
  for (int i = 0; i < NumParameters(kind); ++i)
    internal[i] = values[i] * scale[i];
  const ActiveSet active = ActiveParameters(values, {});
  SymmetricConstants constants;
  constants.ratio = spec.body.Ix / spec.body.Iy;
  auto rhs = [&](double t, const double* x, double* dx) {
    at = internal;
    for (int i = 0; i < NumParameters(kind); ++i) {
      const Scaling s = ParameterTable(kind)[i].scaling;
      if (s != Scaling::kAngle && s != Scaling::kAngleRate &&
          s != Scaling::kPerSecond) {
        at[i] *= 1.0 + values[drift] * (t - times[0]);
      }
    }
    SymmetricDerivative(
        CoefficientView<double>(at.data(), active), constants, x, dx);
  };
  double x[6], k1[6], k2[6], k3[6], k4[6], y[6];
  for (int j = 0; j < 6; ++j) x[j] = internal[Layout(kind).first_initial + j];
  const double h = 2e-5;
  double t = times[0];
  for (size_t i = 0; i < times.size(); ++i) {
    while (t < times[i] - 1e-9) {
      rhs(t, x, k1);
      for (int j = 0; j < 6; ++j) y[j] = x[j] + 0.5 * h * k1[j];
      rhs(t + 0.5 * h, y, k2);
      for (int j = 0; j < 6; ++j) y[j] = x[j] + 0.5 * h * k2[j];
      rhs(t + 0.5 * h, y, k3);
      for (int j = 0; j < 6; ++j) y[j] = x[j] + h * k3[j];
      rhs(t + h, y, k4);
      for (int j = 0; j < 6; ++j)
        x[j] += h / 6.0 * (k1[j] + 2.0 * (k2[j] + k3[j]) + k4[j]);
      t += h;
    }
    for (int j = 0; j < 6; ++j) {
      EXPECT_NEAR(states[6 * i + j], x[j], 1e-8 * (1.0 + std::abs(x[j])))
          << "sample " << i << " state " << j;
    }
  }
  // Without the drift the motion differs by far more than that.
  std::vector<double> steady = values, still(states.size());
  steady[drift] = 0.0;
  ASSERT_TRUE(model.EvaluateStates(
      steady.data(), times.data(), times.size(), still.data(), nullptr));
  EXPECT_GT(std::abs(still[still.size() - 4] - states[states.size() - 4]),
            1e-3);
}

TEST(MotionModel, ReportsABlowUp) {
  ModelSpec spec = SymmetricSpec(Incidence::kVelocityRatio);
  std::vector<double> values(NumParameters(ModelKind::kSymmetric), 0.0);
  values[0] = +16.0;  // statically unstable: theta runs away
  values[26] = 5.0;
  std::vector<double> times;
  for (int i = 0; i < 100; ++i) times.push_back(0.05 * i);
  std::vector<double> angles(300);
  IntegrationFailure failure;
  EXPECT_FALSE(
      MotionModel(spec, ActiveParameters(values, {}))
          .Evaluate(values.data(), times.data(), 100, angles.data(), &failure));
  EXPECT_GT(failure.time, 0.0);
  EXPECT_FALSE(failure.reason.empty());
}

// The Table 6 motion: its four coefficients and initial conditions.
std::vector<double> Table6Values() {
  std::vector<double> v(NumParameters(ModelKind::kSymmetric), 0.0);
  const std::pair<const char*, double> table6[] = {{"Cm_alpha", -0.236},
                                                   {"Cm_q", -4.0},
                                                   {"Cm_alpha_delta2", 5.81},
                                                   {"Cm_q_delta2", 98.5},
                                                   {"phidot0", 641.0},
                                                   {"theta0", 5.18},
                                                   {"thetadot0", -26.356},
                                                   {"psi0", -2.589},
                                                   {"psidot0", -7.77}};
  for (const auto& [name, value] : table6) {
    v[FindParameter(ModelKind::kSymmetric, name)] = value;
  }
  return v;
}

// The filter-error predictor (EvaluateFiltered): with zero gains its
// innovations are the measurement less Evaluate's angles, exactly (roll
// modulo 360 deg); with gains that reset the angles to the readings, a
// random moment the model lacks leaves only one interval's prediction error
// in the innovations, far below the open-loop residual; and Jets through it
// give the derivatives of the held-gain filter (central differences).
struct FilterCase {
  ModelSpec spec = SymmetricSpec(Incidence::kVelocityRatio);
  std::vector<double> values = Table6Values();
  std::vector<double> times;
  std::vector<double> measured;     // 3 per sample, deg
  std::vector<double> reset_gains;  // angles set to the readings

  explicit FilterCase(double rms_moment, double correlation_time = 0.05) {
    for (int i = 0; i <= 200; ++i) times.push_back(0.02 * i);
    MotionModel truth(spec, ActiveParameters(values, {}));
    ProcessNoiseOptions noise;
    noise.rms = {0.0, rms_moment, rms_moment};
    noise.correlation_time = correlation_time;
    noise.seed = 7;
    truth.set_random_moment(std::make_shared<const RandomMoment>(
        noise, times.front(), times.back(), spec.max_step));
    measured.resize(3 * times.size());
    EXPECT_TRUE(truth.Evaluate(values.data(),
                               times.data(),
                               static_cast<int>(times.size()),
                               measured.data(),
                               nullptr));
    reset_gains.assign(18 * times.size(), 0.0);
    const int angle_rows[3] = {kSymPhi, kSymTheta, kSymPsi};
    for (size_t i = 0; i < times.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        reset_gains[18 * i + 3 * angle_rows[c] + c] = kDegree;
      }
    }
  }
  int n() const { return static_cast<int>(times.size()); }

  // The readings with white noise of `sigma` deg added.
  std::vector<double> Noisy(double sigma, unsigned seed) const {
    std::mt19937 generator(seed);
    std::normal_distribution<double> normal(0.0, sigma);
    std::vector<double> noisy = measured;
    for (double& m : noisy) m += normal(generator);
    return noisy;
  }
};

double Rms(const std::vector<double>& v, int channel) {
  double sum = 0.0;
  for (size_t i = channel; i < v.size(); i += 3) sum += v[i] * v[i];
  return std::sqrt(sum / (v.size() / 3));
}

TEST(MotionModelFiltered, ZeroGainsGiveTheOutputErrorResiduals) {
  FilterCase f(3e-4);
  const MotionModel model(f.spec, ActiveParameters(f.values, {}));
  std::vector<double> angles(3 * f.n()), innovations(3 * f.n());
  const std::vector<double> zero(18 * f.n(), 0.0);
  ASSERT_TRUE(model.Evaluate(
      f.values.data(), f.times.data(), f.n(), angles.data(), nullptr));
  ASSERT_TRUE(model.EvaluateFiltered(f.values.data(),
                                     f.times.data(),
                                     f.n(),
                                     f.measured.data(),
                                     zero.data(),
                                     innovations.data(),
                                     nullptr));
  for (int i = 0; i < 3 * f.n(); ++i) {
    double expected = f.measured[i] - angles[i];
    if (i % 3 == 0) expected -= 360.0 * std::round(expected / 360.0);
    EXPECT_EQ(innovations[i], expected) << i;
  }
  EXPECT_GT(Rms(innovations, 1), 0.05);  // the random moment shows open loop
}

TEST(MotionModelFiltered, ResettingGainsLeaveOneIntervalsError) {
  FilterCase f(3e-4);
  const MotionModel model(f.spec, ActiveParameters(f.values, {}));
  std::vector<double> open(3 * f.n()), filtered(3 * f.n());
  const std::vector<double> zero(18 * f.n(), 0.0);
  ASSERT_TRUE(model.EvaluateFiltered(f.values.data(),
                                     f.times.data(),
                                     f.n(),
                                     f.measured.data(),
                                     zero.data(),
                                     open.data(),
                                     nullptr));
  ASSERT_TRUE(model.EvaluateFiltered(f.values.data(),
                                     f.times.data(),
                                     f.n(),
                                     f.measured.data(),
                                     f.reset_gains.data(),
                                     filtered.data(),
                                     nullptr));
  for (int c = 1; c < 3; ++c) {
    EXPECT_LT(Rms(filtered, c), 0.1 * Rms(open, c)) << "channel " << c;
  }
  // Without process noise and with the true parameters there is nothing to
  // correct: every innovation vanishes, whatever the gains.
  FilterCase clean(0.0);
  ASSERT_TRUE(model.EvaluateFiltered(clean.values.data(),
                                     clean.times.data(),
                                     clean.n(),
                                     clean.measured.data(),
                                     clean.reset_gains.data(),
                                     filtered.data(),
                                     nullptr));
  for (double e : filtered) EXPECT_NEAR(e, 0.0, 1e-9);
}

TEST(MotionModelFiltered, JetsGiveTheHeldGainDerivatives) {
  FilterCase f(3e-4);
  const int wrt[2] = {FindParameter(ModelKind::kSymmetric, "Cm_alpha"),
                      FindParameter(ModelKind::kSymmetric, "thetadot0")};
  std::vector<bool> free(f.values.size(), false);
  for (int i : wrt) free[i] = true;
  const MotionModel model(f.spec, ActiveParameters(f.values, free));
  // Gains that pull the angles halfway to the readings.
  std::vector<double> gains = f.reset_gains;
  for (double& g : gains) g *= 0.5;
  using J = ceres::Jet<double, 2>;
  std::vector<J> jets(f.values.begin(), f.values.end());
  for (int d = 0; d < 2; ++d) jets[wrt[d]].v[d] = 1.0;
  std::vector<J> innovations(3 * f.n());
  ASSERT_TRUE(model.EvaluateFiltered(jets.data(),
                                     f.times.data(),
                                     f.n(),
                                     f.measured.data(),
                                     gains.data(),
                                     innovations.data(),
                                     nullptr));
  for (int d = 0; d < 2; ++d) {
    const double h = 1e-6 * std::max(1.0, std::abs(f.values[wrt[d]]));
    std::vector<double> plus = f.values, minus = f.values;
    plus[wrt[d]] += h;
    minus[wrt[d]] -= h;
    std::vector<double> ep(3 * f.n()), em(3 * f.n());
    ASSERT_TRUE(model.EvaluateFiltered(plus.data(),
                                       f.times.data(),
                                       f.n(),
                                       f.measured.data(),
                                       gains.data(),
                                       ep.data(),
                                       nullptr));
    ASSERT_TRUE(model.EvaluateFiltered(minus.data(),
                                       f.times.data(),
                                       f.n(),
                                       f.measured.data(),
                                       gains.data(),
                                       em.data(),
                                       nullptr));
    double scale = 0.0;
    for (const J& e : innovations) scale = std::max(scale, std::abs(e.v[d]));
    ASSERT_GT(scale, 0.0);
    for (int i = 0; i < 3 * f.n(); ++i) {
      EXPECT_NEAR(
          innovations[i].v[d], (ep[i] - em[i]) / (2.0 * h), 1e-5 * scale)
          << "parameter " << wrt[d] << " row " << i;
    }
  }
}

// The extended Kalman filter (Filter): a fit that holds its gains sees its
// innovations exactly; without process noise it is output error (no gain,
// S = R); and at the random moment's own intensity its innovations are
// white with the covariance it claims, where the deviance is least.
constexpr double kSigma = 0.01;  // deg

MotionModel::FilterRun RunFilter(const MotionModel& model,
                                 const FilterCase& f,
                                 const std::vector<double>& measured,
                                 double intensity) {
  MotionModel::FilterRun run;
  EXPECT_TRUE(model.Filter(f.values.data(),
                           f.times.data(),
                           f.n(),
                           measured.data(),
                           {0.0, intensity, intensity},
                           {kSigma, kSigma, kSigma},
                           &run,
                           nullptr));
  return run;
}

TEST(MotionModelFilter, HeldGainsReproduceItsInnovations) {
  FilterCase f(3e-4);
  const MotionModel model(f.spec, ActiveParameters(f.values, {}));
  const std::vector<double> measured = f.Noisy(kSigma, 3);
  const MotionModel::FilterRun run = RunFilter(model, f, measured, 2.0);
  std::vector<double> innovations(3 * f.n());
  ASSERT_TRUE(model.EvaluateFiltered(f.values.data(),
                                     f.times.data(),
                                     f.n(),
                                     measured.data(),
                                     run.gains.data(),
                                     innovations.data(),
                                     nullptr));
  for (int i = 0; i < 3 * f.n(); ++i) {
    EXPECT_EQ(innovations[i], run.innovations[i]) << i;
  }
  double largest_gain = 0.0;
  for (double g : run.gains) largest_gain = std::max(largest_gain, std::abs(g));
  EXPECT_GT(largest_gain, 0.01 * kDegree);
}

TEST(MotionModelFilter, WithoutProcessNoiseItIsOutputError) {
  FilterCase f(3e-4);
  const MotionModel model(f.spec, ActiveParameters(f.values, {}));
  const std::vector<double> measured = f.Noisy(kSigma, 4);
  const MotionModel::FilterRun run = RunFilter(model, f, measured, 0.0);
  std::vector<double> angles(3 * f.n());
  ASSERT_TRUE(model.Evaluate(
      f.values.data(), f.times.data(), f.n(), angles.data(), nullptr));
  double deviance = 0.0;
  for (int i = 0; i < 3 * f.n(); ++i) {
    double expected = measured[i] - angles[i];
    if (i % 3 == 0) expected -= 360.0 * std::round(expected / 360.0);
    EXPECT_EQ(run.innovations[i], expected) << i;
    deviance +=
        expected * expected / (kSigma * kSigma) + std::log(kSigma * kSigma);
  }
  EXPECT_NEAR(run.deviance, deviance, 1e-9 * std::abs(deviance));
  for (double g : run.gains) EXPECT_EQ(g, 0.0);
}

// The random moment's intensity as the filter's white acceleration: the
// spectral density at zero frequency of a Gauss-Markov process of RMS s
// and correlation time tau is 2 s^2 tau, turned into deg/s^2 by qSd/I.
double TrueIntensity(const ModelSpec& spec, double rms, double tau) {
  const double per_coefficient = spec.flow.dynamic_pressure * spec.body.area *
                                 spec.body.diameter / spec.body.Iy;
  return std::sqrt(2.0 * tau) * rms * per_coefficient * kDegreesPerRadian;
}

TEST(MotionModelFilter, InnovationsAreWhiteAtTheTrueIntensity) {
  // A correlation time well below the sample interval: the moment is
  // white as the filter models it.
  const double rms = 1e-3, tau = 0.002;
  FilterCase f(rms, tau);
  const MotionModel model(f.spec, ActiveParameters(f.values, {}));
  const double truth = TrueIntensity(f.spec, rms, tau);
  double best = 0.0, least = INFINITY;
  for (double factor = 0.25; factor < 4.01; factor *= std::sqrt(2.0)) {
    double deviance = 0.0;
    for (unsigned seed = 0; seed < 4; ++seed) {
      deviance +=
          RunFilter(model, f, f.Noisy(kSigma, seed), truth * factor).deviance;
    }
    if (deviance < least) {
      least = deviance;
      best = factor;
    }
  }
  EXPECT_GE(best, 0.7);
  EXPECT_LE(best, 1.42);
  // Normalized innovations e^T S^-1 e average 3 (their dimension), and
  // neighbours are uncorrelated.
  const MotionModel::FilterRun run =
      RunFilter(model, f, f.Noisy(kSigma, 9), truth);
  double sum = 0.0, lag1 = 0.0, power = 0.0;
  std::vector<double> theta(f.n());
  for (int i = 0; i < f.n(); ++i) {
    const Eigen::Map<const Eigen::Matrix3d> s(&run.covariance[9 * i]);
    const Eigen::Map<const Eigen::Vector3d> e(&run.innovations[3 * i]);
    sum += e.dot(s.inverse() * e);
    theta[i] = e[1] / std::sqrt(s(1, 1));
  }
  for (int i = 1; i < f.n(); ++i) {
    lag1 += theta[i] * theta[i - 1];
    power += theta[i] * theta[i];
  }
  EXPECT_NEAR(sum / f.n(), 3.0, 0.45);
  EXPECT_LT(std::abs(lag1 / power), 0.2);
}

}  // namespace
}  // namespace fit3dof
