// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// MotionModel turns a full parameter vector (report units) into the three
// measured angles at given sample times: it scales the coefficients (REG),
// sets the initial state from the initial-condition parameters, integrates
// the equations of motion of the chosen program with RK4, and applies the
// measurement model (flow-angularity offsets theta_T and psi_T are added to
// the computed theta and psi, as INTGRL does; the reading errors of Section
// 5.2 follow).
//
// This is the one path from parameters to angles: `fit3dof simulate`
// evaluates it with doubles, the fitter's residual blocks with ceres::Jet.

#ifndef FIT3DOF_MOTION_MODEL_H_
#define FIT3DOF_MOTION_MODEL_H_

#include <glog/logging.h>

#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "fit3dof/angles.h"
#include "fit3dof/asymmetric_dynamics.h"
#include "fit3dof/body.h"
#include "fit3dof/coefficients.h"
#include "fit3dof/parameters.h"
#include "fit3dof/random_moment.h"
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

// The angle (rad) at which theta_cal3 and psi_cal3 give the reading error.
inline constexpr double kCalibrationAngle = 5.0 * kDegree;

// The slope, per unit of u = angle / kCalibrationAngle, of the straight
// line a linear least-squares calibration over +-range (rad) takes of the
// signed square u |u|: over a uniform u in [-rho, rho] it is 3 rho / 4
// (rho = range / kCalibrationAngle; a range of 0 takes none).
template <typename T>
T SignedSquareLineSlope(const T& range) {
  return 0.75 * range / kCalibrationAngle;
}

class MotionModel {
 public:
  // `active` marks the parameters whose terms are evaluated; see
  // coefficients.h. Use ActiveParameters() to build it.
  MotionModel(const ModelSpec& spec, const ActiveSet& active);

  const ModelSpec& spec() const { return spec_; }

  // The same model integrated with another largest step (s): the coarser
  // motion that a Levenberg-Marquardt run's Jacobians may come from
  // (SegmentCostFunction::set_jacobian_step).
  std::shared_ptr<const MotionModel> WithMaxStep(double max_step) const;
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

  // Evaluate's angles and their derivatives with respect to the m
  // parameters values[wrt[0..m)]: `jacobian` gets 3 n rows of m entries
  // (row 3 i + c is angle c of sample i). The derivatives come from the
  // forward sensitivity equations, dS/dt = F_x S + F_p, stepped by the
  // same RK4 formula as the motion, with F_x and F_p from Jets through the
  // same equations (motion_sensitivity.cc): they equal Evaluate's with
  // ceres::Jet up to rounding, the angles equal Evaluate's exactly, and the
  // cost grows with m far more slowly than Jet lanes do.
  bool EvaluateWithSensitivities(const double* values,
                                 const int* wrt,
                                 int m,
                                 const double* times,
                                 int n,
                                 double* angles,
                                 double* jacobian,
                                 IntegrationFailure* failure) const;

  // The motion with a fixed-gain correction at every sample: the predictor
  // of the filter-error fit (issue 14). At sample i the innovation
  // e_i = measured - h(x-) (deg, three per sample, the roll one taken to
  // the branch nearest +-180 deg) goes to innovations[3 i ..], and the
  // state is corrected, x+ = x- + K_i e_i, with K_i the 6 x 3 row-major
  // gains[18 i ..] (internal units per degree). The gains are data: with
  // Jets the innovations' derivatives are those of a filter whose gains
  // are held (as the filter-error method's Gauss-Newton step holds them).
  // measured: 3 n angles (deg). Returns false like Evaluate.
  template <typename T>
  bool EvaluateFiltered(const T* values,
                        const double* times,
                        int n,
                        const double* measured,
                        const double* gains,
                        T* innovations,
                        IntegrationFailure* failure) const;

  // The extended Kalman filter of the filter-error fit (motion_filter.cc):
  // the motion predicted from sample to sample by the same RK4 steps, its
  // covariance P by the state-transition matrix (from 6-lane Jets through
  // those steps) plus the process noise, and corrected at each sample by
  // the innovation. The process noise is a white random angular
  // acceleration per axis, entering the equations as simulate's random
  // moments do (pitch and yaw about tunnel-fixed axes, roll about the
  // body's; random_moment.h), `process` its intensity in deg/s^1.5 per
  // axis (roll, pitch, yaw): the root of its spectral density, so that
  // over a time dt the rate wanders by intensity sqrt(dt) deg/s. The
  // measurement noise is white with standard deviations `sigma` (deg). The
  // initial state is known (a parameter): P(0) = 0. Returns false like
  // Evaluate.
  struct FilterRun {
    std::vector<double> gains;        // 18 n: K_i, 6 x 3 row-major
    std::vector<double> covariance;   // 9 n: S_i = H P H^T + R (deg^2)
    std::vector<double> innovations;  // 3 n: e_i (deg)
    // sum over samples of e^T S^-1 e + log det S: twice the negative log
    // likelihood, less a constant; and of e^T S^-1 e alone.
    double deviance = 0.0;
    double normalized_sum = 0.0;
  };
  bool Filter(const double* values,
              const double* times,
              int n,
              const double* measured,
              const std::array<double, 3>& process,
              const std::array<double, 3>& sigma,
              FilterRun* run,
              IntegrationFailure* failure) const;

  // Process noise for simulation (random_moment.h): Evaluate and
  // EvaluateStates add the random moments, held over each RK4 step at
  // their value at its midpoint. Not for fitting: sensitivities CHECK that
  // none is set.
  void set_random_moment(std::shared_ptr<const RandomMoment> moment) {
    random_moment_ = std::move(moment);
  }

 private:
  // dx/dt of the chosen program; Tx the state's scalar, Tk the
  // coefficients' (coefficients.h).
  template <typename Tx, typename Tk, typename T = Promoted<Tx, Tk>>
  void Derivative(const CoefficientView<Tk>& k,
                  const Tx* x,
                  T* dx,
                  const TunnelMoment* extra = nullptr) const;

  // Derivative at a state whose sines and cosines `trig` are computed once
  // and shared by several passes (motion_sensitivity.cc: the state pass and
  // the coefficient passes); the trig's type picks the program, which must
  // be the model's.
  template <typename Tx, typename Tk, typename T>
  void Derivative(const CoefficientView<Tk>& k,
                  const Tx* x,
                  const SymmetricTrig<Tx>& trig,
                  T* dx) const {
    SymmetricDerivative(k, symmetric_, x, trig, dx);
  }
  template <typename Tx, typename Tk, typename T>
  void Derivative(const CoefficientView<Tk>& k,
                  const Tx* x,
                  const AsymmetricTrig<Tx>& trig,
                  T* dx) const {
    AsymmetricDerivative(k, asymmetric_, x, trig, dx);
  }

  // dtheta/dt and dpsi/dt of state x (rad/s): state entries in the
  // symmetric program, the kinematics of Appendix A in the asymmetric one.
  template <typename Tx>
  void AngleRates(const Tx* x, Tx* thetadot, Tx* psidot) const {
    if (spec_.model == ModelKind::kSymmetric) {
      *thetadot = x[kSymThetaDot];
      *psidot = x[kSymPsiDot];
      return;
    }
    using std::cos;
    using std::sin;
    Tx phidot;
    BodyToEulerRates<Tx>(sin(x[kAsymPhi]),
                         cos(x[kAsymPhi]),
                         sin(x[kAsymTheta]),
                         cos(x[kAsymTheta]),
                         x[kAsymP],
                         x[kAsymQ],
                         x[kAsymR],
                         &phidot,
                         thetadot,
                         psidot);
  }

  // The measurement model: the three measured angles (deg) of state x,
  // `elapsed` (s) after the segment's first sample, with `internal` the
  // parameters in internal units.
  template <typename Tx, typename Tk, typename T = Promoted<Tx, Tk>>
  void Measure(const Tx* x,
               const Tk* internal,
               double elapsed,
               T* angles) const;

  // The parameters in internal units (REG): values times scale, zeros
  // beyond the model's parameters.
  template <typename T>
  void ToInternal(const T* values,
                  std::array<T, kMaxParameters>* internal) const;

  // The moment coefficients of `internal` (internal units) at `elapsed`
  // s after the segment's first sample, into *drifted: times
  // 1 + q_drift elapsed, as each is a coefficient of q S d and the dynamic
  // pressure drifts (parameters.h). The other entries are left as they are.
  template <typename T>
  void Drift(const T* internal, double elapsed, T* drifted) const {
    const T factor = 1.0 + internal[layout_.q_drift] * elapsed;
    for (int i : drifting_) drifted[i] = internal[i] * factor;
  }

  template <typename T, typename Observe>
  bool Integrate(const T* values,
                 const double* times,
                 int n,
                 std::array<T, kMaxParameters>* internal,
                 const Observe& observe,
                 IntegrationFailure* failure) const;

  StateGuard Guard() const;

  ModelSpec spec_;
  ActiveSet active_;
  std::vector<double> scale_;
  SymmetricConstants symmetric_;
  AsymmetricConstants asymmetric_;
  ParameterLayout layout_;
  // Positions of phi, theta and psi in the state.
  std::array<int, 3> state_index_;
  // For each state variable j whose derivative is exactly state variable
  // kinematic_rate_[j] (the symmetric program's kinematic rows), that
  // index; -1 for the rest.
  std::array<int, 6> kinematic_rate_{{-1, -1, -1, -1, -1, -1}};
  // Whether any roll-interaction or calibration parameter is active
  // (Measure).
  bool roll_interaction_ = false;
  bool roll_harmonic2_ = false;  // the second roll harmonic's
  bool calibration_ = false;
  bool calibration_square_ = false;
  bool drift_ = false;
  bool lag_ = false;
  bool gain_ = false;
  // The active moment coefficients that follow a drifting dynamic pressure
  // (Drift); empty unless q_drift is active.
  std::vector<int> drifting_;
  std::shared_ptr<const RandomMoment> random_moment_;
  // Moment coefficient to internal acceleration per axis (roll, pitch,
  // yaw): the scales of Cl_0, t1 and t3.
  std::array<double, 3> moment_scale_{{0.0, 0.0, 0.0}};
};

// The terms that matter: every free parameter and every non-zero one.
ActiveSet ActiveParameters(const std::vector<double>& values,
                           const std::vector<bool>& free);

// ---------------------------------------------------------------------------
// Implementation.

template <typename Tx, typename Tk, typename T>
void MotionModel::Derivative(const CoefficientView<Tk>& k,
                             const Tx* x,
                             T* dx,
                             const TunnelMoment* extra) const {
  if (spec_.model == ModelKind::kSymmetric) {
    SymmetricDerivative(k, symmetric_, x, SymmetricTrig<Tx>(x), dx, extra);
  } else {
    AsymmetricDerivative(k, asymmetric_, x, AsymmetricTrig<Tx>(x), dx, extra);
  }
}

template <typename Tx, typename Tk, typename T>
void MotionModel::Measure(const Tx* x,
                          const Tk* internal,
                          double elapsed,
                          T* angles) const {
  using std::cos;
  using std::sin;
  const Tx& phi = x[state_index_[0]];
  // Measurement model (INTGRL): theta_m = theta + theta_T,
  // psi_m = psi + psi_T; plus the roll-interaction reading error of Section
  // 5.2 (first harmonics in phi), when any of its parameters is active.
  T theta = x[state_index_[1]] + internal[layout_.theta_offset];
  T psi = x[state_index_[2]] + internal[layout_.psi_offset];
  if (roll_interaction_) {
    const int ri = layout_.roll_interaction;
    const Tx c = cos(phi);
    const Tx s = sin(phi);
    theta += internal[ri] * c + internal[ri + 1] * s;
    psi += internal[ri + 2] * c + internal[ri + 3] * s;
  }
  // The same at the second harmonic (outside diagnose's catalog).
  if (roll_harmonic2_) {
    const int r2 = layout_.roll_harmonic2;
    const Tx c = cos(2.0 * phi);
    const Tx s = sin(2.0 * phi);
    theta += internal[r2] * c + internal[r2 + 1] * s;
    psi += internal[r2 + 2] * c + internal[r2 + 3] * s;
  }
  // The calibration nonlinearity of Section 5.2: a reading error that grows
  // as the cube of the angle the bearing sits at, its size given at 5 deg.
  // Or as the angle's signed square (another form of it).
  if (calibration_ || calibration_square_) {
    using std::abs;
    const Tx u = x[state_index_[1]] / kCalibrationAngle;
    const Tx v = x[state_index_[2]] / kCalibrationAngle;
    if (calibration_) {
      const int cal = layout_.calibration;
      theta += internal[cal] * (u * u * u);
      psi += internal[cal + 1] * (v * v * v);
    }
    if (calibration_square_) {
      // Less the straight line a linear calibration over +-cal_range took
      // of it.
      const int cal = layout_.calibration_square;
      const auto slope = SignedSquareLineSlope(internal[layout_.cal_range]);
      theta += internal[cal] * (u * abs(u) - slope * u);
      psi += internal[cal + 1] * (v * abs(v) - slope * v);
    }
  }
  // A reading that drifts in time (a zero creeping with temperature).
  if (drift_) {
    theta += internal[layout_.drift] * elapsed;
    psi += internal[layout_.drift + 1] * elapsed;
  }
  // A pitch reading whose gain is off the yaw reading's.
  if (gain_) theta += internal[layout_.gain] * x[state_index_[1]];
  // A reading through a first-order lag of time constant tau reads
  // x - tau dx/dt + O((omega tau)^2).
  if (lag_) {
    Tx thetadot, psidot;
    AngleRates(x, &thetadot, &psidot);
    theta -= internal[layout_.lag] * thetadot;
    psi -= internal[layout_.lag + 1] * psidot;
  }
  angles[0] = T(phi * kDegreesPerRadian);
  angles[1] = theta * kDegreesPerRadian;
  angles[2] = psi * kDegreesPerRadian;
}

template <typename T>
void MotionModel::ToInternal(const T* values,
                             std::array<T, kMaxParameters>* internal) const {
  const int np = num_parameters();
  for (int i = 0; i < np; ++i) (*internal)[i] = values[i] * scale_[i];
  for (int i = np; i < kMaxParameters; ++i) (*internal)[i] = T(0.0);
}

template <typename T, typename Observe>
bool MotionModel::Integrate(const T* values,
                            const double* times,
                            int n,
                            std::array<T, kMaxParameters>* internal,
                            const Observe& observe,
                            IntegrationFailure* failure) const {
  ToInternal(values, internal);
  const CoefficientView<T> k(internal->data(), active_);
  // Both programs order their six initial-condition parameters as their
  // state vector: (phi, phidot, theta, thetadot, psi, psidot) and
  // (phi, theta, psi, p, q, r).
  T x[6];
  for (int j = 0; j < 6; ++j) x[j] = (*internal)[layout_.first_initial + j];
  if (random_moment_ == nullptr && drifting_.empty()) {
    auto rhs = [&](const T* s, T* ds) { Derivative(k, s, ds); };
    return IntegrateSamples<T, 6>(
        rhs, times, n, spec_.max_step, Guard(), x, observe, failure);
  }
  // With process noise or a drifting dynamic pressure: the random moment
  // and the moment coefficients held over each step at their values at its
  // midpoint (the midpoint rule: second order in the step).
  std::array<T, kMaxParameters> drifted = *internal;
  const CoefficientView<T> kd(drifted.data(), active_);
  TunnelMoment extra;
  const TunnelMoment* pushed = random_moment_ == nullptr ? nullptr : &extra;
  auto rhs = [&](const T* s, T* ds) { Derivative(kd, s, ds, pushed); };
  auto step = [&](double t, double h) {
    const double middle = t + 0.5 * h;
    if (!drifting_.empty()) {
      Drift(internal->data(), middle - times[0], drifted.data());
    }
    if (pushed != nullptr) {
      const std::array<double, 3> c = random_moment_->At(middle);
      extra.roll = c[0] * moment_scale_[0];
      extra.pitch = c[1] * moment_scale_[1];
      extra.yaw = c[2] * moment_scale_[2];
    }
    RungeKutta4Step<T, 6>(rhs, h, x);
  };
  return IntegrateSamplesWith<T, 6>(
      step, times, n, spec_.max_step, Guard(), x, observe, failure);
}

template <typename T>
bool MotionModel::Evaluate(const T* values,
                           const double* times,
                           int n,
                           T* angles,
                           IntegrationFailure* failure) const {
  std::array<T, kMaxParameters> internal;
  auto observe = [&](int i, const T* x) {
    Measure(x, internal.data(), times[i] - times[0], angles + 3 * i);
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

template <typename T>
bool MotionModel::EvaluateFiltered(const T* values,
                                   const double* times,
                                   int n,
                                   const double* measured,
                                   const double* gains,
                                   T* innovations,
                                   IntegrationFailure* failure) const {
  CHECK(random_moment_ == nullptr)
      << "process noise is for simulation; fits model it otherwise";
  std::array<T, kMaxParameters> internal;
  auto observe = [&](int i, T* x) {
    T predicted[3];
    Measure(x, internal.data(), times[i] - times[0], predicted);
    T* e = innovations + 3 * i;
    for (int c = 0; c < 3; ++c) e[c] = measured[3 * i + c] - predicted[c];
    // Roll is compared modulo 360 deg, as the output-error residual is.
    e[0] -= WholeTurns(ScalarPart(e[0]));
    const double* k = gains + 18 * i;
    for (int j = 0; j < 6; ++j) {
      x[j] += k[3 * j] * e[0] + k[3 * j + 1] * e[1] + k[3 * j + 2] * e[2];
    }
  };
  return Integrate(values, times, n, &internal, observe, failure);
}

extern template bool MotionModel::Evaluate<double>(
    const double*, const double*, int, double*, IntegrationFailure*) const;
extern template bool MotionModel::EvaluateStates<double>(
    const double*, const double*, int, double*, IntegrationFailure*) const;

}  // namespace fit3dof

#endif  // FIT3DOF_MOTION_MODEL_H_
