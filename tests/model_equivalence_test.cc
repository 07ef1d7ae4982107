// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// An axisymmetric body (I_y = I_z, I_zx = 0) flown by both programs: the
// symmetric one in aeroballistic axes and the asymmetric one in body axes
// must give the same phi, theta, psi. Every symmetric term with an exact
// image in the asymmetric expansion is switched on; this cross-checks both
// sets of equations of motion, both moment models, both tunnel-term
// transformations and both initial-state definitions.

#include <cmath>
#include <cstdio>
#include <vector>

#include "fit3dof/motion_model.h"
#include "gtest/gtest.h"

namespace fit3dof {
namespace {

const double kDeg = M_PI / 180.0;

int Sym(const char* name) { return FindParameter(ModelKind::kSymmetric, name); }
int Asym(const char* name) {
  return FindParameter(ModelKind::kAsymmetric, name);
}

struct Pair {
  std::vector<double> symmetric;
  std::vector<double> asymmetric;
};

Pair MatchingParameters() {
  Pair p{std::vector<double>(NumParameters(ModelKind::kSymmetric), 0.0),
         std::vector<double>(NumParameters(ModelKind::kAsymmetric), 0.0)};
  auto& s = p.symmetric;
  auto& a = p.asymmetric;
  s[Sym("Cm_alpha")] = -0.236;
  s[Sym("Cm_q")] = -4.0;
  s[Sym("Cm_alpha_delta2")] = 5.81;
  s[Sym("Cm_q_delta2")] = 98.5;
  s[Sym("Cm_p_alpha")] = 0.8;
  s[Sym("Cl_0")] = -1e-4;
  s[Sym("Cl_p")] = -0.0081;
  s[Sym("Cl_p_delta2")] = -0.05;
  s[Sym("t1")] = 0.016;
  s[Sym("t2")] = -1.6;
  s[Sym("t3")] = -0.0055;
  s[Sym("t4")] = 2.2;
  s[Sym("theta_T")] = -0.13;
  s[Sym("psi_T")] = 0.15;
  // alpha (C1 + C5 delta^2) -> Cm_alpha alpha + C5 (alpha^3 + alpha beta^2);
  // -beta (C1 + C5 delta^2) -> Cn_beta beta + Cn_beta3 beta^3 + ...
  a[Asym("Cm_alpha")] = s[Sym("Cm_alpha")];
  a[Asym("Cn_beta")] = -s[Sym("Cm_alpha")];
  a[Asym("Cm_alpha3")] = s[Sym("Cm_alpha_delta2")];
  a[Asym("Cm_alpha_beta2")] = s[Sym("Cm_alpha_delta2")];
  a[Asym("Cn_beta3")] = -s[Sym("Cm_alpha_delta2")];
  a[Asym("Cn_alpha2_beta")] = -s[Sym("Cm_alpha_delta2")];
  // q (C2 + C6 delta^2), r (C2 + C6 delta^2).
  a[Asym("Cm_q")] = s[Sym("Cm_q")];
  a[Asym("Cn_r")] = s[Sym("Cm_q")];
  a[Asym("Cm_q_alpha2")] = s[Sym("Cm_q_delta2")];
  a[Asym("Cm_q_beta2")] = s[Sym("Cm_q_delta2")];
  a[Asym("Cn_r_alpha2")] = s[Sym("Cm_q_delta2")];
  a[Asym("Cn_r_beta2")] = s[Sym("Cm_q_delta2")];
  // Magnus: p beta C4 in pitch, p alpha C4 in yaw.
  a[Asym("Cm_p_beta")] = s[Sym("Cm_p_alpha")];
  a[Asym("Cn_p_alpha")] = s[Sym("Cm_p_alpha")];
  a[Asym("Cl_0")] = s[Sym("Cl_0")];
  a[Asym("Cl_p")] = s[Sym("Cl_p")];
  a[Asym("Cl_p_alpha2")] = s[Sym("Cl_p_delta2")];
  a[Asym("Cl_p_beta2")] = s[Sym("Cl_p_delta2")];
  for (const char* name : {"t1", "t2", "t3", "t4", "theta_T", "psi_T"}) {
    a[Asym(name)] = s[Sym(name)];
  }
  // Initial state: Euler rates -> body rates (the listing's ICS).
  const double phi = 30.0, phidot = 641.0, theta = 5.18, thetadot = -26.356,
               psi = -2.589, psidot = -7.77;
  s[Sym("phi0")] = phi;
  s[Sym("phidot0")] = phidot;
  s[Sym("theta0")] = theta;
  s[Sym("thetadot0")] = thetadot;
  s[Sym("psi0")] = psi;
  s[Sym("psidot0")] = psidot;
  a[Asym("phi0")] = phi;
  a[Asym("theta0")] = theta;
  a[Asym("psi0")] = psi;
  const double sf = std::sin(phi * kDeg), cf = std::cos(phi * kDeg);
  const double st = std::sin(theta * kDeg), ct = std::cos(theta * kDeg);
  a[Asym("p0")] = phidot - psidot * st;
  a[Asym("q0")] = thetadot * cf + psidot * ct * sf;
  a[Asym("r0")] = psidot * ct * cf - thetadot * sf;
  return p;
}

// Largest difference (deg) between the two formulations over 10 s.
double LargestDifference(Incidence incidence, double step) {
  const Pair p = MatchingParameters();
  ModelSpec spec;
  spec.incidence = incidence;
  spec.body = {0.39, 0.7047, 0.0372, 0.244, 0.244};
  spec.flow = {4774.0, 150.4};
  spec.max_step = step;
  std::vector<double> times;
  for (int i = 0; i <= 200; ++i) times.push_back(0.05 * i);
  const int n = static_cast<int>(times.size());
  spec.model = ModelKind::kSymmetric;
  MotionModel symmetric(spec, ActiveParameters(p.symmetric, {}));
  spec.model = ModelKind::kAsymmetric;
  MotionModel asymmetric(spec, ActiveParameters(p.asymmetric, {}));
  std::vector<double> s(3 * n), a(3 * n);
  EXPECT_TRUE(symmetric.Evaluate(
      p.symmetric.data(), times.data(), n, s.data(), nullptr));
  EXPECT_TRUE(asymmetric.Evaluate(
      p.asymmetric.data(), times.data(), n, a.data(), nullptr));
  double worst = 0.0;
  for (int i = 0; i < 3 * n; ++i)
    worst = std::max(worst, std::abs(s[i] - a[i]));
  // The motion must be a real one: degrees of coning, hundreds of spin.
  EXPECT_GT(std::abs(s[3 * (n - 1)] - s[0]), 1000.0);
  return worst;
}

TEST(ModelEquivalence, AxisymmetricBodyGivesTheSameMotionInBothPrograms) {
  EXPECT_LT(LargestDifference(Incidence::kVelocityRatio, 0.0002), 1e-8);
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
