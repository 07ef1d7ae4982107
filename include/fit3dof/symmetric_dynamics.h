// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The symmetric program of AEDC-TR-78-10 (Table 1): an axially symmetric
// body (I_y = I_z = I) in aeroballistic axes. State
//
//   x = (phi, phidot, theta, thetadot, psi, psidot)   [rad, rad/s]
//
// with the Euler angles psi (about Z), theta (about the new y) and phi (about
// x). The moments are those of the listing's MBAR with the alpha-dot and
// beta-dot terms that TEMP zeroes restored only through the optional
// Cm_alphadot (parameter 15), and the tunnel-fixed terms of Eqs. 39-40.
//
// Everything is templated on the scalar so that ceres::Jet flows through
// unchanged; the simulator (double) and the fitter (Jet) share these
// definitions.

#ifndef FIT3DOF_SYMMETRIC_DYNAMICS_H_
#define FIT3DOF_SYMMETRIC_DYNAMICS_H_

#include <cmath>

#include "fit3dof/angles.h"
#include "fit3dof/bearing_friction.h"
#include "fit3dof/bearing_moment.h"
#include "fit3dof/coefficients.h"
#include "fit3dof/parameters.h"
#include "fit3dof/random_moment.h"

namespace fit3dof {

// Indices into the symmetric state.
enum SymmetricState {
  kSymPhi = 0,
  kSymPhiDot = 1,
  kSymTheta = 2,
  kSymThetaDot = 3,
  kSymPsi = 4,
  kSymPsiDot = 5,
};

// The kinematic rows of Table 1: the rate of each angle is itself a state
// variable, d(angle)/dt = rate exactly, with no coefficient in it
// (SymmetricDerivative writes them from this table). Their rows of df/dx
// are unit vectors and of df/dp zero: the forward sensitivities copy them
// instead of multiplying (motion_sensitivity.cc).
struct KinematicRow {
  int angle;
  int rate;
};
constexpr KinematicRow kSymmetricKinematics[3] = {
    {kSymPhi, kSymPhiDot}, {kSymTheta, kSymThetaDot}, {kSymPsi, kSymPsiDot}};

struct SymmetricConstants {
  double ratio = 0.0;  // R = I_x / I
  Incidence incidence = Incidence::kVelocityRatio;
};

// Sines and cosines of the state's angles, computed once per evaluation
// and shared by the moments and the equations of motion (with Jets every
// trigonometric call costs a full derivative vector).
template <typename T>
struct SymmetricTrig {
  SymmetricTrig() = default;
  explicit SymmetricTrig(const T* x) {
    SinCos(x[kSymTheta], &st, &ct);
    SinCos(x[kSymPsi], &sp, &cp);
  }
  T st, ct, sp, cp;
};

// Moments divided by inertia in aeroballistic axes: mx = M_x/I_x,
// my = M_y/I, mz = M_z/I (the listing's MXOIX, MYOI, MZOI).
// Tx is the state's scalar, Tk the coefficients' (coefficients.h).
template <typename Tx, typename Tk, typename T = Promoted<Tx, Tk>>
void SymmetricMoments(const CoefficientView<Tk>& k,
                      const SymmetricConstants& constants,
                      const Tx* x,
                      const SymmetricTrig<Tx>& trig,
                      T* mx,
                      T* my,
                      T* mz,
                      const TunnelMoment* extra = nullptr) {
  using std::atan;
  using std::cos;
  using std::sqrt;
  using std::tan;
  const Tx& theta = x[kSymTheta];
  const Tx& psi = x[kSymPsi];
  const Tx& phidot = x[kSymPhiDot];
  const Tx& thetadot = x[kSymThetaDot];
  const Tx& psidot = x[kSymPsiDot];
  const Tx& st = trig.st;
  const Tx& ct = trig.ct;
  const Tx& sp = trig.sp;
  const Tx& cp = trig.cp;

  // Eq. 4: body rates in the aeroballistic frame.
  const Tx p = phidot - psidot * st;
  const Tx& q = thetadot;
  const Tx r = psidot * ct;

  // Incidence (TEMP). Velocity ratios, Eq. 9, or angle of attack and
  // sideslip, Eq. 34 written in the Euler angles.
  Tx alpha, beta;
  if (constants.incidence == Incidence::kVelocityRatio) {
    alpha = cp * st;
    beta = -sp;
  } else {
    alpha = theta;
    beta = atan(-tan(psi) / ct);
  }
  const Tx delta2 = alpha * alpha + beta * beta;
  // delta = sqrt(delta2) has an infinite derivative at zero incidence; it is
  // only needed by the |delta| terms and then only away from the origin.
  Tx delta(0.0);
  if ((k.on(3) || k.on(9) || k.on(11)) && delta2 > Tx(0.0)) {
    delta = sqrt(delta2);
  }

  // Eq. 16 with Table 4b's numbering.
  T stiffness(0.0);
  if (k.on(1)) stiffness += k(1);
  if (k.on(3)) stiffness += k(3) * delta;
  if (k.on(5)) stiffness += k(5) * delta2;
  T damping(0.0);
  if (k.on(2)) damping += k(2);
  if (k.on(9)) damping += k(9) * delta;
  if (k.on(6)) damping += k(6) * delta2;
  T magnus(0.0);
  if (k.on(4)) magnus += k(4);
  if (k.on(12)) magnus += k(12) * delta2;

  T damping_y = damping;
  T damping_z = damping;
  if (k.on(7)) {
    damping_y -= k(7) * beta * beta;
    damping_z -= k(7) * alpha * alpha;
  }
  *my = alpha * stiffness + q * damping_y + p * beta * magnus;
  *mz = -beta * stiffness + r * damping_z + p * alpha * magnus;
  if (k.on(8)) {
    *my += k(8) * r * alpha * beta;
    *mz += k(8) * q * alpha * beta;
  }

  // Optional alpha-dot term (parameter 15), for the Section 5.1 experiment:
  // M_y/I += C15 alphadot, M_z/I -= C15 betadot, rates from Eq. 10 (or the
  // derivative of Eq. 34, as TEMP computes it for IANGLE != 0).
  if (k.on(15)) {
    Tx alphadot, betadot;
    if (constants.incidence == Incidence::kVelocityRatio) {
      alphadot = -psidot * sp * st + thetadot * cp * ct;
      betadot = -psidot * cp;
    } else {
      alphadot = thetadot;
      const Tx cb = cos(beta);
      betadot = -(psidot / (cp * cp) + tan(psi) * (st / ct) * thetadot) *
                (cb * cb) / ct;
    }
    *my += k(15) * alphadot;
    *mz -= k(15) * betadot;
  }

  // fit3dof extensions: a body-fixed trim moment (35, 36), turned from
  // body axes into the non-rolling frame by the roll angle, and the gas
  // bearing's moment (37, 38; bearing_moment.h).
  if (k.on(35) || k.on(36)) {
    using std::sin;
    const Tx sf = sin(x[kSymPhi]);
    const Tx cf = cos(x[kSymPhi]);
    T cm0(0.0), cn0(0.0);
    if (k.on(35)) cm0 += k(35);
    if (k.on(36)) cn0 += k(36);
    *my += cm0 * cf - cn0 * sf;
    *mz += cm0 * sf + cn0 * cf;
  }
  if (k.on(37)) {
    const T fade = BearingFade(delta2 / (k(38) * k(38)));
    *my += k(37) * alpha * fade;
    *mz -= k(37) * beta * fade;
  }
  // A yaw-plane stiffness of the flow (44; parameters.h): the non-rolling
  // frame's z axis stays in the tunnel's yaw plane.
  if (k.on(44)) *mz += k(44) * beta;
  // Dry friction of the bearing (48; bearing_friction.h).
  if (k.on(48)) AddBearingFriction(k(48), q, r, my, mz);
  // Dry friction about each axis alone (49; bearing_friction.h).
  if (k.on(49)) {
    *my += AxisFriction(k(49), q);
    *mz += AxisFriction(k(49), r);
  }
  // Dry friction about the pitch axis alone and the yaw axis alone (50,
  // 51; bearing_friction.h).
  if (k.on(50)) *my += AxisFriction(k(50), q);
  if (k.on(51)) *mz += AxisFriction(k(51), r);

  // Roll: Cl_0 + p (Cl_p + Cl_p_delta delta + Cl_p_delta2 delta^2).
  T roll_damping(0.0);
  if (k.on(13)) roll_damping += k(13);
  if (k.on(11)) roll_damping += k(11) * delta;
  if (k.on(14)) roll_damping += k(14) * delta2;
  *mx = p * roll_damping;
  if (k.on(10)) *mx += k(10);

  // Tunnel-fixed stiffness and damping, Eqs. 39-40 (parameters 19-22).
  const bool pitch_tunnel = k.on(20) || k.on(21);
  const bool yaw_tunnel = k.on(19) || k.on(22);
  // Process noise (simulate only; random_moment.h) joins them.
  if (pitch_tunnel || yaw_tunnel || extra != nullptr) {
    T myt(0.0), mzt(0.0);
    if (extra != nullptr) {
      myt += extra->pitch;
      mzt += extra->yaw;
      *mx += extra->roll;
    }
    if (k.on(21)) myt += k(21) * theta;
    if (k.on(20)) myt += k(20) * thetadot;
    if (k.on(22)) mzt += k(22) * psi;
    if (k.on(19)) mzt += k(19) * psidot;
    *mx += (myt * sp * ct - mzt * st) / constants.ratio;
    *my += myt * cp;
    *mz += myt * sp * st + mzt * ct;
  }
}

// Eq. 6 (the listing's FCT): dx/dt for the symmetric body. These follow from
// dh/dt + omega_frame x h = M with h = (I_x p, I q, I r) in the non-rolling
// frame, whose angular velocity is (-psidot sin(theta), thetadot,
// psidot cos(theta)). trig: the sines and cosines of x, given so that
// several coefficient scalars at one state share them.
template <typename Tx, typename Tk, typename T = Promoted<Tx, Tk>>
void SymmetricDerivative(const CoefficientView<Tk>& k,
                         const SymmetricConstants& constants,
                         const Tx* x,
                         const SymmetricTrig<Tx>& trig,
                         T* dx,
                         const TunnelMoment* extra = nullptr) {
  T mx, my, mz;
  SymmetricMoments(k, constants, x, trig, &mx, &my, &mz, extra);
  const double ratio = constants.ratio;
  const Tx& phidot = x[kSymPhiDot];
  const Tx& thetadot = x[kSymThetaDot];
  const Tx& psidot = x[kSymPsiDot];
  const Tx& st = trig.st;
  const Tx& ct = trig.ct;
  const Tx sec = 1.0 / ct;
  const Tx tt = st * sec;
  for (const KinematicRow& row : kSymmetricKinematics) {
    dx[row.angle] = T(x[row.rate]);
  }
  dx[kSymPhiDot] = mx + psidot * thetadot * ct + mz * tt +
                   (2.0 - ratio) * psidot * thetadot * tt * st +
                   ratio * phidot * thetadot * tt;
  dx[kSymThetaDot] = my - (1.0 - ratio) * psidot * psidot * st * ct -
                     ratio * phidot * psidot * ct;
  dx[kSymPsiDot] = mz * sec + (2.0 - ratio) * psidot * thetadot * tt +
                   ratio * phidot * thetadot * sec;
}

// The same, computing the sines and cosines of x.
template <typename Tx, typename Tk, typename T = Promoted<Tx, Tk>>
void SymmetricDerivative(const CoefficientView<Tk>& k,
                         const SymmetricConstants& constants,
                         const Tx* x,
                         T* dx,
                         const TunnelMoment* extra = nullptr) {
  SymmetricDerivative(k, constants, x, SymmetricTrig<Tx>(x), dx, extra);
}

}  // namespace fit3dof

#endif  // FIT3DOF_SYMMETRIC_DYNAMICS_H_
