// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Dry (Coulomb) friction of the bearing against the pitch-yaw motion,
// shared by both programs (outside diagnose's catalog, which fits both
// forms as probes). A ball pivot's dry
// friction opposes the sliding velocity with a force of constant size, so
// the moment about the pivot is
//
//   (M_y, M_z) / (q S d) = -Cm_friction (q, r) / |w| s(|w| / w_0),
//   |w| = sqrt(q^2 + r^2),
//
// (Cm_friction: symmetric parameter 48, asymmetric 88), the transverse
// angular velocity's direction times a constant size. It is
// isotropic, the same in the non-rolling frame and in body axes (a turn
// about x keeps |w|). The spin's own friction is a constant roll torque
// while the spin keeps its sign: the catalog's Cl_0, so none is added here.
// s = tanh fades the moment linearly below w_0 = 1 deg/s: the sign
// function made smooth, so that the integrator and the Jets see a
// continuous moment where the rate reverses (a planar motion's ends). With
// s(x)/x = BearingFade(x^2), no square root is taken at zero rate.
//
// Unlike a viscous damping (Cm_q, Eq. 39's t2 and t4) its equivalent
// damping grows as the amplitude falls: a small motion decays linearly in
// time, not exponentially.
//
// A friction acting on each of the non-rolling frame's pitch and yaw axes
// alone (Cm_axis_friction: symmetric 49, asymmetric 89) is what pivots
// turning about fixed axes give (a gimbal's, or lead wires crossing the
// bearing, which rub as the model pitches and as it yaws):
//
//   M_y / (q S d) = -Cm_axis_friction s(q / w_0),
//   M_z / (q S d) = -Cm_axis_friction s(r / w_0),
//
// each a constant size while its own rate keeps its sign. Unlike the
// ball's, it takes the full size on an axis whose rate is small against
// the other's: a motion pitching in one plane has its small yaw rate
// damped hard, which a viscous tunnel damping in yaw (Eq. 39's t4)
// imitates on one run. One size for both axes: with a size of its own for
// each, the probe (diagnose.h) explained to the noise a 3-s coning run
// that a Magnus moment, a nonlinear damping and a calibration error had
// made (its constant-amplitude rates leave a friction per axis little to
// tell it from a damping). A friction of one axis alone is its own
// parameter (Cm_pitch_friction, Cn_yaw_friction: symmetric 50-51,
// asymmetric 90-91), AxisFriction on that axis only: on a circular cone a
// pitch pivot's friction had been taken for Eq. 39's tunnel damping, and
// one parameter cannot follow what two catalog effects damp on both axes.
// Templated on the scalar for ceres::Jet.

#ifndef FIT3DOF_BEARING_FRICTION_H_
#define FIT3DOF_BEARING_FRICTION_H_

#include "fit3dof/bearing_moment.h"

namespace fit3dof {

// The rate (rad/s) below which the friction fades linearly: 1 deg/s.
inline constexpr double kFrictionFadeRate = 0.017453292519943295;

// The friction's moment about the transverse axes, per unit of the
// coefficient's scaled value `f` (q S d / I times Cm_friction): adds
// -f (q, r) / |w| s(|w| / w_0) to (*my, *mz).
template <typename Tw, typename Tk, typename T>
void AddBearingFriction(const Tk& f, const Tw& q, const Tw& r, T* my, T* mz) {
  const double w0 = kFrictionFadeRate;
  const Tw x2 = (q * q + r * r) / (w0 * w0);
  const T scale = f * BearingFade(x2) / w0;
  *my -= scale * q;
  *mz -= scale * r;
}

// Dry friction about one axis of rate `w`, per unit of the coefficient's
// scaled value `f`: -f s(w / w_0), s(x) = tanh x = x BearingFade(x^2).
template <typename Tw, typename Tk>
auto AxisFriction(const Tk& f, const Tw& w) {
  const double w0 = kFrictionFadeRate;
  return -f * (w * BearingFade(w * w / (w0 * w0)) / w0);
}

}  // namespace fit3dof

#endif  // FIT3DOF_BEARING_FRICTION_H_
