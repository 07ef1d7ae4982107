// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Angles and angular rates, one definition each: degrees and radians
// (kDegree), and Euler rates (phidot, thetadot, psidot) against body rates
// (p, q, r) for the 3-2-1 sequence psi, theta, phi of AEDC-TR-78-10,
// Appendix A. The asymmetric equations of motion use BodyToEulerRates; the
// initial-condition estimates and ToAsymmetric (model_conversion.h) use
// EulerToBodyRates (the listing's ICS). Templated on the scalar so that
// ceres::Jet flows through.
//
// Example Usage:
//
//   double p, q, r;
//   EulerToBodyRates(std::sin(phi * kDegree), std::cos(phi * kDegree),
//                    std::sin(theta * kDegree), std::cos(theta * kDegree),
//                    phidot, thetadot, psidot, &p, &q, &r);

#ifndef FIT3DOF_ANGLES_H_
#define FIT3DOF_ANGLES_H_

#include <cmath>

#include "ceres/jet.h"

namespace fit3dof {

// Radians per degree, and degrees per radian.
inline constexpr double kDegree = M_PI / 180.0;
inline constexpr double kDegreesPerRadian = 180.0 / M_PI;

// The whole turns in an angle of `degrees`, in degrees: subtracting them
// takes a roll difference to the branch nearest zero (-180..180), as roll
// is compared modulo 360 deg (the listing's INTGRL).
inline double WholeTurns(double degrees) {
  return 360.0 * std::round(degrees / 360.0);
}

// sin x and cos x from one evaluation of each at x's value: for a Jet the
// derivative lanes are cos x * dx and -sin x * dx, as ceres::sin and
// ceres::cos give them, but those two compute both functions each. Half
// the calls; the equations of motion take their sines and cosines here
// (SymmetricTrig, AsymmetricTrig). Within a quarter turn of zero, where
// the pitch and yaw angles of a model on the bearing stay, they are their
// Taylor series to x^17 and x^18 (truncated at under 1e-19 there), within
// two units in the last place of the library's (angles_test.cc): glibc's
// sincos took 15% of a diagnosis, and each stage of the integrator waits
// for it. The series' polynomials in x^2 are evaluated in Estrin's
// scheme, pairs of terms side by side, whose chain of dependent
// operations is half Horner's: 14 ns against the library's 24 on a chain
// of dependent calls. Beyond a quarter turn (the roll angle), the
// library's.
inline void SinCos(double x, double* s, double* c) {
  if (std::abs(x) > 0.25 * M_PI) {
    *s = std::sin(x);
    *c = std::cos(x);
    return;
  }
  // (-1)^k / (2k+1)! and (-1)^k / (2k+2)!, k = 1..8.
  constexpr double s1 = -1.0 / 6.0, s2 = 1.0 / 120.0, s3 = -1.0 / 5040.0,
                   s4 = 1.0 / 362880.0, s5 = -1.0 / 39916800.0,
                   s6 = 1.0 / 6227020800.0, s7 = -1.0 / 1307674368000.0,
                   s8 = 1.0 / 355687428096000.0;
  constexpr double c1 = 1.0 / 24.0, c2 = -1.0 / 720.0, c3 = 1.0 / 40320.0,
                   c4 = -1.0 / 3628800.0, c5 = 1.0 / 479001600.0,
                   c6 = -1.0 / 87178291200.0, c7 = 1.0 / 20922789888000.0,
                   c8 = -1.0 / 6402373705728000.0;
  const double z = x * x;
  const double z2 = z * z;
  const double z4 = z2 * z2;
  const double ps = (s1 + s2 * z) + z2 * (s3 + s4 * z) +
                    z4 * ((s5 + s6 * z) + z2 * (s7 + s8 * z));
  const double pc = (c1 + c2 * z) + z2 * (c3 + c4 * z) +
                    z4 * ((c5 + c6 * z) + z2 * (c7 + c8 * z));
  *s = x + x * z * ps;
  *c = 1.0 - 0.5 * z + z2 * pc;
}
template <typename T, int N>
void SinCos(const ceres::Jet<T, N>& x,
            ceres::Jet<T, N>* s,
            ceres::Jet<T, N>* c) {
  T sa, ca;
  SinCos(x.a, &sa, &ca);
  *s = ceres::Jet<T, N>(sa, ca * x.v);
  *c = ceres::Jet<T, N>(ca, -sa * x.v);
}

// Body rates from Euler rates at roll phi and pitch theta, given their
// sines and cosines. Any unit of rate; the result is in the same one.
template <typename T>
void EulerToBodyRates(const T& sf,
                      const T& cf,
                      const T& st,
                      const T& ct,
                      const T& phidot,
                      const T& thetadot,
                      const T& psidot,
                      T* p,
                      T* q,
                      T* r) {
  *p = phidot - psidot * st;
  *q = thetadot * cf + psidot * ct * sf;
  *r = psidot * ct * cf - thetadot * sf;
}

// Euler rates from body rates: the kinematic equations of Appendix A
// (singular at theta = +-90 deg, where cos theta = 0).
template <typename T>
void BodyToEulerRates(const T& sf,
                      const T& cf,
                      const T& st,
                      const T& ct,
                      const T& p,
                      const T& q,
                      const T& r,
                      T* phidot,
                      T* thetadot,
                      T* psidot) {
  const T sec = 1.0 / ct;
  const T q_sf_r_cf = q * sf + r * cf;
  *phidot = p + st * sec * q_sf_r_cf;
  *thetadot = q * cf - r * sf;
  *psidot = q_sf_r_cf * sec;
}

}  // namespace fit3dof

#endif  // FIT3DOF_ANGLES_H_
