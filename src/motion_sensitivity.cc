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
// and the product F_x S. The initial conditions enter only S(0); the
// measurement model's parameters only the observation.
//
// S is stored row by row (row j: dx_j/dp, m entries), so that a row of
// F_x S is a sum of six contiguous rows (vectorized), and a kinematic row
// of the symmetric program (dx_j/dt = x_rate exactly) is a copy of row
// `rate`: half of F_x S costs nothing there.

#include <glog/logging.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <type_traits>
#include <utility>
#include <vector>

#include "ceres/jet.h"
#include "fit3dof/motion_model.h"

namespace fit3dof {
namespace {

using StateJet = ceres::Jet<double, 6>;

// The parameters in internal units as Jets whose lanes carry the
// derivatives with respect to up to kLanes of them (a lane costs the same
// whether used or not).
template <int kLanes>
struct CoefficientPass {
  using Jet = ceres::Jet<double, kLanes>;
  std::array<Jet, kMaxParameters> internal;
  int first = 0;  // the lanes' columns of S: first, first + 1, ...
  int lanes = 0;  // lanes in use
};

// Lanes per pass: 8, the last pass 4 or 2 when at most that many remain
// (a 2-lane pass for the last one or two columns: 0.92x of a 4-lane one
// at k = 16, 2026-11-23; carrying them in spare lanes of the state
// pass instead cost 1.15x, as every coefficient there becomes a Jet).
// Measured on the Table 6 record with 20 and 27 free
// (bench/evaluation_benchmark, least of 6 interleaved runs): 8-lane passes cost
// 0.85x and 0.89x of 12-lane ones, though they execute 6% more instructions.
constexpr int kWide = 8;
struct CoefficientPasses {
  std::vector<CoefficientPass<kWide>> wide;
  std::vector<CoefficientPass<4>> narrow;
  std::vector<CoefficientPass<2>> thin;

  template <typename Visit>
  void ForEach(const Visit& visit) const {
    for (const auto& pass : wide) visit(pass);
    for (const auto& pass : narrow) visit(pass);
    for (const auto& pass : thin) visit(pass);
  }

  // visit(&pass, other's pass) for each pass of these and the same one of
  // `other`, built from the same parameters.
  template <typename Visit>
  void ForEachWith(const CoefficientPasses& other, const Visit& visit) {
    for (size_t i = 0; i < wide.size(); ++i) visit(&wide[i], other.wide[i]);
    for (size_t i = 0; i < narrow.size(); ++i)
      visit(&narrow[i], other.narrow[i]);
    for (size_t i = 0; i < thin.size(); ++i) visit(&thin[i], other.thin[i]);
  }
};

// Seeds `pass` with the parameters `internal`, lane l carrying the scale
// of parameters[first + l], the derivative for column first + l of S.
template <int kLanes>
void SeedPass(const std::array<double, kMaxParameters>& internal,
              const std::vector<double>& scale,
              const std::vector<int>& parameters,
              int first,
              int lanes,
              CoefficientPass<kLanes>* pass) {
  CHECK_LE(lanes, kLanes);
  for (int p = 0; p < kMaxParameters; ++p) {
    pass->internal[p] = typename CoefficientPass<kLanes>::Jet(internal[p]);
  }
  for (int lane = 0; lane < lanes; ++lane) {
    const int parameter = parameters[first + lane];
    pass->internal[parameter].v[lane] = scale[parameter];
  }
  pass->first = first;
  pass->lanes = lanes;
}

// The passes for the coefficients `parameters`, S's first columns.
CoefficientPasses MakePasses(const std::array<double, kMaxParameters>& internal,
                             const std::vector<double>& scale,
                             const std::vector<int>& parameters) {
  CoefficientPasses passes;
  const int count = static_cast<int>(parameters.size());
  for (int first = 0; first < count; first += kWide) {
    const int lanes = std::min(count - first, kWide);
    auto seed = [&](auto* pass) {
      SeedPass(internal, scale, parameters, first, lanes, pass);
    };
    if (lanes <= 2) {
      seed(&passes.thin.emplace_back());
    } else if (lanes <= 4) {
      seed(&passes.narrow.emplace_back());
    } else {
      seed(&passes.wide.emplace_back());
    }
  }
  return passes;
}

// S's columns: the coefficients first (each pass's lanes on adjacent
// columns), then the initial conditions; column q of S is column
// jacobian_column[q] of the caller's Jacobian.
struct SensitivityColumns {
  SensitivityColumns(const int* wrt, int m, int first_initial, int np) {
    std::vector<int> initials;
    for (int l = 0; l < m; ++l) {
      const int i = wrt[l];
      CHECK(i >= 0 && i < np) << "parameter " << i;
      if (i >= first_initial && i < first_initial + 6) {
        initials.push_back(l);
      } else {
        jacobian_column.push_back(l);
        coefficient_parameters.push_back(i);
      }
    }
    jacobian_column.insert(
        jacobian_column.end(), initials.begin(), initials.end());
  }
  int num_coefficients() const {
    return static_cast<int>(coefficient_parameters.size());
  }

  std::vector<int> jacobian_column;
  std::vector<int> coefficient_parameters;  // of columns 0 .. num - 1
};

// Seeds one StateJet per state variable: lane j is d/dx_j.
void SeedState(const double* x, StateJet* xj) {
  for (int j = 0; j < 6; ++j) xj[j] = StateJet(x[j], j);
}

// The values of StateJet sines and cosines: the coefficient passes' trig.
SymmetricTrig<double> ValuesOf(const SymmetricTrig<StateJet>& t) {
  SymmetricTrig<double> values;
  values.st = t.st.a;
  values.ct = t.ct.a;
  values.sp = t.sp.a;
  values.cp = t.cp.a;
  return values;
}
AsymmetricTrig<double> ValuesOf(const AsymmetricTrig<StateJet>& t) {
  AsymmetricTrig<double> values;
  values.sf = t.sf.a;
  values.cf = t.cf.a;
  values.st = t.st.a;
  values.ct = t.ct.a;
  values.sp = t.sp.a;
  values.cp = t.cp.a;
  return values;
}

// out[l] = sum_j d[j] s[j m + l], l < m: a row of the gradient d times S.
void RowTimesSensitivity(const Eigen::Matrix<double, 6, 1>& d,
                         const double* __restrict s,
                         int m,
                         double* __restrict out) {
  for (int l = 0; l < m; ++l) {
    out[l] = d[0] * s[l] + d[1] * s[m + l] + d[2] * s[2 * m + l] +
             d[3] * s[3 * m + l] + d[4] * s[4 * m + l] + d[5] * s[5 * m + l];
  }
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
  const int first_initial = layout_.first_initial;

  const SensitivityColumns columns(wrt, m, first_initial, np);
  const CoefficientPasses passes =
      MakePasses(internal, scale_, columns.coefficient_parameters);
  // The equations of motion see the coefficients as the dynamic pressure
  // has drifted at each step (Integrate): these copies, updated per step
  // when q_drift is active; the measurement model sees them as given.
  std::array<double, kMaxParameters> drifted = internal;
  CoefficientPasses drifted_passes =
      drifting_.empty() ? CoefficientPasses() : passes;
  const CoefficientPasses& rate_passes =
      drifting_.empty() ? passes : drifted_passes;
  const CoefficientView<double> k(drifted.data(), active_);
  const std::vector<int>& jacobian_column = columns.jacobian_column;

  // z = (x, S) with S row by row: S(j, q) = z[6 + m j + q]; S(0) holds the
  // initial conditions' unit derivatives (times their scale).
  const int dim = 6 + 6 * m;
  std::vector<double> z(dim, 0.0);
  for (int j = 0; j < 6; ++j) z[j] = internal[first_initial + j];
  for (int q = columns.num_coefficients(); q < m; ++q) {
    const int i = wrt[jacobian_column[q]];
    z[6 + m * (i - first_initial) + q] = scale_[i];
  }

  // ds += F_p, each pass's lanes on its columns.
  auto add_coefficient_rates = [&](const double* y,
                                   const auto& trig,
                                   double* ds) {
    rate_passes.ForEach([&](const auto& pass) {
      typename std::decay_t<decltype(pass)>::Jet fp[6];
      Derivative(CoefficientView(pass.internal.data(), active_), y, trig, fp);
      for (int j = 0; j < 6; ++j) {
        if (kinematic_rate_[j] >= 0) continue;  // no coefficient in it
        double* out = ds + m * j + pass.first;
        for (int lane = 0; lane < pass.lanes; ++lane)
          out[lane] += fp[j].v[lane];
      }
    });
  };

  // f, F_x S and F_p at z = y, the state's sines and cosines computed once
  // (`trig`, over StateJets) for every pass.
  auto rates =
      [&](const double* y, const StateJet* xj, const auto& trig, double* dy) {
        StateJet fj[6];
        Derivative(k, xj, trig, fj);
        const double* s = y + 6;
        double* ds = dy + 6;
        for (int j = 0; j < 6; ++j) {
          dy[j] = fj[j].a;
          if (kinematic_rate_[j] >= 0) {
            std::copy_n(s + m * kinematic_rate_[j], m, ds + m * j);
          } else {
            RowTimesSensitivity(fj[j].v, s, m, ds + m * j);
          }
        }
        add_coefficient_rates(y, ValuesOf(trig), ds);
      };
  auto rhs = [&](const double* y, double* dy) {
    StateJet xj[6];
    SeedState(y, xj);
    if (spec_.model == ModelKind::kSymmetric) {
      rates(y, xj, SymmetricTrig<StateJet>(xj), dy);
    } else {
      rates(y, xj, AsymmetricTrig<StateJet>(xj), dy);
    }
  };

  std::vector<double> rows(3 * m);  // the sample's rows, S's column order
  auto observe = [&](int i, const double* y) {
    StateJet xj[6], aj[3];
    SeedState(y, xj);
    Measure(xj, internal.data(), times[i] - times[0], aj);
    for (int c = 0; c < 3; ++c) {
      angles[3 * i + c] = aj[c].a;
      RowTimesSensitivity(aj[c].v, y + 6, m, &rows[m * c]);
    }
    passes.ForEach([&](const auto& pass) {
      typename std::decay_t<decltype(pass)>::Jet ap[3];
      Measure(y, pass.internal.data(), times[i] - times[0], ap);
      for (int c = 0; c < 3; ++c) {
        for (int lane = 0; lane < pass.lanes; ++lane) {
          rows[m * c + pass.first + lane] += ap[c].v[lane];
        }
      }
    });
    for (int c = 0; c < 3; ++c) {
      double* out = jacobian + (3 * i + c) * m;
      for (int q = 0; q < m; ++q) out[jacobian_column[q]] = rows[m * c + q];
    }
  };

  std::vector<double> work(5 * dim);
  double* k1 = work.data();
  auto step = [&](double t, double h) {
    if (!drifting_.empty()) {
      const double elapsed = t + 0.5 * h - times[0];
      Drift(internal.data(), elapsed, drifted.data());
      drifted_passes.ForEachWith(passes, [&](auto* to, const auto& from) {
        Drift(from.internal.data(), elapsed, to->internal.data());
      });
    }
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
