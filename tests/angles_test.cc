// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/angles.h"

#include <cmath>
#include <limits>

#include "ceres/jet.h"
#include "gtest/gtest.h"

namespace fit3dof {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// The series within a quarter turn, and the library beyond, agree with
// std::sin and std::cos to two units in the last place of sin x's size,
// and of 1 for cos x: over pitch and yaw angles, near zero, at the
// switch, and over a spinning model's many turns of roll.
TEST(SinCos, AgreesWithTheLibraryToTheLastBits) {
  for (int i = -200000; i <= 200000; ++i) {
    for (const double scale : {1e-6, 1.0, 4.0, 2000.0}) {
      const double x = scale * i / 200000.0;
      const double sin_x = std::sin(x);
      const double cos_x = std::cos(x);
      double s, c;
      SinCos(x, &s, &c);
      ASSERT_LE(std::abs(s - sin_x),
                2.0 * kEps * std::max(std::abs(sin_x), 1e-300))
          << x;
      ASSERT_LE(std::abs(c - cos_x), 2.0 * kEps) << x;  // |cos x| <= 1
    }
  }
}

TEST(SinCos, IsExactAtZeroAndOddAndEven) {
  double s, c;
  SinCos(0.0, &s, &c);
  EXPECT_EQ(s, 0.0);
  EXPECT_EQ(c, 1.0);
  for (const double x : {1e-300, 1e-8, 0.1, 0.5, 0.25 * M_PI, 2.0}) {
    double s1, c1, s2, c2;
    SinCos(x, &s1, &c1);
    SinCos(-x, &s2, &c2);
    EXPECT_EQ(s1, -s2) << x;
    EXPECT_EQ(c1, c2) << x;
  }
}

// A Jet's lanes carry cos x dx and -sin x dx, as ceres::sin and
// ceres::cos give them.
TEST(SinCos, CarriesTheDerivativesOfAJet) {
  using J = ceres::Jet<double, 2>;
  for (const double x : {-0.3, 0.05, 0.7, 3.0}) {
    J a(x, 0);
    a.v[1] = 2.5;
    J s, c;
    SinCos(a, &s, &c);
    const J s_ref = ceres::sin(a);
    const J c_ref = ceres::cos(a);
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(s.v[k], s_ref.v[k], 4.0 * kEps) << x;
      EXPECT_NEAR(c.v[k], c_ref.v[k], 4.0 * kEps) << x;
    }
    EXPECT_NEAR(s.a, s_ref.a, 2.0 * kEps);
    EXPECT_NEAR(c.a, c_ref.a, 2.0 * kEps);
  }
}

}  // namespace
}  // namespace fit3dof
