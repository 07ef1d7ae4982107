// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The asymmetric program of AEDC-TR-78-10 (Table 2, Appendix A): a body with
// a plane of mirror symmetry (x-z), in body axes, with a product of inertia
// I_zx (parameter 60, fittable). State
//
//   x = (phi, theta, psi, p, q, r)   [rad, rad/s]
//
// with 3-2-1 Euler angles and body rates. The moment expansion is Eq. 14 as
// the listing's MBAR writes it (parameters 1-57), plus the tunnel-fixed
// terms of Eq. 41 (61-64).
//
// Sign convention of the product of inertia (Eq. 2 and the listing's FCT):
// h_x = I_x p - I_zx r, h_z = I_z r - I_zx p. Check Case II of the report
// (I_zx = -100) reproduces only with this sign.

#ifndef FIT3DOF_ASYMMETRIC_DYNAMICS_H_
#define FIT3DOF_ASYMMETRIC_DYNAMICS_H_

#include <cmath>

#include "fit3dof/angles.h"
#include "fit3dof/bearing_friction.h"
#include "fit3dof/bearing_moment.h"
#include "fit3dof/coefficients.h"
#include "fit3dof/parameters.h"
#include "fit3dof/random_moment.h"

namespace fit3dof {

enum AsymmetricState {
  kAsymPhi = 0,
  kAsymTheta = 1,
  kAsymPsi = 2,
  kAsymP = 3,
  kAsymQ = 4,
  kAsymR = 5,
};

struct AsymmetricConstants {
  double Ix = 0.0;
  double Iy = 0.0;
  double Iz = 0.0;
  Incidence incidence = Incidence::kVelocityRatio;
};

// Sines and cosines of the three Euler angles, shared by the moments and
// the equations of motion.
template <typename T>
struct AsymmetricTrig {
  AsymmetricTrig() = default;
  explicit AsymmetricTrig(const T* x) {
    SinCos(x[kAsymPhi], &sf, &cf);
    SinCos(x[kAsymTheta], &st, &ct);
    SinCos(x[kAsymPsi], &sp, &cp);
  }
  T sf, cf, st, ct, sp, cp;
};

// Moments divided by the inertia of their axis, body axes:
// mx = M_x/I_x, my = M_y/I_y, mz = M_z/I_z (the listing's MXOI, MYOI, MZOI).
// Tx is the state's scalar, Tk the coefficients' (coefficients.h).
template <typename Tx, typename Tk, typename T = Promoted<Tx, Tk>>
void AsymmetricMoments(const CoefficientView<Tk>& k,
                       const AsymmetricConstants& constants,
                       const Tx* x,
                       const AsymmetricTrig<Tx>& trig,
                       T* mx,
                       T* my,
                       T* mz,
                       const TunnelMoment* extra = nullptr) {
  using std::abs;
  using std::atan;
  const Tx& theta = x[kAsymTheta];
  const Tx& psi = x[kAsymPsi];
  const Tx& p = x[kAsymP];
  const Tx& q = x[kAsymQ];
  const Tx& r = x[kAsymR];
  const Tx& sf = trig.sf;
  const Tx& cf = trig.cf;
  const Tx& st = trig.st;
  const Tx& ct = trig.ct;
  const Tx& sp = trig.sp;
  const Tx& cp = trig.cp;

  // Eq. A-4 (TEMP): the free-stream direction in body axes.
  Tx a = sp * sf + cp * st * cf;
  Tx b = -sp * cf + cp * st * sf;
  if (constants.incidence == Incidence::kAngleOfAttack) {
    const Tx gamma = cp * ct;
    a = atan(a / gamma);
    b = atan(b / gamma);
  }
  const Tx a2 = a * a;
  const Tx b2 = b * b;
  const Tx aa = abs(a);
  const Tx ab = abs(b);
  const Tx aab = abs(a * b);

  // Rolling moment.
  T roll(0.0);
  if (k.on(47)) roll += k(47);
  if (k.on(48)) roll += k(48) * a;
  if (k.on(49)) roll += k(49) * b;
  if (k.on(50)) roll += k(50) * (a * b);
  if (k.on(51)) roll += k(51) * (aa * b);
  if (k.on(52)) roll += k(52) * (b * ab);
  T roll_damping(0.0);
  if (k.on(53)) roll_damping += k(53);
  if (k.on(54)) roll_damping += k(54) * aa;
  if (k.on(55)) roll_damping += k(55) * ab;
  if (k.on(56)) roll_damping += k(56) * a2;
  if (k.on(57)) roll_damping += k(57) * b2;
  *mx = roll + p * roll_damping;

  // Pitching moment.
  T pitch(0.0);
  if (k.on(1)) pitch += k(1);
  if (k.on(2)) pitch += k(2) * a;
  if (k.on(3)) pitch += k(3) * aa;
  if (k.on(4)) pitch += k(4) * a2;
  if (k.on(5)) pitch += k(5) * (a * aa);
  if (k.on(6)) pitch += k(6) * (a * a2);
  if (k.on(7)) pitch += k(7) * (aa * a2);
  if (k.on(8)) pitch += k(8) * ab;
  if (k.on(9)) pitch += k(9) * b2;
  if (k.on(10)) pitch += k(10) * (ab * b2);
  if (k.on(11)) pitch += k(11) * (a * ab);
  if (k.on(12)) pitch += k(12) * aab;
  if (k.on(13)) pitch += k(13) * (ab * a2);
  if (k.on(14)) pitch += k(14) * (a * aab);
  if (k.on(15)) pitch += k(15) * (a * b2);
  if (k.on(16)) pitch += k(16) * (aa * b2);
  T pitch_damping(0.0);
  if (k.on(17)) pitch_damping += k(17);
  if (k.on(18)) pitch_damping += k(18) * a;
  if (k.on(19)) pitch_damping += k(19) * aa;
  if (k.on(20)) pitch_damping += k(20) * a2;
  if (k.on(21)) pitch_damping += k(21) * (a * aa);
  if (k.on(22)) pitch_damping += k(22) * ab;
  if (k.on(23)) pitch_damping += k(23) * b2;
  if (k.on(24)) pitch_damping += k(24) * (a * ab);
  if (k.on(25)) pitch_damping += k(25) * aab;
  *my = pitch + q * pitch_damping;
  if (k.on(26)) *my += k(26) * r * b;
  if (k.on(27)) *my += k(27) * p * b;

  // Yawing moment.
  T yaw(0.0);
  if (k.on(28)) yaw += k(28);
  if (k.on(29)) yaw += k(29) * b;
  if (k.on(30)) yaw += k(30) * (a * b);
  if (k.on(31)) yaw += k(31) * (b * aa);
  if (k.on(32)) yaw += k(32) * (b * b2);
  if (k.on(33)) yaw += k(33) * (b * a2);
  if (k.on(34)) yaw += k(34) * (b * ab);
  if (k.on(35)) yaw += k(35) * (b * aab);
  T yaw_damping(0.0);
  if (k.on(36)) yaw_damping += k(36);
  if (k.on(37)) yaw_damping += k(37) * a;
  if (k.on(38)) yaw_damping += k(38) * aa;
  if (k.on(39)) yaw_damping += k(39) * a2;
  if (k.on(40)) yaw_damping += k(40) * ab;
  if (k.on(41)) yaw_damping += k(41) * b2;
  if (k.on(42)) yaw_damping += k(42) * (a * aa);
  if (k.on(43)) yaw_damping += k(43) * (a * ab);
  if (k.on(44)) yaw_damping += k(44) * aab;
  *mz = yaw + r * yaw_damping;
  if (k.on(45)) *mz += k(45) * q * b;
  if (k.on(46)) *mz += k(46) * p * a;
  // The gas bearing's moment (77, 78; bearing_moment.h): Cm_bearing is
  // scaled for pitch, I_y / I_z moves it to the yaw axis.
  if (k.on(77)) {
    const T fade = BearingFade((a2 + b2) / (k(78) * k(78)));
    *my += k(77) * a * fade;
    *mz -= k(77) * b * fade * (constants.Iy / constants.Iz);
  }
  // A yaw-plane stiffness of the flow (84; parameters.h): the moment
  // Cn_beta_flow beta' about the non-rolling frame's z axis, beta' the
  // sideslip in that frame (the body's a, b turned back by the roll
  // angle), taken to body axes as the symmetric program's trim moment is
  // brought from them. Scaled for pitch, as Cm_bearing.
  if (k.on(84)) {
    const T yaw = k(84) * (b * cf - a * sf);
    *my += yaw * sf;
    *mz += yaw * cf * (constants.Iy / constants.Iz);
  }
  // Dry friction of the bearing (88; bearing_friction.h), isotropic, so
  // written in the body rates as in the symmetric program's; scaled for
  // pitch, as Cm_bearing.
  if (k.on(88)) {
    T fy(0.0), fz(0.0);
    AddBearingFriction(k(88), q, r, &fy, &fz);
    *my += fy;
    *mz += fz * (constants.Iy / constants.Iz);
  }
  // Dry friction about each of the non-rolling frame's pitch and yaw axes
  // (89; bearing_friction.h): the body rates turned into that frame by the
  // roll angle, the moments turned back, as for Cn_beta_flow above.
  if (k.on(89) || k.on(90) || k.on(91)) {
    // The friction about each axis alone (90, 91) joins it there.
    const auto wy = q * cf - r * sf;
    const auto wz = r * cf + q * sf;
    T fy(0.0), fz(0.0);
    if (k.on(89)) {
      fy += AxisFriction(k(89), wy);
      fz += AxisFriction(k(89), wz);
    }
    if (k.on(90)) fy += AxisFriction(k(90), wy);
    if (k.on(91)) fz += AxisFriction(k(91), wz);
    *my += fy * cf + fz * sf;
    *mz += (fz * cf - fy * sf) * (constants.Iy / constants.Iz);
  }

  // Tunnel-fixed stiffness and damping, Eqs. 39 and 41. myt is M_yT / I_y
  // and mzt is M_zT / I_z; the ratios of inertias move them to the axis
  // they act on (the listing's RX1/RY1 and friends).
  const bool pitch_tunnel = k.on(62) || k.on(63);
  const bool yaw_tunnel = k.on(61) || k.on(64);
  // Process noise (simulate only; random_moment.h) joins them.
  if (pitch_tunnel || yaw_tunnel || extra != nullptr) {
    T myt(0.0), mzt(0.0);
    if (extra != nullptr) {
      myt += extra->pitch;
      mzt += extra->yaw;
      *mx += extra->roll;
    }
    if (k.on(63)) myt += k(63) * theta;
    if (k.on(62)) myt += k(62) * (q * cf - r * sf);  // thetadot
    if (k.on(64)) mzt += k(64) * psi;
    if (k.on(61)) mzt += k(61) * ((r * cf + q * sf) / ct);  // psidot
    const double iy_ix = constants.Iy / constants.Ix;
    const double iz_ix = constants.Iz / constants.Ix;
    const double iz_iy = constants.Iz / constants.Iy;
    const double iy_iz = constants.Iy / constants.Iz;
    *mx += myt * sp * ct * iy_ix - mzt * st * iz_ix;
    *my += myt * cp * cf + (myt * sp * st + mzt * ct * iz_iy) * sf;
    *mz += -myt * cp * sf * iy_iz + (myt * sp * st * iy_iz + mzt * ct) * cf;
  }
}

// Appendix A (the listing's FCT): 3-2-1 kinematics and Euler's equations
// with the product of inertia I_zx = k(60) (slug ft^2, not scaled).
// trig: the sines and cosines of x, given so that several coefficient
// scalars at one state share them.
template <typename Tx, typename Tk, typename T = Promoted<Tx, Tk>>
void AsymmetricDerivative(const CoefficientView<Tk>& k,
                          const AsymmetricConstants& constants,
                          const Tx* x,
                          const AsymmetricTrig<Tx>& trig,
                          T* dx,
                          const TunnelMoment* extra = nullptr) {
  T mx, my, mz;
  AsymmetricMoments(k, constants, x, trig, &mx, &my, &mz, extra);
  const Tx& p = x[kAsymP];
  const Tx& q = x[kAsymQ];
  const Tx& r = x[kAsymR];
  const Tx& sf = trig.sf;
  const Tx& cf = trig.cf;
  const Tx& st = trig.st;
  const Tx& ct = trig.ct;

  Tx euler_rates[3];
  BodyToEulerRates(sf,
                   cf,
                   st,
                   ct,
                   p,
                   q,
                   r,
                   &euler_rates[0],
                   &euler_rates[1],
                   &euler_rates[2]);
  dx[kAsymPhi] = T(euler_rates[0]);
  dx[kAsymTheta] = T(euler_rates[1]);
  dx[kAsymPsi] = T(euler_rates[2]);

  // Ix' = (I_z - I_y)/I_x etc.; J = I_zx / I. With h_x = I_x p - I_zx r and
  // h_z = I_z r - I_zx p, solving the x and z equations of
  // dh/dt + omega x h = M for pdot and rdot gives the listing's form.
  const double ixp = (constants.Iz - constants.Iy) / constants.Ix;
  const double iyp = (constants.Ix - constants.Iz) / constants.Iy;
  const double izp = (constants.Iy - constants.Ix) / constants.Iz;
  if (k.on(60)) {
    const Tk jx = k(60) / constants.Ix;
    const Tk jy = k(60) / constants.Iy;
    const Tk jz = k(60) / constants.Iz;
    const Tk rj = 1.0 - jx * jz;
    dx[kAsymP] =
        (mx + mz * jx - q * r * (jz * jx + ixp) + p * q * (1.0 - izp) * jx) /
        rj;
    dx[kAsymQ] = my - (p * p - r * r) * jy - r * p * iyp;
    dx[kAsymR] =
        (mz + mx * jz - p * q * (izp - jx * jz) - q * r * (1.0 + ixp) * jz) /
        rj;
  } else {
    dx[kAsymP] = mx - q * r * ixp;
    dx[kAsymQ] = my - r * p * iyp;
    dx[kAsymR] = mz - p * q * izp;
  }
}

// The same, computing the sines and cosines of x.
template <typename Tx, typename Tk, typename T = Promoted<Tx, Tk>>
void AsymmetricDerivative(const CoefficientView<Tk>& k,
                          const AsymmetricConstants& constants,
                          const Tx* x,
                          T* dx,
                          const TunnelMoment* extra = nullptr) {
  AsymmetricDerivative(k, constants, x, AsymmetricTrig<Tx>(x), dx, extra);
}

}  // namespace fit3dof

#endif  // FIT3DOF_ASYMMETRIC_DYNAMICS_H_
