// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/integration_step.h"

#include <glog/logging.h>

#include <algorithm>
#include <limits>
#include <memory>

#include "assembly.h"
#include "fit_problem.h"

namespace fit3dof {
namespace {

// Step doublings CoarsestStep tries: 32 times the config's step at most.
constexpr int kMaxDoublings = 5;

// The computed angles of each segment of `a` (empty where the motion
// cannot be integrated).
std::vector<std::vector<double>> SegmentAngles(const Assembly& a) {
  std::vector<std::vector<double>> angles(a.costs.size());
  for (size_t s = 0; s < a.costs.size(); ++s) {
    if (!a.costs[s]->ComputeAngles(
            SegmentFullValues(a, s), &angles[s], nullptr)) {
      angles[s].clear();
    }
  }
  return angles;
}

double WidestInterval(const std::vector<TimeHistory>& data) {
  double widest = 0.0;
  for (const TimeHistory& d : data) {
    for (int i = 1; i < d.size(); ++i) {
      widest = std::max(widest, d.t[i] - d.t[i - 1]);
    }
  }
  return widest;
}

}  // namespace

double StepChiSquare(const Case& c,
                     const std::vector<TimeHistory>& data,
                     const FitResult& fit,
                     double step) {
  CHECK_GT(step, 0.0);
  CHECK_EQ(fit.segments.size(), data.size());
  const FitProblem p = PrepareProblem(CaseAtSolution(c, fit), data);
  const std::vector<double> unit(p.free.size(), 1.0);
  const Assembly fine = Assemble(p.segments, p.free, p.model, p.values, unit);
  const Assembly coarse =
      Assemble(p.segments, p.free, p.model->WithMaxStep(step), p.values, unit);
  const auto a = SegmentAngles(fine);
  const auto b = SegmentAngles(coarse);
  double sum = 0.0;
  for (size_t s = 0; s < data.size(); ++s) {
    if (a[s].empty() || a[s].size() != b[s].size()) {
      return std::numeric_limits<double>::infinity();
    }
    const ChannelValues& sigma = fit.segments[s].sigma_deg;
    for (size_t i = 0; i < a[s].size(); ++i) {
      const double apart = (a[s][i] - b[s][i]) / sigma[i % 3];
      sum += apart * apart;
    }
  }
  return sum;
}

double CoarsestStep(const Case& c,
                    const std::vector<TimeHistory>& data,
                    const FitResult& fit,
                    double chi_square) {
  const double widest = WidestInterval(data);
  double step = c.solver.step;
  for (int k = 0; k < kMaxDoublings && 2.0 * step <= widest; ++k) {
    const double coarser = 2.0 * step;
    const double apart = StepChiSquare(c, data, fit, coarser);
    VLOG(1) << "integration step " << coarser << " s: motion apart by " << apart
            << " (limit " << chi_square << ")";
    if (!(apart <= chi_square)) break;
    step = coarser;
  }
  return step;
}

}  // namespace fit3dof
