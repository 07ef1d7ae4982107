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

namespace fit3dof {

// g = tanh(x) / x with x^2 = delta^2 / delta_b^2.
template <typename T>
T BearingFade(const T& x2) {
  using std::sqrt;
  using std::tanh;
  // tanh(x)/x = 1 - x^2/3 + 2 x^4/15 - 17 x^6/315 + ...: exact to rounding
  // below 1e-4, where the quotient would lose digits.
  if (x2 < 1e-4) return 1.0 - x2 / 3.0 + 2.0 / 15.0 * x2 * x2;
  const T x = sqrt(x2);
  return tanh(x) / x;
}

}  // namespace fit3dof

#endif  // FIT3DOF_BEARING_MOMENT_H_
