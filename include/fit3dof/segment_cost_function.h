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
// reach the equations as constants. The Jacobian is built in passes of 12
// lanes (ceres::Jet<double, 12>), the last pass 4 wide when at most 4
// remain. Measured with bench/evaluation_benchmark (Table 6 record, 800
// samples; one forward integration 0.95 ms; more free parameters also
// switch on more terms of the model): Jacobian time over forward time,
// divided by k + 1,
//
//   free k                                   4     10     20     27
//   widths 4, 8, 12, 16, 24, 32, one pass  0.83   0.62   0.94   1.14
//   passes of 12 (or 4), this class        0.47   0.56   0.75   0.86
//   DynamicAutoDiffCostFunction, stride 4  0.49   0.64   0.74   0.81
//   DynamicAutoDiffCostFunction, stride 8  0.76   0.72   0.63   0.84
//
// (the Dynamic rows are the same residuals as a functor, all free
// coordinates in one block, built with the same inlining flags). Neither is
// faster across the board; this class is at 4 and 10 free, and it keeps the
// roll branch, the scaling and the count of failed evaluations in one
// place. Wider Jets cost more per lane than Jet<12> (their operations
// spill out of registers and L1), and GCC left Jet<8>'s Eigen loops out of
// line in this unit. The target of 0.5 (k + 1) is met only up to k = 4.
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

  // Lanes of one pass (the widest Jet instantiated); more free
  // coordinates take several passes.
  static constexpr int kMaxLanes = 12;

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
