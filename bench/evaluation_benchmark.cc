// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Cost of one residual evaluation (a forward integration) against one
// Jacobian evaluation of a segment residual block, for the Table 6 case
// (800 samples, step 0.01 s), as the number of free parameters k grows.
// The ratios are what matter: Jacobian / forward should stay below
// (k + 1) / 2, and 4 free parameters should cost at most a quarter of 27.
// BM_DynamicJacobian is the same residual block as Ceres'
// DynamicAutoDiffCostFunction would build it (stride 4, Ceres' default,
// and 8): the comparison SegmentCostFunction's header quotes.

#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <vector>

#include "ceres/dynamic_autodiff_cost_function.h"
#include "colored_covariance.h"
#include "fit3dof/config.h"
#include "fit3dof/segment_cost_function.h"
#include "fit3dof/time_history.h"

namespace fit3dof {
namespace {

struct Block {
  std::unique_ptr<SegmentCostFunction> cost;
  std::vector<double> u;  // free values (scale 1)
  std::shared_ptr<const MotionModel> model;
  std::vector<double> base;
  std::vector<int> free;
  TimeHistory data;
  ChannelValues sigma;
};

// The segment's residuals as a functor for DynamicAutoDiffCostFunction:
// every free coordinate in one parameter block, the equations evaluated
// with whatever Jet Ceres passes.
struct DynamicSegmentResiduals {
  const Block* b;

  template <typename T>
  bool operator()(T const* const* parameters, T* residuals) const {
    std::vector<T> full(b->base.size());
    for (size_t i = 0; i < b->base.size(); ++i) full[i] = T(b->base[i]);
    for (size_t j = 0; j < b->free.size(); ++j) {
      full[b->free[j]] = parameters[0][j];
    }
    const int n = b->data.size();
    std::vector<T> angles(3 * n);
    if (!b->model->Evaluate(
            full.data(), b->data.t.data(), n, angles.data(), nullptr)) {
      return false;
    }
    const double sigma[3] = {b->sigma.phi, b->sigma.theta, b->sigma.psi};
    const double* measured[3] = {
        b->data.phi.data(), b->data.theta.data(), b->data.psi.data()};
    for (int i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) {
        residuals[3 * i + c] = (angles[3 * i + c] - measured[c][i]) / sigma[c];
      }
    }
    return true;
  }
};

// The Table 6 truth with the first k of the symmetric model's 27 usable
// parameters free: the four of Table 6, the six initial conditions, then
// every other term.
Block MakeBlock(int k) {
  static const Case c = LoadConfig(std::string(FIT3DOF_SOURCE_DIR) +
                                   "/configs/report/table6_sigma0.01.yaml");
  static const TimeHistory data = ReadTimeHistory(c.segments[0].data_file);
  std::vector<double> base = c.Values();
  const std::vector<std::pair<int, double>> truth = {{0, -0.236},
                                                     {1, -4.0},
                                                     {4, 5.81},
                                                     {5, 98.5},
                                                     {25, 641.0},
                                                     {26, 5.18},
                                                     {27, -26.356},
                                                     {28, -2.589},
                                                     {29, -7.77}};
  for (auto [i, v] : truth) base[i] = v;
  const std::vector<int> order = {0,  1,  4,  5,  24, 25, 26, 27, 28,
                                  29, 2,  3,  6,  7,  8,  9,  10, 11,
                                  12, 13, 14, 18, 19, 20, 21, 22, 23};
  const std::vector<int> free(order.begin(), order.begin() + k);
  std::vector<bool> flags(base.size(), false);
  for (int i : free) flags[i] = true;
  auto model = std::make_shared<const MotionModel>(
      c.Spec(), ActiveParameters(base, flags));
  Block b;
  for (int i : free) b.u.push_back(base[i]);
  b.model = model;
  b.base = base;
  b.free = free;
  b.data = data;
  b.sigma = c.sigma;
  b.cost = std::make_unique<SegmentCostFunction>(
      model, base, free, k, std::vector<double>(k, 1.0), data, c.sigma);
  return b;
}

void BM_Forward(benchmark::State& state) {
  Block b = MakeBlock(static_cast<int>(state.range(0)));
  std::vector<double> residuals(b.cost->num_residuals());
  const double* blocks[1] = {b.u.data()};
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        b.cost->Evaluate(blocks, residuals.data(), nullptr));
  }
}

// Times Jacobian evaluations of `cost` at the block's values.
void TimeJacobians(benchmark::State& state,
                   const Block& b,
                   const ceres::CostFunction& cost) {
  const int k = static_cast<int>(b.u.size());
  std::vector<double> residuals(cost.num_residuals());
  std::vector<double> jacobian(cost.num_residuals() * k);
  const double* blocks[1] = {b.u.data()};
  double* jacobians[1] = {jacobian.data()};
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        cost.Evaluate(blocks, residuals.data(), jacobians));
  }
}

// The cost function as fits use it (JacobianMethod::kAuto).
void BM_Jacobian(benchmark::State& state) {
  const Block b = MakeBlock(static_cast<int>(state.range(0)));
  TimeJacobians(state, b, *b.cost);
}

// Each of its two methods alone.
template <SegmentCostFunction::JacobianMethod kMethod>
void BM_JacobianBy(benchmark::State& state) {
  Block b = MakeBlock(static_cast<int>(state.range(0)));
  b.cost->set_jacobian_method(kMethod);
  TimeJacobians(state, b, *b.cost);
}
void BM_JetLaneJacobian(benchmark::State& state) {
  BM_JacobianBy<SegmentCostFunction::JacobianMethod::kJetLanes>(state);
}
void BM_SensitivityJacobian(benchmark::State& state) {
  BM_JacobianBy<SegmentCostFunction::JacobianMethod::kSensitivities>(state);
}

// The free-parameter counts both methods are timed at: every one the
// symmetric Table 6 case has.
void MethodArgs(benchmark::internal::Benchmark* b) {
  for (int k = 1; k <= 27; ++k) b->Arg(k);
}

template <int kStride>
void BM_DynamicJacobian(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0));
  const Block b = MakeBlock(k);
  ceres::DynamicAutoDiffCostFunction<DynamicSegmentResiduals, kStride> cost(
      new DynamicSegmentResiduals{&b});
  cost.AddParameterBlock(k);
  cost.SetNumResiduals(b.cost->num_residuals());
  TimeJacobians(state, b, cost);
}

// The colored-residual covariance of a Table 6 fit (three channels of 800
// samples, 10 free coordinates), the cost the standard errors add to a fit:
// tools/bench divides it by the whole fit's time.
void BM_ColoredCovariance(benchmark::State& state) {
  const int k = 10;
  Block b = MakeBlock(k);
  std::vector<double> residuals(b.cost->num_residuals());
  std::vector<double> jacobian(b.cost->num_residuals() * k);
  const double* blocks[1] = {b.u.data()};
  double* jacobians[1] = {jacobian.data()};
  b.cost->Evaluate(blocks, residuals.data(), jacobians);
  const int n = b.cost->num_samples();
  std::vector<ResidualSeries> series(3);
  Eigen::MatrixXd jtj = Eigen::MatrixXd::Zero(k, k);
  for (int ch = 0; ch < 3; ++ch) {
    series[ch].jacobian.resize(n, k);
    series[ch].residual.resize(n);
    series[ch].times = Eigen::VectorXd::LinSpaced(n, 0.0, 0.06 * (n - 1));
    // Roll at the Table 6 spin (the order spectrum's cost) and, in pitch
    // and yaw, an angle of about 5 deg (the calibration terms').
    series[ch].roll = 2.0 * M_PI * 1.78 * series[ch].times;
    if (ch > 0) {
      series[ch].angle =
          0.09 * (2.0 * M_PI * 0.3 * series[ch].times).array().sin();
    }
    for (int i = 0; i < n; ++i) {
      // Noise-like residuals: the truth's are zero.
      series[ch].residual(i) = std::sin(1e3 * (3 * i + ch));
      for (int a = 0; a < k; ++a) {
        series[ch].jacobian(i, a) = jacobian[(3 * i + ch) * k + a];
      }
    }
    jtj += series[ch].jacobian.transpose() * series[ch].jacobian;
  }
  const Eigen::MatrixXd b_matrix = jtj.inverse();
  for (auto _ : state) {
    std::vector<SeriesCorrelation> stats;
    benchmark::DoNotOptimize(SandwichCovariance(
        b_matrix, ColoredInformation(series, b_matrix, &stats)));
  }
}
BENCHMARK(BM_ColoredCovariance)->Unit(benchmark::kMillisecond);

BENCHMARK(BM_Forward)->Apply(MethodArgs)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Jacobian)->Apply(MethodArgs)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_JetLaneJacobian)->Apply(MethodArgs)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SensitivityJacobian)
    ->Apply(MethodArgs)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_DynamicJacobian, 4)
    ->Arg(4)
    ->Arg(10)
    ->Arg(20)
    ->Arg(27)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_DynamicJacobian, 8)
    ->Arg(4)
    ->Arg(10)
    ->Arg(20)
    ->Arg(27)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace fit3dof

BENCHMARK_MAIN();
