// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The Jet evaluation of SegmentCostFunction, included only by the
// translation units that instantiate it for the supported widths (the
// autodiff templates are the expensive part of the build).

#ifndef FIT3DOF_SRC_SEGMENT_COST_FUNCTION_LANES_H_
#define FIT3DOF_SRC_SEGMENT_COST_FUNCTION_LANES_H_

#include <cmath>
#include <vector>

#include "ceres/jet.h"
#include "fit3dof/segment_cost_function.h"

namespace fit3dof {

template <int N>
bool SegmentCostFunction::EvaluateLanes(const double* u,
                                        const int* lanes,
                                        int count,
                                        double* residuals,
                                        double** jacobians) const {
  using J = ceres::Jet<double, N>;
  const int n = data_.size();
  std::vector<J> full(base_.size());
  for (size_t i = 0; i < base_.size(); ++i) full[i] = J(base_[i]);
  for (size_t j = 0; j < free_.size(); ++j)
    full[free_[j]] = J(scale_[j] * u[j]);
  for (int l = 0; l < count; ++l) full[free_[lanes[l]]].v[l] = scale_[lanes[l]];
  std::vector<J> angles(3 * n);
  if (!model_->Evaluate(
          full.data(), data_.t.data(), n, angles.data(), nullptr)) {
    return false;
  }
  const double inv_sigma[3] = {
      1.0 / sigma_.phi, 1.0 / sigma_.theta, 1.0 / sigma_.psi};
  int block[N], column[N];
  for (int l = 0; l < count; ++l) Locate(lanes[l], &block[l], &column[l]);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      const int row = 3 * i + c;
      const J& computed = angles[row];
      const double r = WeightedResidual(i, c, computed.a, inv_sigma[c]);
      if (!std::isfinite(r)) return false;
      residuals[row] = r;
      for (int l = 0; l < count; ++l) {
        const double d = computed.v[l] * inv_sigma[c];
        if (!std::isfinite(d)) return false;
        const int b = block[l];
        jacobians[b][row * parameter_block_sizes()[b] + column[l]] = d;
      }
    }
  }
  return true;
}

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_SEGMENT_COST_FUNCTION_LANES_H_
