// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The gas bearing's own moment (Section 5.2 of AEDC-TR-78-10), shared by
// both programs. The report's pendulum study found, at 400 psi bearing
// pressure, moments "near psi and theta equal to zero" that acted like an
// extra stiffness at small angles (the equivalent Cm_alpha of a pendulum
// was a factor of three off at small angles and right at moderate ones),
// proportional to the angle (M_y = 0.330 alpha ft-lbf, M_z = -0.330 beta).
// So its form here is a stiffness that fades beyond a saturation angle:
//
//   M_y / (q S d) = Cm_bearing alpha g(delta),
//   M_z / (q S d) = -Cm_bearing beta g(delta),
//   g(delta) = tanh(delta / delta_b) / (delta / delta_b),
//
// linear (g = 1) for delta << delta_b = bearing_angle and of constant size
// Cm_bearing delta_b beyond it. g is even and smooth in delta: written in
// delta^2 it needs no square root at zero incidence, where Jets would get
// an infinite derivative.
//
// Templated on the scalar so that ceres::Jet flows through.

#ifndef FIT3DOF_BEARING_MOMENT_H_
#define FIT3DOF_BEARING_MOMENT_H_

#include <cmath>

#include "ceres/jet.h"

namespace fit3dof {

// g = tanh(x) / x with x^2 = delta^2 / delta_b^2, and (when `slope` is not
// null) its derivative with respect to x^2, from one evaluation of exp:
// glibc's tanh goes through expm1, which took 10% of a Table 6 diagnosis
// with a bearing moment, twice the time of exp. tanh x = (1 - e)/(1 + e),
// e = exp(-2x), loses to the difference 1 - e a relative 1e-14 at most
// where it is used (x >= 0.01); below, where the quotient would lose
// digits, tanh(x)/x = 1 - x^2/3 + 2 x^4/15 - 17 x^6/315 + 62 x^8/2835 -
// ..., whose first omitted term is 1e-22 there (without the last two
// terms, 5e-14 and a slope 2e-9 off). dg/d(x^2) = ((1 - tanh^2 x) - g) /
// (2 x^2).
inline double BearingFade(double x2, double* slope) {
  if (x2 < 1e-4) {
    if (slope != nullptr) {
      *slope = -1.0 / 3.0 +
               x2 * (4.0 / 15.0 + x2 * (-17.0 / 105.0 + x2 * 248.0 / 2835.0));
    }
    return 1.0 +
           x2 * (-1.0 / 3.0 +
                 x2 * (2.0 / 15.0 + x2 * (-17.0 / 315.0 + x2 * 62.0 / 2835.0)));
  }
  const double x = std::sqrt(x2);
  const double e = std::exp(-2.0 * x);
  const double t = (1.0 - e) / (1.0 + e);
  const double g = t / x;
  if (slope != nullptr) *slope = ((1.0 - t * t) - g) / (2.0 * x2);
  return g;
}

inline double BearingFade(double x2) { return BearingFade(x2, nullptr); }

// For a Jet the derivative lanes are dg/d(x^2) times x^2's: one scalar
// evaluation instead of a Jet's square root, tanh and quotient.
template <int N>
ceres::Jet<double, N> BearingFade(const ceres::Jet<double, N>& x2) {
  double slope;
  const double g = BearingFade(x2.a, &slope);
  return ceres::Jet<double, N>(g, slope * x2.v);
}

}  // namespace fit3dof

#endif  // FIT3DOF_BEARING_MOMENT_H_
