// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The bearing moment's fade g = tanh(x)/x (bearing_moment.h), which the
// bearing moment and the friction probes share: its values against the
// library's tanh, its slope in x^2 against a difference, and its Jet lanes
// against Ceres' own Jet arithmetic of the same function.

#include "fit3dof/bearing_moment.h"

#include <cmath>

#include "ceres/jet.h"
#include "gtest/gtest.h"

namespace fit3dof {
namespace {

// tanh(x)/x in long double, with x^2 = x2.
long double Reference(long double x2) {
  const long double x = std::sqrt(x2);
  return std::tanh(x) / x;
}

TEST(BearingFade, AgreesWithTanhOverEveryScale) {
  for (double x2 = 1e-8; x2 < 1e5; x2 *= 1.37) {
    const double g = BearingFade(x2);
    EXPECT_NEAR(g, static_cast<double>(Reference(x2)), 2e-14 * g)
        << "x^2 = " << x2;
  }
  EXPECT_EQ(BearingFade(0.0), 1.0);
}

TEST(BearingFade, IsContinuousWhereItsSeriesEnds) {
  // Above, tanh through exp loses up to a relative 1e-14 (bearing_moment.h).
  const double below = std::nextafter(1e-4, 0.0);
  EXPECT_NEAR(BearingFade(below), BearingFade(1e-4), 1e-14);
  double slope_below, slope_above;
  BearingFade(below, &slope_below);
  BearingFade(1e-4, &slope_above);
  EXPECT_NEAR(slope_below, slope_above, 1e-9);
}

TEST(BearingFade, SlopeIsTheDerivativeInTheSquare) {
  for (double x2 = 1e-6; x2 < 1e4; x2 *= 2.9) {
    double slope;
    BearingFade(x2, &slope);
    // A central difference in long double: truncation h^2 g''' / 6 and
    // rounding 1e-19 / h, both far below the tolerance.
    const long double h = 1e-4L * x2;
    const long double difference =
        (Reference(x2 + h) - Reference(x2 - h)) / (2.0L * h);
    EXPECT_NEAR(slope, static_cast<double>(difference), 1e-7 * std::abs(slope))
        << "x^2 = " << x2;
  }
}

TEST(BearingFade, JetLanesAreCeresOwn) {
  using Jet = ceres::Jet<double, 3>;
  // From where the series ends (below, the quotient of Jets loses digits).
  for (double x2 = 1e-4; x2 < 3e3; x2 *= 3.1) {
    Jet in(x2);
    in.v << 1.0, -2.5, 0.25 * x2;
    const Jet fade = BearingFade(in);
    // The form the fade had before: sqrt, tanh and a quotient of Jets.
    const Jet x = ceres::sqrt(in);
    const Jet expected = ceres::tanh(x) / x;
    EXPECT_NEAR(fade.a, expected.a, 2e-14 * expected.a);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(fade.v[i], expected.v[i], 1e-9 * std::abs(in.v[i]))
          << "x^2 = " << x2 << ", lane " << i;
    }
  }
}

}  // namespace
}  // namespace fit3dof
