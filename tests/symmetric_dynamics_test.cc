// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/symmetric_dynamics.h"

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "ceres/jet.h"
#include "fit3dof/angles.h"
#include "fit3dof/motion_model.h"
#include "gtest/gtest.h"

namespace fit3dof {
namespace {

// Inertial angular momentum and kinetic energy of the axisymmetric body for
// a symmetric-model state. The aeroballistic frame is Rz(psi) Ry(theta) of
// the tunnel frame; its angular velocity in itself is Eq. 5.
void Invariants(const Body& b,
                const double* x,
                Eigen::Vector3d* h,
                double* energy) {
  const double theta = x[kSymTheta], psi = x[kSymPsi];
  const double p = x[kSymPhiDot] - x[kSymPsiDot] * std::sin(theta);
  const double q = x[kSymThetaDot];
  const double r = x[kSymPsiDot] * std::cos(theta);
  const Eigen::Vector3d h_aero(b.Ix * p, b.Iy * q, b.Iy * r);
  const Eigen::Matrix3d rotation =
      (Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()))
          .toRotationMatrix();
  *h = rotation * h_aero;
  *energy = 0.5 * (b.Ix * p * p + b.Iy * (q * q + r * r));
}

// With every moment zero the motion is torque-free: angular momentum (in the
// tunnel frame) and kinetic energy stay constant to integration accuracy.
TEST(SymmetricDynamics, TorqueFreeMotionConservesMomentumAndEnergy) {
  ModelSpec spec;
  spec.model = ModelKind::kSymmetric;
  spec.body = {0.39, 0.7047, 0.0372, 0.244, 0.244};
  spec.flow = {4774.0, 150.4};
  spec.max_step = 0.001;
  std::vector<double> values(NumParameters(ModelKind::kSymmetric), 0.0);
  // A large coning motion: theta up to ~25 deg, spin 641 deg/s.
  values[24] = 10.0;   // phi0
  values[25] = 641.0;  // phidot0
  values[26] = 20.0;   // theta0
  values[27] = -60.0;  // thetadot0
  values[28] = -15.0;  // psi0
  values[29] = 80.0;   // psidot0
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
  Invariants(spec.body, &states[0], &h0, &e0);
  double worst_h = 0.0, worst_e = 0.0;
  for (size_t i = 1; i < times.size(); ++i) {
    Eigen::Vector3d h;
    double e;
    Invariants(spec.body, &states[6 * i], &h, &e);
    worst_h = std::max(worst_h, (h - h0).norm() / h0.norm());
    worst_e = std::max(worst_e, std::abs(e - e0) / e0);
  }
  EXPECT_LT(worst_h, 1e-9);
  EXPECT_LT(worst_e, 1e-9);
  // And the motion is far from trivial: theta swings by degrees.
  double theta_min = 1e9, theta_max = -1e9;
  for (size_t i = 0; i < times.size(); ++i) {
    theta_min = std::min(theta_min, states[6 * i + kSymTheta]);
    theta_max = std::max(theta_max, states[6 * i + kSymTheta]);
  }
  EXPECT_GT(theta_max - theta_min, 5.0 * kDegree);
}

// The listing's MBAR for a hand-checked state: pure stiffness gives
// M_y/I = alpha C1, M_z/I = -beta C1 with the velocity ratios of Eq. 9.
TEST(SymmetricDynamics, StiffnessActsAlongTheIncidence) {
  std::vector<double> c(kMaxParameters, 0.0);
  ActiveSet active;
  c[0] = -40.0;
  active[0] = true;
  CoefficientView<double> k(c.data(), active);
  SymmetricConstants constants{0.15, Incidence::kVelocityRatio};
  const double x[6] = {0.3, 10.0, 4.0 * kDegree, 0.0, -2.0 * kDegree, 0.0};
  double mx, my, mz;
  SymmetricMoments(k, constants, x, SymmetricTrig<double>(x), &mx, &my, &mz);
  EXPECT_DOUBLE_EQ(my, -40.0 * std::cos(x[4]) * std::sin(x[2]));
  EXPECT_DOUBLE_EQ(mz, -40.0 * std::sin(x[4]));
  EXPECT_DOUBLE_EQ(mx, 0.0);
}

// Compiles and runs with ceres::Jet, and the Jet's value equals the double
// computation.
TEST(SymmetricDynamics, RunsWithJets) {
  using J = ceres::Jet<double, 3>;
  std::vector<J> c(kMaxParameters, J(0.0));
  ActiveSet active;
  for (int i :
       {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 18, 19, 20, 21}) {
    c[i] = J(0.1 * (i + 1), i % 3);
    active[i] = true;
  }
  std::vector<double> cd(kMaxParameters);
  for (int i = 0; i < kMaxParameters; ++i) cd[i] = c[i].a;
  for (Incidence incidence :
       {Incidence::kVelocityRatio, Incidence::kAngleOfAttack}) {
    SymmetricConstants constants{0.15, incidence};
    const double xd[6] = {0.3, 10.0, 0.07, 0.2, -0.04, 0.3};
    J xj[6], dxj[6];
    double dxd[6];
    for (int j = 0; j < 6; ++j) xj[j] = J(xd[j]);
    SymmetricDerivative(
        CoefficientView<J>(c.data(), active), constants, xj, dxj);
    SymmetricDerivative(
        CoefficientView<double>(cd.data(), active), constants, xd, dxd);
    for (int j = 0; j < 6; ++j) {
      EXPECT_DOUBLE_EQ(dxj[j].a, dxd[j]);
      EXPECT_TRUE(std::isfinite(dxj[j].v.norm()));
    }
  }
}

}  // namespace
}  // namespace fit3dof
