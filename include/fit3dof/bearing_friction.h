// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Dry (Coulomb) friction of the bearing against the pitch-yaw motion,
// shared by both programs (symmetric parameter 48, asymmetric 88; outside
// diagnose's catalog, which fits it as a probe). A ball pivot's dry
// friction opposes the sliding velocity with a force of constant size, so
// the moment about the pivot is
//
//   (M_y, M_z) / (q S d) = -Cm_friction (q, r) / |w| s(|w| / w_0),
//   |w| = sqrt(q^2 + r^2),
//
// the transverse angular velocity's direction times a constant size. It is
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
// time, not exponentially. Templated on the scalar for ceres::Jet.

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

}  // namespace fit3dof

#endif  // FIT3DOF_BEARING_FRICTION_H_
