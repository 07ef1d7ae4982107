// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// MotionModel::Filter (motion_model.h): the extended Kalman filter whose
// gains and innovation covariances the filter-error fit (filter_error.h)
// holds while it steps the coefficients.
//
// Prediction: the state goes from sample to sample by the motion's own RK4
// steps, carried as 6-lane Jets seeded with the identity at the previous
// sample, so that at the next sample the lanes hold the state-transition
// matrix Phi of exactly those steps; P <- Phi P Phi^T + Q_d with the
// process noise Q_d = (Phi Q(x0) Phi^T + Q(x1)) dt / 2 (the trapezoid rule
// for the integral of Phi(s) Q Phi(s)^T), Q(x) = G W G^T the random
// moments' density on the state: W theirs per axis, G how they enter the
// equations at x (as simulate's do: pitch and yaw about tunnel-fixed axes,
// roll about the body's). Update: H from Jets through the measurement model, S
// = H P H^T
// + R, K = P H^T S^-1, x <- x + K e (the same expression, term for term,
// as EvaluateFiltered, so that a fit holding these gains sees the same
// innovations), and P in Joseph form, (I - K H) P (I - K H)^T + K R K^T,
// which stays symmetric and positive.

#include <glog/logging.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>

#include "ceres/jet.h"
#include "fit3dof/motion_model.h"

namespace fit3dof {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Matrix36 = Eigen::Matrix<double, 3, 6>;
using Matrix63 = Eigen::Matrix<double, 6, 3>;
using StateJet = ceres::Jet<double, 6>;

// The state-transition matrix held in the lanes of x.
Matrix6 Transition(const StateJet* x) {
  Matrix6 phi;
  for (int r = 0; r < 6; ++r) phi.row(r) = x[r].v.transpose();
  return phi;
}

// The update at sample i with measurement Jacobian hx, innovation e and
// measurement noise r: S = H P H^T + R and the gain K = P H^T S^-1 go to
// the run (with e and the deviance's terms), P becomes (I - K H) P
// (I - K H)^T + K R K^T. False if S is not positive definite.
bool Update(int i,
            const Matrix36& hx,
            const double* e,
            const Eigen::Matrix3d& r,
            Matrix6* p,
            MotionModel::FilterRun* run) {
  const Eigen::Matrix3d s = hx * *p * hx.transpose() + r;
  const Eigen::LLT<Eigen::Matrix3d> llt(s);
  if (llt.info() != Eigen::Success) return false;
  const Matrix63 gain = llt.solve(hx * *p).transpose();
  const Eigen::Map<const Eigen::Vector3d> ev(e);
  const double normalized = ev.dot(llt.solve(ev));
  run->normalized_sum += normalized;
  run->deviance +=
      normalized +
      2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
  double* kout = &run->gains[18 * i];
  for (int j = 0; j < 6; ++j) {
    for (int c = 0; c < 3; ++c) kout[3 * j + c] = gain(j, c);
  }
  Eigen::Map<Eigen::Matrix3d>(&run->covariance[9 * i]) = s;
  for (int c = 0; c < 3; ++c) run->innovations[3 * i + c] = e[c];
  const Matrix6 a = Matrix6::Identity() - gain * hx;
  *p = a * *p * a.transpose() + gain * r * gain.transpose();
  return true;
}

}  // namespace

bool MotionModel::Filter(const double* values,
                         const double* times,
                         int n,
                         const double* measured,
                         const std::array<double, 3>& process,
                         const std::array<double, 3>& sigma,
                         FilterRun* run,
                         IntegrationFailure* failure) const {
  CHECK(random_moment_ == nullptr)
      << "process noise is for simulation; fits model it otherwise";
  std::array<double, kMaxParameters> internal;
  ToInternal(values, &internal);
  const CoefficientView<double> k(internal.data(), active_);
  // The process noise's spectral density on the state at x: G W G^T, W
  // the accelerations' densities (internal units) and G = df/d(moment),
  // the way simulate's random moments enter (f is linear in them).
  Eigen::Vector3d w;
  for (int axis = 0; axis < 3; ++axis) {
    w[axis] = std::pow(process[axis] * kDegree, 2);
  }
  auto density = [&](const double* state) {
    Matrix63 g;
    double base[6], pushed[6];
    Derivative(k, state, base);
    for (int axis = 0; axis < 3; ++axis) {
      TunnelMoment unit;
      (axis == 0 ? unit.roll : axis == 1 ? unit.pitch : unit.yaw) = 1.0;
      Derivative(k, state, pushed, &unit);
      for (int j = 0; j < 6; ++j) g(j, axis) = pushed[j] - base[j];
    }
    return Matrix6(g * w.asDiagonal() * g.transpose());
  };
  Eigen::Matrix3d r = Eigen::Matrix3d::Zero();
  for (int c = 0; c < 3; ++c) r(c, c) = sigma[c] * sigma[c];

  run->gains.assign(18 * n, 0.0);
  run->covariance.assign(9 * n, 0.0);
  run->innovations.assign(3 * n, 0.0);
  run->deviance = 0.0;
  run->normalized_sum = 0.0;
  StateJet x[6];
  for (int j = 0; j < 6; ++j) {
    x[j] = StateJet(internal[layout_.first_initial + j], j);
  }
  Matrix6 p = Matrix6::Zero();
  Matrix6 q_before;  // the density at the previous sample
  bool singular = false;
  auto observe = [&](int i, StateJet* y) {
    double state[6];
    for (int j = 0; j < 6; ++j) state[j] = y[j].a;
    if (i > 0) {
      const Matrix6 phi = Transition(y);
      const double dt = times[i] - times[i - 1];
      p = phi * p * phi.transpose() +
          0.5 * dt * (phi * q_before * phi.transpose() + density(state));
    }
    StateJet h[3];
    Measure(y, internal.data(), times[i] - times[0], h);
    Matrix36 hx;
    double e[3];
    for (int c = 0; c < 3; ++c) {
      hx.row(c) = h[c].v.transpose();
      e[c] = measured[3 * i + c] - h[c].a;
    }
    e[0] -= WholeTurns(e[0]);
    if (!Update(i, hx, e, r, &p, run)) {
      singular = true;
      return;
    }
    // As EvaluateFiltered corrects the state, term for term; the lanes
    // start again from the identity.
    const double* kout = &run->gains[18 * i];
    for (int j = 0; j < 6; ++j) {
      const double* kj = kout + 3 * j;
      const double corrected =
          y[j].a + (kj[0] * e[0] + kj[1] * e[1] + kj[2] * e[2]);
      y[j] = StateJet(corrected, j);
      state[j] = corrected;
    }
    q_before = density(state);
  };
  // The dynamic pressure's drift as Integrate applies it.
  std::array<double, kMaxParameters> drifted = internal;
  const CoefficientView<double> kd(drifted.data(), active_);
  auto rhs = [&](const StateJet* s, StateJet* ds) { Derivative(kd, s, ds); };
  auto step = [&](double t, double h) {
    if (!drifting_.empty()) {
      Drift(internal.data(), t + 0.5 * h - times[0], drifted.data());
    }
    RungeKutta4Step<StateJet, 6>(rhs, h, x);
  };
  if (!IntegrateSamplesWith<StateJet, 6>(
          step, times, n, spec_.max_step, Guard(), x, observe, failure)) {
    return false;
  }
  if (singular && failure != nullptr) {
    failure->reason = "the innovation covariance is not positive definite";
  }
  return !singular;
}

}  // namespace fit3dof
