// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// One data segment as a Ceres residual block (segment_cost_function.h):
// the forward pass, the Jacobian in passes of Jet lanes.

#include "fit3dof/segment_cost_function.h"

#include <glog/logging.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "fit3dof/angles.h"
#include "segment_cost_function_lanes.h"

namespace fit3dof {
// Compiled in segment_cost_function_jets_N.cc, each width in its own unit
// (in parallel); this unit needs only Predict and WhitenedResiduals for
// doubles from the header.
#define FIT3DOF_JET_WIDTH(N)                                                 \
  extern template bool SegmentCostFunction::EvaluateLanes<N>(                \
      const MotionModel&, const double*, const int*, int, double*, double**) \
      const;
FIT3DOF_JET_WIDTH(2)
FIT3DOF_JET_WIDTH(4)
FIT3DOF_JET_WIDTH(6)
FIT3DOF_JET_WIDTH(8)
FIT3DOF_JET_WIDTH(12)
#undef FIT3DOF_JET_WIDTH
}  // namespace fit3dof

namespace fit3dof {

SegmentCostFunction::SegmentCostFunction(
    std::shared_ptr<const MotionModel> model,
    std::vector<double> base,
    std::vector<int> free,
    int num_shared,
    std::vector<double> scale,
    TimeHistory data,
    ChannelValues sigma)
    : model_(std::move(model)),
      base_(std::move(base)),
      free_(std::move(free)),
      num_shared_(num_shared),
      scale_(std::move(scale)),
      data_(std::move(data)),
      sigma_(sigma) {
  const int num_own = static_cast<int>(free_.size()) - num_shared_;
  if (num_shared_ > 0) mutable_parameter_block_sizes()->push_back(num_shared_);
  if (num_own > 0) mutable_parameter_block_sizes()->push_back(num_own);
  set_num_residuals(3 * data_.size());
}

void SegmentCostFunction::Locate(int j, int* block, int* column) const {
  if (j < num_shared_) {
    *block = 0;
    *column = j;
  } else {
    *block = num_shared_ > 0 ? 1 : 0;
    *column = j - num_shared_;
  }
}

void SegmentCostFunction::GatherFree(double const* const* parameters,
                                     double* u) const {
  for (size_t j = 0; j < free_.size(); ++j) {
    int block, column;
    Locate(static_cast<int>(j), &block, &column);
    u[j] = parameters[block][column];
  }
}

std::vector<double> SegmentCostFunction::FullFromFree(const double* u) const {
  std::vector<double> full = base_;
  for (size_t j = 0; j < free_.size(); ++j) full[free_[j]] = scale_[j] * u[j];
  ApplyTies(ties_, full.data());
  return full;
}

void SegmentCostFunction::set_ties(std::vector<ParameterTie> ties) {
  for (const ParameterTie& tie : ties) {
    CHECK(std::find(free_.begin(), free_.end(), tie.image) == free_.end())
        << "tied parameter " << tie.image << " is free";
  }
  ties_ = std::move(ties);
  remembered_.valid = false;  // residuals of other full values
}

std::vector<double> SegmentCostFunction::FullValues(
    double const* const* parameters) const {
  std::vector<double> u(free_.size());
  GatherFree(parameters, u.data());
  return FullFromFree(u.data());
}

double SegmentCostFunction::WeightedResidual(int i,
                                             int c,
                                             double computed,
                                             double inv_sigma) const {
  const double* measured[3] = {
      data_.phi.data(), data_.theta.data(), data_.psi.data()};
  double offset = 0.0;
  if (c == 0) offset = WholeTurns(computed - measured[0][i]);
  return (computed - offset - measured[c][i]) * inv_sigma;
}

void SegmentCostFunction::set_innovation_weights(
    std::shared_ptr<const InnovationWeights> w) {
  if (w != nullptr) {
    const int n = data_.size();
    CHECK_EQ(w->gains.size(), 18u * n);
    CHECK_EQ(w->whitening.size(), 9u * n);
    measured_.resize(3 * n);
    for (int i = 0; i < n; ++i) {
      measured_[3 * i] = data_.phi[i];
      measured_[3 * i + 1] = data_.theta[i];
      measured_[3 * i + 2] = data_.psi[i];
    }
  }
  innovation_weights_ = std::move(w);
  remembered_.valid = false;  // residuals weighted otherwise
}

bool SegmentCostFunction::ComputeAngles(const std::vector<double>& full,
                                        std::vector<double>* angles,
                                        IntegrationFailure* failure) const {
  const int n = data_.size();
  angles->resize(3 * n);
  if (!Predict(*model_, full.data(), angles->data(), failure)) return false;
  if (innovation_weights_ != nullptr) return true;  // on the branch already
  for (int i = 0; i < n; ++i) {
    double& phi = (*angles)[3 * i];
    phi -= WholeTurns(phi - data_.phi[i]);
  }
  return true;
}

bool SegmentCostFunction::EvaluatePass(const MotionModel& model,
                                       const double* u,
                                       const int* lanes,
                                       int count,
                                       double* residuals,
                                       double** jacobians) const {
  CHECK_LE(count, kMaxLanes);
#ifndef FIT3DOF_FEWER_JET_WIDTHS
  if (count <= 2) {
    return EvaluateLanes<2>(model, u, lanes, count, residuals, jacobians);
  }
#endif
  if (count <= 4) {
    return EvaluateLanes<4>(model, u, lanes, count, residuals, jacobians);
  }
#ifndef FIT3DOF_FEWER_JET_WIDTHS
  if (count <= 6) {
    return EvaluateLanes<6>(model, u, lanes, count, residuals, jacobians);
  }
#endif
  if (count <= 8) {
    return EvaluateLanes<8>(model, u, lanes, count, residuals, jacobians);
  }
  return EvaluateLanes<12>(model, u, lanes, count, residuals, jacobians);
}

bool SegmentCostFunction::EvaluateSensitivities(const MotionModel& model,
                                                const double* u,
                                                const std::vector<int>& lanes,
                                                double* residuals,
                                                double** jacobians) const {
  const std::vector<double> full = FullFromFree(u);
  const int n = data_.size();
  const int m = static_cast<int>(lanes.size());
  std::vector<int> wrt(m), block(m), column(m);
  for (int l = 0; l < m; ++l) {
    wrt[l] = free_[lanes[l]];
    Locate(lanes[l], &block[l], &column[l]);
  }
  // A tied image's sensitivity is added to its source's column.
  struct ImageColumn {
    int lane;
    double factor;
  };
  std::vector<ImageColumn> images;
  for (const ParameterTie& tie : ties_) {
    for (int l = 0; l < m; ++l) {
      if (wrt[l] != tie.source) continue;
      images.push_back({l, tie.factor});
      wrt.push_back(tie.image);
    }
  }
  const int columns = static_cast<int>(wrt.size());
  std::vector<double> angles(3 * n), derivatives(3 * n * columns);
  if (!model.EvaluateWithSensitivities(full.data(),
                                       wrt.data(),
                                       columns,
                                       data_.t.data(),
                                       n,
                                       angles.data(),
                                       derivatives.data(),
                                       nullptr)) {
    return false;
  }
  const double inv_sigma[3] = {
      1.0 / sigma_.phi, 1.0 / sigma_.theta, 1.0 / sigma_.psi};
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      const int row = 3 * i + c;
      const double r = WeightedResidual(i, c, angles[row], inv_sigma[c]);
      if (!std::isfinite(r)) return false;
      residuals[row] = r;
      double* dvalue = &derivatives[row * columns];
      for (size_t e = 0; e < images.size(); ++e) {
        dvalue[images[e].lane] += images[e].factor * dvalue[m + e];
      }
      for (int l = 0; l < m; ++l) {
        // d/du = scale d/dvalue (value = scale u).
        const double d = dvalue[l] * scale_[lanes[l]] * inv_sigma[c];
        if (!std::isfinite(d)) return false;
        const int b = block[l];
        jacobians[b][row * parameter_block_sizes()[b] + column[l]] = d;
      }
    }
  }
  return true;
}

bool SegmentCostFunction::Evaluate(double const* const* parameters,
                                   double* residuals,
                                   double** jacobians) const {
  const bool ok = EvaluateOrFail(parameters, residuals, jacobians);
  if (!ok) ++failures_;
  return ok;
}

bool SegmentCostFunction::EvaluateOrFail(double const* const* parameters,
                                         double* residuals,
                                         double** jacobians) const {
  const int k = static_cast<int>(free_.size());
  std::vector<double> u(k);
  GatherFree(parameters, u.data());
  std::vector<int> lanes;
  if (jacobians != nullptr) {
    for (int j = 0; j < k; ++j) {
      int block, column;
      Locate(j, &block, &column);
      if (jacobians[block] != nullptr) lanes.push_back(j);
    }
  }
  if (lanes.empty()) {
    const bool ok = EvaluateResiduals(u.data(), residuals);
    if (remembered_.on) {
      remembered_.valid = ok;
      remembered_.u = u;
      remembered_.residuals.assign(residuals, residuals + num_residuals());
    }
    return ok;
  }
  if (SkippedJacobian(u, residuals, jacobians)) return true;
  ++jacobians_;
  if (jacobian_model_ == nullptr || innovation_weights_ != nullptr) {
    return EvaluateJacobian(*model_, u.data(), lanes, residuals, jacobians);
  }
  // The residuals from the model's motion, the Jacobian from the coarser
  // one (its residuals discarded), or from the model's where that fails.
  // Ceres evaluates the Jacobian of an accepted step at the trial point
  // whose residuals it has just had: those, when remembered, are the same
  // numbers (a third of the fine integrations of a fit).
  if (!RememberedResiduals(u, residuals) &&
      !EvaluateResiduals(u.data(), residuals)) {
    return false;
  }
  std::vector<double> coarse(num_residuals());
  if (EvaluateJacobian(
          *jacobian_model_, u.data(), lanes, coarse.data(), jacobians)) {
    return true;
  }
  return EvaluateJacobian(*model_, u.data(), lanes, coarse.data(), jacobians);
}

bool SegmentCostFunction::EvaluateResiduals(const double* u,
                                            double* residuals) const {
  const std::vector<double> full = FullFromFree(u);
  std::vector<double> angles;
  if (!ComputeAngles(full, &angles, nullptr)) return false;
  if (innovation_weights_ != nullptr) {
    for (int i = 0; i < data_.size(); ++i) {
      WhitenedResiduals(i, &angles[3 * i], residuals + 3 * i);
    }
    for (int r = 0; r < num_residuals(); ++r) {
      if (!std::isfinite(residuals[r])) return false;
    }
    return true;
  }
  const double* measured[3] = {
      data_.phi.data(), data_.theta.data(), data_.psi.data()};
  const double sigma[3] = {sigma_.phi, sigma_.theta, sigma_.psi};
  for (int i = 0; i < data_.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double r = (angles[3 * i + c] - measured[c][i]) / sigma[c];
      if (!std::isfinite(r)) return false;
      residuals[3 * i + c] = r;
    }
  }
  return true;
}

bool SegmentCostFunction::EvaluateJacobian(const MotionModel& model,
                                           const double* u,
                                           const std::vector<int>& lanes,
                                           double* residuals,
                                           double** jacobians) const {
  const int columns = static_cast<int>(lanes.size());
  // The filter's predictor has no sensitivity form: Jet lanes.
  const bool sensitivities =
      innovation_weights_ == nullptr &&
      (method_ == JacobianMethod::kSensitivities ||
       (method_ == JacobianMethod::kAuto && columns >= kMinSensitivityColumns));
  if (sensitivities) {
    return EvaluateSensitivities(model, u, lanes, residuals, jacobians);
  }
  // Passes of up to 12 lanes, each as narrow as its columns allow (2, 4, 6,
  // 8 or 12; the header says why).
  for (size_t first = 0, count = 0; first < lanes.size(); first += count) {
    count = std::min<size_t>(kMaxLanes, lanes.size() - first);
    if (!EvaluatePass(model,
                      u,
                      lanes.data() + first,
                      static_cast<int>(count),
                      residuals,
                      jacobians)) {
      return false;
    }
  }
  return true;
}

void SegmentCostFunction::set_remember_residuals(bool on) {
  remembered_ = Remembered();
  remembered_.on = on;
}

double SegmentCostFunction::remembered_cost() const {
  if (!remembered_.valid) return std::numeric_limits<double>::quiet_NaN();
  // As Ceres computes a block's cost (ResidualBlock::Evaluate).
  return 0.5 * Eigen::Map<const Eigen::VectorXd>(remembered_.residuals.data(),
                                                 num_residuals())
                   .squaredNorm();
}

bool SegmentCostFunction::RememberedResiduals(const std::vector<double>& u,
                                              double* residuals) const {
  if (!remembered_.valid || u != remembered_.u) return false;
  std::copy(
      remembered_.residuals.begin(), remembered_.residuals.end(), residuals);
  return true;
}

bool SegmentCostFunction::SkippedJacobian(const std::vector<double>& u,
                                          double* residuals,
                                          double** jacobians) const {
  const bool skip = remembered_.skip;
  remembered_.skip = false;
  if (!skip || !RememberedResiduals(u, residuals)) return false;
  const std::vector<int32_t>& sizes = parameter_block_sizes();
  for (size_t b = 0; b < sizes.size(); ++b) {
    if (jacobians[b] != nullptr) {
      std::fill_n(jacobians[b], num_residuals() * sizes[b], 0.0);
    }
  }
  return true;
}

void SegmentCostFunction::set_jacobian_step(double step) {
  jacobian_model_ =
      step > model_->spec().max_step ? model_->WithMaxStep(step) : nullptr;
}

}  // namespace fit3dof
