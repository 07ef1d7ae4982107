// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// MotionModel turns a full parameter vector (report units) into the three
// measured angles at given sample times: it scales the coefficients (REG),
// sets the initial state from the initial-condition parameters, integrates
// the equations of motion of the chosen program with RK4, and applies the
// measurement model (flow-angularity offsets theta_T and psi_T are added to
// the computed theta and psi, as INTGRL does).
//
// This is the one path from parameters to angles: `fit3dof simulate`
// evaluates it with doubles, the fitter's residual blocks with ceres::Jet.

#ifndef FIT3DOF_MOTION_MODEL_H_
#define FIT3DOF_MOTION_MODEL_H_

#include <array>
#include <vector>

#include "fit3dof/angles.h"
#include "fit3dof/asymmetric_dynamics.h"
#include "fit3dof/body.h"
#include "fit3dof/coefficients.h"
#include "fit3dof/parameters.h"
#include "fit3dof/runge_kutta.h"
#include "fit3dof/scaling.h"
#include "fit3dof/symmetric_dynamics.h"

namespace fit3dof {

struct ModelSpec {
  ModelKind model = ModelKind::kSymmetric;
  Incidence incidence = Incidence::kVelocityRatio;
  Body body;
  Flow flow;
  double max_step = 0.001;  // s, the report's DTMIN
};

// The most RK4 steps one evaluation of the motion may take: a fit evaluates
// it hundreds of times, with Jets; beyond this it would run for days, and a
// time column in milliseconds or a step of 1e-9 s is the likely cause.
inline constexpr double kMaxIntegrationSteps = 1e8;

// Throws InputError naming `source` when `steps` (TotalSubsteps summed over
// the records of one evaluation, spanning `span` seconds) exceeds
// kMaxIntegrationSteps, with the count, solver.step and the span.
void CheckIntegrationSteps(double steps,
                           double span,
                           double max_step,
                           const std::string& source);

class MotionModel {
 public:
  // `active` marks the parameters whose terms are evaluated; see
  // coefficients.h. Use ActiveParameters() to build it.
  MotionModel(const ModelSpec& spec, const ActiveSet& active);

  const ModelSpec& spec() const { return spec_; }
  int num_parameters() const { return NumParameters(spec_.model); }
  const std::vector<double>& scale() const { return scale_; }

  // values: num_parameters() entries in report units. Writes 3 n measured
  // angles in degrees, (phi, theta, psi) per sample, to `angles`. The
  // initial conditions hold at times[0]. Returns false (and fills
  // `failure`, if given) when the motion blows up or theta nears 90 deg.
  template <typename T>
  bool Evaluate(const T* values,
                const double* times,
                int n,
                T* angles,
                IntegrationFailure* failure) const;

  // Like Evaluate, but writes the integrated state (6 per sample, internal
  // units: rad, rad/s) instead of the measured angles.
  template <typename T>
  bool EvaluateStates(const T* values,
                      const double* times,
                      int n,
                      T* states,
                      IntegrationFailure* failure) const;

 private:
  template <typename T, typename Observe>
  bool Integrate(const T* values,
                 const double* times,
                 int n,
                 std::array<T, kMaxParameters>* internal,
                 const Observe& observe,
                 IntegrationFailure* failure) const;

  ModelSpec spec_;
  ActiveSet active_;
  std::vector<double> scale_;
};

// The terms that matter: every free parameter and every non-zero one.
ActiveSet ActiveParameters(const std::vector<double>& values,
                           const std::vector<bool>& free);

// ---------------------------------------------------------------------------
// Implementation.

template <typename T, typename Observe>
bool MotionModel::Integrate(const T* values,
                            const double* times,
                            int n,
                            std::array<T, kMaxParameters>* internal,
                            const Observe& observe,
                            IntegrationFailure* failure) const {
  const int np = num_parameters();
  for (int i = 0; i < np; ++i) (*internal)[i] = values[i] * scale_[i];
  for (int i = np; i < kMaxParameters; ++i) (*internal)[i] = T(0.0);
  const CoefficientView<T> k(internal->data(), active_);
  const ParameterLayout& layout = Layout(spec_.model);
  // Both programs order their six initial-condition parameters as their
  // state vector: (phi, phidot, theta, thetadot, psi, psidot) and
  // (phi, theta, psi, p, q, r).
  T x[6];
  for (int j = 0; j < 6; ++j) x[j] = (*internal)[layout.first_initial + j];
  StateGuard guard;
  if (spec_.model == ModelKind::kSymmetric) {
    SymmetricConstants constants;
    constants.ratio = spec_.body.Ix / spec_.body.Iy;
    constants.incidence = spec_.incidence;
    guard.theta_index = kSymTheta;
    auto rhs = [&](const T* s, T* ds) {
      SymmetricDerivative(k, constants, s, ds);
    };
    return IntegrateSamples<T, 6>(
        rhs, times, n, spec_.max_step, guard, x, observe, failure);
  }
  AsymmetricConstants constants;
  constants.Ix = spec_.body.Ix;
  constants.Iy = spec_.body.Iy;
  constants.Iz = spec_.body.Iz;
  constants.incidence = spec_.incidence;
  guard.theta_index = kAsymTheta;
  auto rhs = [&](const T* s, T* ds) {
    AsymmetricDerivative(k, constants, s, ds);
  };
  return IntegrateSamples<T, 6>(
      rhs, times, n, spec_.max_step, guard, x, observe, failure);
}

template <typename T>
bool MotionModel::Evaluate(const T* values,
                           const double* times,
                           int n,
                           T* angles,
                           IntegrationFailure* failure) const {
  std::array<T, kMaxParameters> internal;
  const ParameterLayout& layout = Layout(spec_.model);
  const bool symmetric = spec_.model == ModelKind::kSymmetric;
  const int phi_index = symmetric ? int{kSymPhi} : int{kAsymPhi};
  const int theta_index = symmetric ? int{kSymTheta} : int{kAsymTheta};
  const int psi_index = symmetric ? int{kSymPsi} : int{kAsymPsi};
  // Measurement model (INTGRL): theta_m = theta + theta_T,
  // psi_m = psi + psi_T; plus the roll-interaction reading error of Section
  // 5.2 (first harmonics in phi), when any of its parameters is active.
  const int ri = layout.roll_interaction;
  const bool roll_interaction =
      active_[ri] || active_[ri + 1] || active_[ri + 2] || active_[ri + 3];
  auto observe = [&](int i, const T* x) {
    using std::cos;
    using std::sin;
    T theta = x[theta_index] + internal[layout.theta_offset];
    T psi = x[psi_index] + internal[layout.psi_offset];
    if (roll_interaction) {
      const T c = cos(x[phi_index]);
      const T s = sin(x[phi_index]);
      theta += internal[ri] * c + internal[ri + 1] * s;
      psi += internal[ri + 2] * c + internal[ri + 3] * s;
    }
    angles[3 * i + 0] = x[phi_index] * kDegreesPerRadian;
    angles[3 * i + 1] = theta * kDegreesPerRadian;
    angles[3 * i + 2] = psi * kDegreesPerRadian;
  };
  return Integrate(values, times, n, &internal, observe, failure);
}

template <typename T>
bool MotionModel::EvaluateStates(const T* values,
                                 const double* times,
                                 int n,
                                 T* states,
                                 IntegrationFailure* failure) const {
  std::array<T, kMaxParameters> internal;
  auto observe = [&](int i, const T* x) {
    for (int j = 0; j < 6; ++j) states[6 * i + j] = x[j];
  };
  return Integrate(values, times, n, &internal, observe, failure);
}

extern template bool MotionModel::Evaluate<double>(
    const double*, const double*, int, double*, IntegrationFailure*) const;
extern template bool MotionModel::EvaluateStates<double>(
    const double*, const double*, int, double*, IntegrationFailure*) const;

}  // namespace fit3dof

#endif  // FIT3DOF_MOTION_MODEL_H_
