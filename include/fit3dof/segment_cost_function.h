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
// derivative is written by hand: even the sensitivity equations below take
// their F_x and F_p from Jets through the same templated equations.
//
// Frozen parameters cost nothing. Only free coordinates get a derivative
// column: they live in their own parameter blocks (the shared aerodynamic
// block, then the segment's initial-condition block) while frozen values
// reach the equations as constants. Two ways to the Jacobian:
//
// - Jet lanes: the motion integrated with ceres::Jet<double, N>, N = 2, 4,
//   6, 8 or 12 (the narrowest that holds the columns), one pass per 12
//   columns;
// - forward sensitivities (MotionModel::EvaluateWithSensitivities): the
//   motion and dx/dp stepped together, with a 6-lane Jet over the state and
//   8-lane Jets over the coefficients at each right-hand side (the last
//   pass 4 or 2 lanes when no more are left), the state's sines and
//   cosines computed once for all of them; the per-column work is three
//   rows of F_x S (the symmetric program's three kinematic rows are
//   copies) instead of every operation of the equations.
//
// Both give the same residuals exactly and the same derivatives to rounding
// (segment_cost_function_test). Either may run on a coarser motion
// (set_jacobian_step: a refit's Levenberg-Marquardt steps, stage_solver.h),
// the residuals still the model's. kAuto takes Jet lanes up to 8 columns and
// the sensitivities from 9 on. Measured with tools/bench
// (bench/evaluation_benchmark: Table 6 record, 800 samples, 4800 RK4
// steps; more free parameters also switch on more terms of the model, and
// each Jacobian is divided by the forward pass of the same model), least
// CPU time of 8 interleaved runs, Jacobian / forward / (k + 1), every k the
// symmetric case has (2026-11-23):
//
//  k        1    2    3    4    5    6    7    8    9   10   11   12   13   14
//  lanes  .84  .56  .61  .49  .53  .45  .51  .46  .78  .71  .60  .56  .69  .67
//  sens. 1.99 1.35 1.14  .90  .78  .67  .61  .54  .51  .47  .45  .42  .42  .41
//  kAuto  .84  .56  .61  .49  .53  .45  .52  .46  .51  .47  .45  .42  .42  .41
//
//  k       15   16   17   18   19   20   21   22   23   24   25   26   27
//  lanes  .66  .63  .64  .62  .65  .63  .84  .90  .87  .81  .87  .84  .84
//  sens.  .47  .45  .49  .47  .43  .43  .44  .47  .55  .52  .52  .50  .47
//  kAuto  .47  .45  .49  .48  .43  .43  .45  .47  .56  .52  .52  .50  .47
//
// (lanes: Jet lanes only; sens.: sensitivities only; kAuto: as fits run.)
// Before (same day, k = 1, 4, 8, 10, 12, 16, 20, 24, 27): 1.29, 0.53,
// 0.43, 0.54, 0.50, 0.55, 0.49, 0.51, 0.50; and before that 1.38, 0.55,
// 0.80, 0.67, 0.56, 0.62, 0.68, 0.65, 0.62. Repeated runs move single
// entries by up to 10%. Ceres' DynamicAutoDiffCostFunction (stride 4 and
// 8) is in the same table of tools/bench: no better.
//
// Where 0.5 (k + 1) is missed, and why. k <= 3: a Jacobian includes the
// residuals (one forward pass) and every operation then carries at least
// one derivative lane (about another), so about 2 forward passes is the
// floor: 0.5 (k + 1) is out of reach below k = 3 (k = 1 takes 1.7, k = 3
// a 4-lane pass, 2.4). k = 5, 7: one 6- or 8-lane pass costs what
// it costs at k = 6, 8 (3.2 and 4.1 forward passes), divided by one fewer
// column. k = 23-26: the tunnel terms switched on at k = 21-24 put more
// operations in every coefficient pass, and 17-20 coefficients need a
// third pass (about two forward passes whatever its lanes: the double
// arithmetic of the equations is repeated in each).

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

// The filter-error fit's weights (filter_error.h): the residuals become
// the innovations of a filter whose gains are held, whitened by their
// covariances: r_i = L_i^-1 (h(x-_i) - y_i), S_i = L_i L_i^T, with x-_i
// the state predicted from the previous sample's corrected one (as
// MotionModel::EvaluateFiltered computes it).
struct InnovationWeights {
  std::vector<double> gains;      // 18 n: K_i, 6 x 3 row-major
  std::vector<double> whitening;  // 9 n: L_i^-1, 3 x 3 row-major (1/deg)
};

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

  // Makes the residuals innovations (InnovationWeights; the sigmas then
  // serve only as the reported noise levels); null returns to output
  // error. Jacobians then come from Jet lanes.
  void set_innovation_weights(std::shared_ptr<const InnovationWeights> w);

  // Ties among the parameters (ParameterTie, case.h): each image follows
  // its source in every evaluation, and a free source's derivative counts
  // its images' (d/d source + factor d/d image). Images are never free.
  void set_ties(std::vector<ParameterTie> ties);

  // The full parameter vector for the blocks' current values.
  std::vector<double> FullValues(double const* const* parameters) const;

  // Computed measured angles (deg, 3 per sample) for a full parameter
  // vector; the roll angle on the branch nearest the measurement. With
  // innovation weights, the filter's one-step predictions.
  bool ComputeAngles(const std::vector<double>& full,
                     std::vector<double>* angles,
                     IntegrationFailure* failure) const;

  const TimeHistory& data() const { return data_; }
  // Evaluations that failed because the motion blew up (trial steps that
  // Levenberg-Marquardt then rejects).
  int failed_evaluations() const { return failures_.load(); }
  // Evaluations that integrated a Jacobian (not those skip_next_jacobian
  // spared).
  int jacobian_evaluations() const { return jacobians_.load(); }
  int num_samples() const { return data_.size(); }
  int num_free() const { return static_cast<int>(free_.size()); }

  // Lanes of one pass (the widest Jet instantiated); more free
  // coordinates take several passes.
  static constexpr int kMaxLanes = 12;

  // How Jacobians are computed: Jet lanes through the whole integration,
  // or forward sensitivities (MotionModel::EvaluateWithSensitivities);
  // kAuto takes the sensitivities from kMinSensitivityColumns columns on.
  enum class JacobianMethod { kAuto, kJetLanes, kSensitivities };
  static constexpr int kMinSensitivityColumns = 9;
  void set_jacobian_method(JacobianMethod method) { method_ = method; }

  // Jacobians from the motion integrated with the largest step `step` (s)
  // instead of the model's: a Levenberg-Marquardt run's (stage_solver.cc),
  // whose answer is the minimum of the residuals, which stay the model's
  // exactly (computed alongside by a forward pass). Where the coarser
  // motion blows up, the Jacobian is the model's. The model's own step or
  // less: the model's Jacobians; so too with innovation weights (the
  // filter's predictor).
  void set_jacobian_step(double step);

  // The Jacobian Levenberg-Marquardt never uses (stage_solver.cc). Ceres
  // evaluates the Jacobian at each accepted point before its iteration
  // callback may stop the run there, and at the point where the run stops
  // that Jacobian goes unused: a third of a refit's Jacobians, which stop
  // after two or three steps. With remember_residuals on, each
  // residual-only evaluation keeps its point and residuals (the trial
  // point's); after skip_next_jacobian(), the next evaluation with
  // Jacobians at that same point returns those residuals and zero
  // Jacobians without integrating (elsewhere it evaluates in full). With
  // a coarser Jacobian step (set_jacobian_step), any evaluation with
  // Jacobians at the remembered point takes its residuals from there
  // instead of integrating the model's motion again. Ceres evaluates a
  // block on one thread at a time, which these rely on.
  void set_remember_residuals(bool on);
  // Half the sum of squares of the remembered residuals (Ceres' cost of
  // the block), or NaN when none are remembered.
  double remembered_cost() const;
  void skip_next_jacobian() const { remembered_.skip = true; }

 private:
  // Evaluates with Jets whose lanes carry the derivatives with respect to
  // free coordinates lanes[0..count).
  template <int N>
  bool EvaluateLanes(const MotionModel& model,
                     const double* u,
                     const int* lanes,
                     int count,
                     double* residuals,
                     double** jacobians) const;
  bool EvaluateOrFail(double const* const* parameters,
                      double* residuals,
                      double** jacobians) const;
  // Copies the remembered residuals into `residuals` if u is the
  // remembered point; false otherwise.
  bool RememberedResiduals(const std::vector<double>& u,
                           double* residuals) const;
  // Returns the remembered residuals and zero Jacobians if skip_next_jacobian
  // was asked and u is the remembered point; clears the request.
  bool SkippedJacobian(const std::vector<double>& u,
                       double* residuals,
                       double** jacobians) const;
  bool EvaluateSensitivities(const MotionModel& model,
                             const double* u,
                             const std::vector<int>& lanes,
                             double* residuals,
                             double** jacobians) const;
  bool EvaluatePass(const MotionModel& model,
                    const double* u,
                    const int* lanes,
                    int count,
                    double* residuals,
                    double** jacobians) const;
  void GatherFree(double const* const* parameters, double* u) const;
  // The full parameter vector for free coordinates u (value = scale u).
  std::vector<double> FullFromFree(const double* u) const;
  // The weighted residual of angle c (0 roll, 1 pitch, 2 yaw) at sample i
  // computed as `computed` deg; roll on the branch nearest the
  // measurement.
  double WeightedResidual(int i,
                          int c,
                          double computed,
                          double inv_sigma) const;
  // The computed angles (3 n) for a full parameter vector: the motion's,
  // or with innovation weights the filter's one-step predictions (on the
  // measurement's roll branch). T: double or a Jet.
  template <typename T>
  bool Predict(const MotionModel& model,
               const T* full,
               T* angles,
               IntegrationFailure* failure) const;
  // The weighted residuals alone, from the model's motion.
  bool EvaluateResiduals(const double* u, double* residuals) const;
  // The residuals and the Jacobian, both from `model`'s motion.
  bool EvaluateJacobian(const MotionModel& model,
                        const double* u,
                        const std::vector<int>& lanes,
                        double* residuals,
                        double** jacobians) const;
  // Sample i's three residuals with innovation weights: L_i^-1 (computed
  // - measured).
  template <typename T>
  void WhitenedResiduals(int i, const T* computed, T* residuals) const;
  // Block and column of free coordinate j.
  void Locate(int j, int* block, int* column) const;

  std::shared_ptr<const MotionModel> model_;
  // The coarser motion of set_jacobian_step; null: model_.
  std::shared_ptr<const MotionModel> jacobian_model_;
  std::vector<double> base_;
  std::vector<int> free_;
  int num_shared_;
  std::vector<double> scale_;
  TimeHistory data_;
  ChannelValues sigma_;
  JacobianMethod method_ = JacobianMethod::kAuto;
  std::shared_ptr<const InnovationWeights> innovation_weights_;
  std::vector<ParameterTie> ties_;
  std::vector<double> measured_;  // 3 n, for the filter
  mutable std::atomic<int> failures_{0};
  mutable std::atomic<int> jacobians_{0};
  struct Remembered {
    bool on = false;
    bool skip = false;
    bool valid = false;  // a residual-only evaluation succeeded since
    std::vector<double> u;
    std::vector<double> residuals;
  };
  mutable Remembered remembered_;
};

}  // namespace fit3dof

#endif  // FIT3DOF_SEGMENT_COST_FUNCTION_H_
