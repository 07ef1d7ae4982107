// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// One data segment as one Ceres residual block. The cost function integrates
// the 3DOF equations (MotionModel) through RK4 and returns the
// sigma-weighted residuals of phi, theta, psi at every sample,
//
//   r = ((phi_c - phi_m) / s_phi, (theta_c - theta_m) / s_theta,
//        (psi_c - psi_m) / s_psi),
//
// with the computed roll angle moved to the branch nearest the measurement
// (roll is compared modulo 360 deg, as the listing's INTGRL does).
//
// Derivatives come from automatic differentiation: ceres::Jet carries them
// through the equations of motion, the moment models and the integrator. No
// sensitivity equations are written by hand.
//
// Frozen parameters cost nothing. Only free coordinates get a derivative
// lane: they live in their own parameter blocks (the shared aerodynamic
// block, then the segment's initial-condition block) while frozen values
// reach the equations as constants, and the Jet width is the smallest of a
// few instantiated sizes (4, 8, 12, 16, 24, 32) that holds the free
// coordinates; beyond 32 the Jacobian is built in passes of 32 lanes. (Ceres'
// AutoDiffCostFunction would seed a lane for every coordinate of every
// block, frozen or not.)
//
// Free coordinates are optimized in scaled units u = value / scale so that
// the Jacobian columns are of similar size; the covariance is unscaled
// afterwards.

#ifndef FIT3DOF_SEGMENT_COST_FUNCTION_H_
#define FIT3DOF_SEGMENT_COST_FUNCTION_H_

#include <atomic>
#include <memory>
#include <vector>

#include "ceres/cost_function.h"
#include "fit3dof/case.h"
#include "fit3dof/motion_model.h"
#include "fit3dof/time_history.h"

namespace fit3dof {

class SegmentCostFunction : public ceres::CostFunction {
 public:
  // base: the full parameter vector (report units) with the frozen values
  // and this segment's initial conditions. free: positions of the free
  // coordinates in that vector, the num_shared shared ones first (parameter
  // block 0 if num_shared > 0), then the segment's own (the next block).
  // scale: value = scale[j] * u[j] for free coordinate j.
  SegmentCostFunction(std::shared_ptr<const MotionModel> model,
                      std::vector<double> base,
                      std::vector<int> free,
                      int num_shared,
                      std::vector<double> scale,
                      TimeHistory data,
                      ChannelValues sigma);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

  // The full parameter vector for the blocks' current values.
  std::vector<double> FullValues(double const* const* parameters) const;

  // Computed measured angles (deg, 3 per sample) for a full parameter
  // vector; the roll angle on the branch nearest the measurement.
  bool ComputeAngles(const std::vector<double>& full,
                     std::vector<double>* angles,
                     IntegrationFailure* failure) const;

  const TimeHistory& data() const { return data_; }
  // Evaluations that failed because the motion blew up (trial steps that
  // Levenberg-Marquardt then rejects).
  int failed_evaluations() const { return failures_.load(); }
  int num_samples() const { return data_.size(); }
  int num_free() const { return static_cast<int>(free_.size()); }

  // Widest Jet instantiated; more free coordinates take several passes.
  static constexpr int kMaxLanes = 32;

 private:
  // Evaluates with Jets whose lanes carry the derivatives with respect to
  // free coordinates lanes[0..count).
  template <int N>
  bool EvaluateLanes(const double* u,
                     const int* lanes,
                     int count,
                     double* residuals,
                     double** jacobians) const;
  bool EvaluateOrFail(double const* const* parameters,
                      double* residuals,
                      double** jacobians) const;
  bool EvaluatePass(const double* u,
                    const int* lanes,
                    int count,
                    double* residuals,
                    double** jacobians) const;
  void GatherFree(double const* const* parameters, double* u) const;
  // Block and column of free coordinate j.
  void Locate(int j, int* block, int* column) const;

  std::shared_ptr<const MotionModel> model_;
  std::vector<double> base_;
  std::vector<int> free_;
  int num_shared_;
  std::vector<double> scale_;
  TimeHistory data_;
  ChannelValues sigma_;
  mutable std::atomic<int> failures_{0};
};

}  // namespace fit3dof

#endif  // FIT3DOF_SEGMENT_COST_FUNCTION_H_
