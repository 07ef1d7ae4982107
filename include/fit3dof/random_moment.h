// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Process noise for `fit3dof simulate`: a random moment per axis, the kind
// Section 6 of the report blames for the Tunnel A coefficients' errors
// (flow unsteadiness, turbulence, bearing pressure). Each axis is a
// first-order Gauss-Markov process (exponentially correlated, the
// Ornstein-Uhlenbeck process) with a given RMS moment coefficient and
// correlation time, drawn from a seeded generator on a fine grid; the
// pitch and yaw moments act in tunnel-fixed axes (like Eqs. 39-41's
// terms), the roll moment about the body axis.
//
//   simulate: {dt: 0.06, duration: 8,
//              process_noise: {pitch: 3.0e-4, yaw: 3.0e-4,
//                              correlation_time: 0.05, seed: 7}}
//
// A fit has its own model of process noise (the filter-error method); this
// is the truth simulated data are made from.

#ifndef FIT3DOF_RANDOM_MOMENT_H_
#define FIT3DOF_RANDOM_MOMENT_H_

#include <array>
#include <cstdint>
#include <vector>

namespace fit3dof {

struct ProcessNoiseOptions {
  // RMS moment coefficient per axis: roll (Cl), pitch (Cm), yaw (Cn).
  std::array<double, 3> rms{{0.0, 0.0, 0.0}};
  double correlation_time = 0.05;  // s
  std::uint64_t seed = 1;

  bool enabled() const { return rms[0] > 0.0 || rms[1] > 0.0 || rms[2] > 0.0; }
};
bool operator==(const ProcessNoiseOptions& a, const ProcessNoiseOptions& b);

// Extra moments the equations of motion add, as angular accelerations in
// the model's internal units (rad/s^2, moment over the inertia of its
// axis): pitch and yaw tunnel-fixed, roll about the body's axis.
struct TunnelMoment {
  double roll = 0.0;
  double pitch = 0.0;
  double yaw = 0.0;
};

// One draw of the random moments over [t0, t1].
class RandomMoment {
 public:
  // The processes start in their stationary distribution at t0 and are
  // stepped exactly (x' = a x + sqrt(1 - a^2) rms w, a = exp(-dt / tau))
  // on a grid of at most tau / 20 and `max_step`.
  RandomMoment(const ProcessNoiseOptions& options,
               double t0,
               double t1,
               double max_step);

  // The moment coefficients (Cl, Cm, Cn) at t, linear between grid points.
  std::array<double, 3> At(double t) const;

 private:
  double t0_ = 0.0;
  double grid_ = 1.0;
  std::vector<std::array<double, 3>> values_;
};

}  // namespace fit3dof

#endif  // FIT3DOF_RANDOM_MOMENT_H_
