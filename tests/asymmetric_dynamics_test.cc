// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/asymmetric_dynamics.h"

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "ceres/jet.h"
#include "fit3dof/motion_model.h"
#include "gtest/gtest.h"

namespace fit3dof {
namespace {

void Invariants(const Body& b,
                double izx,
                const double* x,
                Eigen::Vector3d* h,
                double* energy) {
  const double p = x[kAsymP], q = x[kAsymQ], r = x[kAsymR];
  // Eq. 2 with the listing's sign: h_x = I_x p - I_zx r, h_z = I_z r - I_zx p.
  const Eigen::Vector3d h_body(
      b.Ix * p - izx * r, b.Iy * q, b.Iz * r - izx * p);
  const Eigen::Matrix3d rotation =
      (Eigen::AngleAxisd(x[kAsymPsi], Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(x[kAsymTheta], Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(x[kAsymPhi], Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  *h = rotation * h_body;
  *energy =
      0.5 * (b.Ix * p * p + b.Iy * q * q + b.Iz * r * r - 2.0 * izx * p * r);
}

// Torque-free motion of a body with three different moments of inertia and a
// product of inertia conserves angular momentum and kinetic energy.
TEST(AsymmetricDynamics, TorqueFreeMotionConservesMomentumAndEnergy) {
  ModelSpec spec;
  spec.model = ModelKind::kAsymmetric;
  spec.body = {0.3491, 0.6667, 0.0301, 0.2583, 0.2465};
  spec.flow = {2000.0, 400.0};
  spec.max_step = 0.0005;
  std::vector<double> values(NumParameters(ModelKind::kAsymmetric), 0.0);
  values[59] = 0.012;  // Izx
  values[66] = 5.0;    // phi0
  values[67] = 12.0;   // theta0
  values[68] = -6.0;   // psi0
  values[69] = 500.0;  // p0
  values[70] = -40.0;  // q0
  values[71] = 55.0;   // r0
  MotionModel model(spec, ActiveParameters(values, {}));
  std::vector<double> times;
  for (int i = 0; i <= 100; ++i) times.push_back(0.1 * i);
  std::vector<double> states(6 * times.size());
  ASSERT_TRUE(model.EvaluateStates(values.data(),
                                   times.data(),
                                   static_cast<int>(times.size()),
                                   states.data(),
                                   nullptr));
  Eigen::Vector3d h0;
  double e0;
  Invariants(spec.body, values[59], &states[0], &h0, &e0);
  double worst_h = 0.0, worst_e = 0.0;
  for (size_t i = 1; i < times.size(); ++i) {
    Eigen::Vector3d h;
    double e;
    Invariants(spec.body, values[59], &states[6 * i], &h, &e);
    worst_h = std::max(worst_h, (h - h0).norm() / h0.norm());
    worst_e = std::max(worst_e, std::abs(e - e0) / e0);
  }
  EXPECT_LT(worst_h, 1e-9);
  EXPECT_LT(worst_e, 1e-9);
}

// The other sign of I_zx would not conserve the momentum defined with the
// listing's convention: the test above really checks the sign.
TEST(AsymmetricDynamics, ProductOfInertiaSignMatters) {
  const Body b{0.3491, 0.6667, 0.0301, 0.2583, 0.2465};
  const double x[6] = {0.1, 0.2, -0.1, 8.0, -0.7, 1.0};
  Eigen::Vector3d plus, minus;
  double e;
  Invariants(b, 0.012, x, &plus, &e);
  Invariants(b, -0.012, x, &minus, &e);
  EXPECT_GT((plus - minus).norm(), 1e-3);
}

TEST(AsymmetricDynamics, RunsWithJets) {
  using J = ceres::Jet<double, 4>;
  std::vector<J> c(kMaxParameters, J(0.0));
  std::vector<double> cd(kMaxParameters, 0.0);
  ActiveSet active;
  for (int i = 0; i < 64; ++i) {
    if (i == 57 || i == 58) continue;  // spares
    const double value = i == 59 ? 0.01 : 0.05 * ((i % 7) - 3);
    c[i] = J(value, i % 4);
    cd[i] = value;
    active[i] = true;
  }
  for (Incidence incidence :
       {Incidence::kVelocityRatio, Incidence::kAngleOfAttack}) {
    AsymmetricConstants constants{0.03, 0.25, 0.24, incidence};
    const double xd[6] = {0.4, 0.06, -0.03, 9.0, 0.3, -0.2};
    J xj[6], dxj[6];
    double dxd[6];
    for (int j = 0; j < 6; ++j) xj[j] = J(xd[j]);
    AsymmetricDerivative(
        CoefficientView<J>(c.data(), active), constants, xj, dxj);
    AsymmetricDerivative(
        CoefficientView<double>(cd.data(), active), constants, xd, dxd);
    for (int j = 0; j < 6; ++j) {
      EXPECT_NEAR(dxj[j].a, dxd[j], 1e-12 * (1.0 + std::abs(dxd[j])));
      EXPECT_TRUE(std::isfinite(dxj[j].v.norm()));
    }
  }
}

}  // namespace
}  // namespace fit3dof
