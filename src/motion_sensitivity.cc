// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// MotionModel::EvaluateWithSensitivities (motion_model.h): the measured
// angles and their derivatives with respect to m parameters by forward
// sensitivities.
//
// Why: with Jets every operation of the equations of motion carries all m
// derivative lanes, so a Jacobian costs about 0.5-0.7 forward passes per
// lane. The sensitivities S = dx/dp (6 x m) obey dS/dt = F_x S + F_p, where
// F_x = df/dx (6 x 6) and F_p = df/dp. Stepping (x, S) together with the
// motion's own RK4 formula gives exactly the derivatives of the RK4
// solution (for an explicit Runge-Kutta scheme, differentiating the steps
// and stepping the variational equations are the same arithmetic). Each
// right-hand side then costs one evaluation with a 6-lane Jet over the
// state (f and F_x), one with Jets over the free coefficients at a double
// state (F_p: only the operations that touch a coefficient carry lanes),
// and a 6 x 6 by 6 x m product. The initial conditions enter only S(0);
// the measurement model's parameters only the observation.

#include <glog/logging.h>

#include <Eigen/Core>
#include <array>
#include <vector>

#include "ceres/jet.h"
#include "fit3dof/motion_model.h"

namespace fit3dof {
namespace {

using StateJet = ceres::Jet<double, 6>;

// Coefficient lanes per Jet pass of F_p and of the measurement model.
constexpr int kCoefficientLanes = 12;
using CoefficientJet = ceres::Jet<double, kCoefficientLanes>;

// The parameters in internal units as Jets whose lanes carry the
// derivatives with respect to up to kCoefficientLanes of them.
struct CoefficientPass {
  std::array<CoefficientJet, kMaxParameters> internal;
  std::vector<int> columns;  // column of the Jacobian of each lane
};

// Seeds one StateJet per state variable: lane j is d/dx_j.
void SeedState(const double* x, StateJet* xj) {
  for (int j = 0; j < 6; ++j) xj[j] = StateJet(x[j], j);
}

}  // namespace

bool MotionModel::EvaluateWithSensitivities(const double* values,
                                            const int* wrt,
                                            int m,
                                            const double* times,
                                            int n,
                                            double* angles,
                                            double* jacobian,
                                            IntegrationFailure* failure) const {
  CHECK(random_moment_ == nullptr)
      << "process noise is for simulation; fits model it otherwise";
  const int np = num_parameters();
  std::array<double, kMaxParameters> internal;
  ToInternal(values, &internal);
  const CoefficientView<double> k(internal.data(), active_);
  const int first_initial = layout_.first_initial;

  // z = (x, S) with S column-major: S(j, l) = z[6 + 6 l + j].
  const int dim = 6 + 6 * m;
  std::vector<double> z(dim, 0.0);
  for (int j = 0; j < 6; ++j) z[j] = internal[first_initial + j];
  std::vector<CoefficientPass> passes;
  for (int l = 0; l < m; ++l) {
    const int i = wrt[l];
    CHECK(i >= 0 && i < np) << "parameter " << i;
    if (i >= first_initial && i < first_initial + 6) {
      z[6 + 6 * l + (i - first_initial)] = scale_[i];
      continue;
    }
    if (passes.empty() ||
        passes.back().columns.size() == size_t{kCoefficientLanes}) {
      passes.emplace_back();
      for (int p = 0; p < kMaxParameters; ++p) {
        passes.back().internal[p] = CoefficientJet(internal[p]);
      }
    }
    CoefficientPass& pass = passes.back();
    pass.internal[i].v[pass.columns.size()] = scale_[i];
    pass.columns.push_back(l);
  }

  using Matrix6 = Eigen::Matrix<double, 6, 6, Eigen::RowMajor>;
  using Sensitivity = Eigen::Matrix<double, 6, Eigen::Dynamic>;
  auto rhs = [&](const double* y, double* dy) {
    StateJet xj[6], fj[6];
    SeedState(y, xj);
    Derivative(k, xj, fj);
    Matrix6 fx;
    for (int j = 0; j < 6; ++j) {
      dy[j] = fj[j].a;
      fx.row(j) = fj[j].v.transpose();
    }
    Eigen::Map<const Sensitivity> s(y + 6, 6, m);
    Eigen::Map<Sensitivity> ds(dy + 6, 6, m);
    ds.noalias() = fx * s;
    for (const CoefficientPass& pass : passes) {
      CoefficientJet fp[6];
      Derivative(CoefficientView<CoefficientJet>(pass.internal.data(), active_),
                 y,
                 fp);
      for (size_t lane = 0; lane < pass.columns.size(); ++lane) {
        for (int j = 0; j < 6; ++j) ds(j, pass.columns[lane]) += fp[j].v[lane];
      }
    }
  };

  auto observe = [&](int i, const double* y) {
    StateJet xj[6], aj[3];
    SeedState(y, xj);
    Measure(xj, internal.data(), aj);
    Eigen::Map<const Sensitivity> s(y + 6, 6, m);
    for (int c = 0; c < 3; ++c) {
      angles[3 * i + c] = aj[c].a;
      Eigen::Map<Eigen::RowVectorXd> row(jacobian + (3 * i + c) * m, m);
      row.noalias() = aj[c].v.transpose() * s;
    }
    for (const CoefficientPass& pass : passes) {
      CoefficientJet ap[3];
      Measure(y, pass.internal.data(), ap);
      for (size_t lane = 0; lane < pass.columns.size(); ++lane) {
        for (int c = 0; c < 3; ++c) {
          jacobian[(3 * i + c) * m + pass.columns[lane]] += ap[c].v[lane];
        }
      }
    }
  };

  std::vector<double> work(5 * dim);
  double* k1 = work.data();
  auto step = [&](double h) {
    RungeKutta4Step(rhs,
                    h,
                    dim,
                    z.data(),
                    k1,
                    k1 + dim,
                    k1 + 2 * dim,
                    k1 + 3 * dim,
                    k1 + 4 * dim);
  };
  return IntegrateSamplesWith<double, 6>(
      step, times, n, spec_.max_step, Guard(), z.data(), observe, failure);
}

}  // namespace fit3dof
