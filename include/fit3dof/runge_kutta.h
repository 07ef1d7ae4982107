// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Classical fourth-order Runge-Kutta with a fixed step, the report's DRKGS,
// and the sample loop of its INTGRL: between two samples the interval is cut
// into the fewest equal substeps that do not exceed `max_step`.
//
// Templated on the scalar (double or ceres::Jet) and on the right-hand side,
// a callable `f(const T* x, T* dx)` of an autonomous system: the 3DOF
// equations do not depend on time explicitly. What does (simulate's random
// moments, a drifting dynamic pressure) the caller's step function holds
// over each step at its midpoint value (IntegrateSamplesWith gives the step
// its time; MotionModel::Integrate).
//
// Example Usage:
//
//   auto rhs = [&](const double* x, double* dx) { ... };
//   std::array<double, 6> x = x0;
//   IntegrationFailure failure;
//   bool ok = IntegrateSamples<double, 6>(rhs, times, n, 0.001, guard,
//       x.data(), [&](int i, const double* x) { store(i, x); }, &failure);

#ifndef FIT3DOF_RUNGE_KUTTA_H_
#define FIT3DOF_RUNGE_KUTTA_H_

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>

#include "ceres/jet.h"
#include "fit3dof/angles.h"

namespace fit3dof {

// One RK4 step of size h, in place, for a system of `dim` states (an int,
// or a std::integral_constant when the size is known at compile time),
// with k1..k4 and y as scratch of dim values each (none of them x). The
// forward sensitivities (MotionModel::EvaluateWithSensitivities) step the
// motion and its derivatives with this same formula, so that their
// derivatives are those of this scheme.
template <typename T, typename Rhs, typename Dim>
void RungeKutta4Step(const Rhs& f,
                     double h,
                     Dim dim,
                     T* __restrict x,
                     T* __restrict k1,
                     T* __restrict k2,
                     T* __restrict k3,
                     T* __restrict k4,
                     T* __restrict y) {
  f(x, k1);
  for (int i = 0; i < dim; ++i) y[i] = x[i] + (0.5 * h) * k1[i];
  f(y, k2);
  for (int i = 0; i < dim; ++i) y[i] = x[i] + (0.5 * h) * k2[i];
  f(y, k3);
  for (int i = 0; i < dim; ++i) y[i] = x[i] + h * k3[i];
  f(y, k4);
  for (int i = 0; i < dim; ++i) {
    x[i] += (h / 6.0) * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
  }
}

// The same step for a system whose size is known at compile time.
template <typename T, int kDim, typename Rhs>
void RungeKutta4Step(const Rhs& f, double h, T* x) {
  T k1[kDim], k2[kDim], k3[kDim], k4[kDim], y[kDim];
  RungeKutta4Step(
      f, h, std::integral_constant<int, kDim>(), x, k1, k2, k3, k4, y);
}

// RK4 steps to integrate through n sample times with substeps of at most
// max_step: the work of one evaluation of the motion. A double, so that a
// time column in the wrong units gives a large number, not an overflow.
inline double TotalSubsteps(const double* times, int n, double max_step) {
  double total = 0.0;
  for (int i = 1; i < n; ++i) {
    total +=
        std::max(1.0, std::ceil((times[i] - times[i - 1]) / max_step - 1e-9));
  }
  return total;
}

// Number of equal substeps for an interval so that none exceeds max_step.
// Callers keep interval / max_step within an int (CheckIntegrationSteps).
inline int NumSubsteps(double interval, double max_step) {
  const int n = static_cast<int>(std::ceil(interval / max_step - 1e-9));
  return n < 1 ? 1 : n;
}

// Why an integration stopped early.
struct IntegrationFailure {
  double time = 0.0;
  std::string reason;
};

inline double ScalarPart(double x) { return x; }
template <typename U, int N>
double ScalarPart(const ceres::Jet<U, N>& x) {
  return x.a;
}

// Guards the integration: the state must stay finite and |theta| below
// `max_abs_theta` radians, where the Euler-angle equations (1/cos(theta))
// are still well away from their singularity at 90 deg.
struct StateGuard {
  int theta_index = 2;
  double max_abs_theta = 85.0 * kDegree;
};

// Integrates from times[0] (x holds the state there) through times[n-1],
// calling observe(i, x) at every sample, the first included: step(t, h)
// advances the system by one RK4 step of size h from time t (times[0] plus
// the steps taken so far, for what the step holds over it), its first kDim
// values being the motion's state x, which the guard checks. observe may
// correct x (a filter's update); the integration goes on from the corrected
// state. Returns false and fills `failure` if the guard trips.
template <typename T, int kDim, typename Step, typename Observe>
bool IntegrateSamplesWith(const Step& step,
                          const double* times,
                          int n,
                          double max_step,
                          const StateGuard& guard,
                          T* x,
                          const Observe& observe,
                          IntegrationFailure* failure) {
  auto check = [&](double t) {
    for (int j = 0; j < kDim; ++j) {
      if (!std::isfinite(ScalarPart(x[j]))) {
        if (failure != nullptr) {
          failure->time = t;
          failure->reason = "the motion became infinite or NaN";
        }
        return false;
      }
    }
    if (std::abs(ScalarPart(x[guard.theta_index])) > guard.max_abs_theta) {
      if (failure != nullptr) {
        failure->time = t;
        failure->reason =
            "theta reached " +
            std::to_string(ScalarPart(x[guard.theta_index]) *
                           kDegreesPerRadian) +
            " deg; the Euler-angle equations are singular at 90 deg";
      }
      return false;
    }
    return true;
  };
  if (n <= 0) return true;
  if (!check(times[0])) return false;
  observe(0, x);
  double t = times[0];
  for (int i = 1; i < n; ++i) {
    const double interval = times[i] - times[i - 1];
    const int substeps = NumSubsteps(interval, max_step);
    const double h = interval / substeps;
    for (int s = 0; s < substeps; ++s) {
      step(t, h);
      t += h;
    }
    if (!check(times[i])) return false;
    observe(i, x);
  }
  return true;
}

// IntegrateSamplesWith for the system dx/dt = f(x) of kDim states.
template <typename T, int kDim, typename Rhs, typename Observe>
bool IntegrateSamples(const Rhs& f,
                      const double* times,
                      int n,
                      double max_step,
                      const StateGuard& guard,
                      T* x,
                      const Observe& observe,
                      IntegrationFailure* failure) {
  auto step = [&](double, double h) { RungeKutta4Step<T, kDim>(f, h, x); };
  return IntegrateSamplesWith<T, kDim>(
      step, times, n, max_step, guard, x, observe, failure);
}

}  // namespace fit3dof

#endif  // FIT3DOF_RUNGE_KUTTA_H_
