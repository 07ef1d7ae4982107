// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The Jet evaluation of SegmentCostFunction, included only by
// segment_cost_function.cc (Predict and WhitenedResiduals for doubles) and
// the translation units that instantiate EvaluateLanes for the supported
// widths (the autodiff templates are the expensive part of the build).

#ifndef FIT3DOF_SRC_SEGMENT_COST_FUNCTION_LANES_H_
#define FIT3DOF_SRC_SEGMENT_COST_FUNCTION_LANES_H_

#include <cmath>
#include <vector>

#include "ceres/jet.h"
#include "fit3dof/segment_cost_function.h"

namespace fit3dof {

template <typename T>
bool SegmentCostFunction::Predict(const MotionModel& model,
                                  const T* full,
                                  T* angles,
                                  IntegrationFailure* failure) const {
  const int n = data_.size();
  if (innovation_weights_ == nullptr) {
    return model.Evaluate(full, data_.t.data(), n, angles, failure);
  }
  if (!model.EvaluateFiltered(full,
                              data_.t.data(),
                              n,
                              measured_.data(),
                              innovation_weights_->gains.data(),
                              angles,
                              failure)) {
    return false;
  }
  // angles holds the innovations e = y - h: the prediction is y - e.
  for (int r = 0; r < 3 * n; ++r) angles[r] = measured_[r] - angles[r];
  return true;
}

template <typename T>
void SegmentCostFunction::WhitenedResiduals(int i,
                                            const T* computed,
                                            T* residuals) const {
  const double* w = &innovation_weights_->whitening[9 * i];
  T d[3];
  for (int c = 0; c < 3; ++c) d[c] = computed[c] - measured_[3 * i + c];
  for (int c = 0; c < 3; ++c) {
    residuals[c] = w[3 * c] * d[0] + w[3 * c + 1] * d[1] + w[3 * c + 2] * d[2];
  }
}

template <int N>
bool SegmentCostFunction::EvaluateLanes(const MotionModel& model,
                                        const double* u,
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
  ApplyTies(ties_, full.data());
  std::vector<J> angles(3 * n);
  if (!Predict(model, full.data(), angles.data(), nullptr)) return false;
  const double inv_sigma[3] = {
      1.0 / sigma_.phi, 1.0 / sigma_.theta, 1.0 / sigma_.psi};
  int block[N], column[N];
  for (int l = 0; l < count; ++l) Locate(lanes[l], &block[l], &column[l]);
  for (int i = 0; i < n; ++i) {
    J whitened[3];
    if (innovation_weights_ != nullptr) {
      WhitenedResiduals(i, &angles[3 * i], whitened);
    }
    for (int c = 0; c < 3; ++c) {
      const int row = 3 * i + c;
      double r;
      Eigen::Matrix<double, N, 1> dr;
      if (innovation_weights_ != nullptr) {
        r = whitened[c].a;
        dr = whitened[c].v;
      } else {
        r = WeightedResidual(i, c, angles[row].a, inv_sigma[c]);
        dr = angles[row].v * inv_sigma[c];
      }
      if (!std::isfinite(r)) return false;
      residuals[row] = r;
      for (int l = 0; l < count; ++l) {
        const double d = dr[l];
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
