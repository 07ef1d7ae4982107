// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A FitProblem (fit_problem.h) as a Ceres problem: one residual block per
// segment (segment_cost_function.h) over the shared block and the segment's
// own block, in scaled coordinates u = value / scale so that every Jacobian
// column can be brought to unit length. Also the normal equations of the
// weighted residuals, read off the Jacobian the problem evaluates.

#ifndef FIT3DOF_SRC_ASSEMBLY_H_
#define FIT3DOF_SRC_ASSEMBLY_H_

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "ceres/ceres.h"
#include "fit3dof/segment_cost_function.h"
#include "fit_problem.h"

namespace fit3dof {

struct Assembly {
  std::unique_ptr<ceres::Problem> problem;
  std::vector<SegmentCostFunction*> costs;  // owned by the problem
  // Every free coordinate in the global order (shared, then each
  // segment's own) in one buffer, the blocks pointing into it: their
  // addresses then follow the global order. ceres::Covariance orders its
  // columns by block address; with a buffer per block that order, and the
  // last digits of every error bar, depended on where the heap put them.
  std::vector<double> u;
  std::vector<double*> blocks;  // in global order, non-empty ones only
  std::vector<std::vector<double*>> segment_blocks;  // each residual's
};

// The problem for physical values `values` (global free order) of
// `segments` laid out as `free`, in coordinates u = value / scale; its
// evaluation callback, if any, `evaluation_callback` (not owned).
Assembly Assemble(const std::vector<PreparedSegment>& segments,
                  const FreeLayout& free,
                  const std::shared_ptr<const MotionModel>& model,
                  const std::vector<double>& values,
                  const std::vector<double>& scale,
                  ceres::EvaluationCallback* evaluation_callback = nullptr);

// Physical values of the free coordinates (global order) from the blocks.
std::vector<double> FreeValues(const Assembly& a,
                               const FreeLayout& free,
                               const std::vector<double>& scale);

// The full parameter vector segment `s` sees in the assembly.
std::vector<double> SegmentFullValues(const Assembly& a, size_t s);

// Threads beyond the caller's that Ceres may evaluate `a`'s residual
// blocks on (Solver::Options::num_threads and Problem::EvaluateOptions'
// less one): one for exactly two segments, none otherwise. Ceres sums the
// blocks' costs thread by thread and then the threads' sums; two blocks'
// costs summed in either order are the same number, three or more need
// not be, and a fit must repeat to the bit (the fit memo and diagnose's
// comparisons rely on it). Hold them from the budget (ThreadLease).
int HelperThreadsFor(const Assembly& a);

// The Jacobian of the weighted residuals (rows: each segment's samples in
// order, phi, theta, psi per sample; columns in global free order, in the
// assembly's scaled coordinates) and the residuals; false if the motion
// cannot be integrated. The assembly must not hold any coordinate.
bool EvaluateJacobian(const Assembly& a,
                      ceres::CRSMatrix* jacobian,
                      std::vector<double>* residuals);

// J^T J, the residual sum of squares and, if asked, J^T r of a Jacobian.
void NormalEquations(const ceres::CRSMatrix& jacobian,
                     const std::vector<double>& residuals,
                     Eigen::MatrixXd* jtj,
                     double* ressum,
                     Eigen::VectorXd* jtr = nullptr);

// J^T J of the weighted residuals (columns in global free order, in the
// assembly's scaled coordinates), the residual sum of squares and, if asked,
// J^T r; false if the motion cannot be integrated. The assembly must not
// hold any coordinate (HoldCoordinates): its Jacobian would lack columns.
bool Information(const Assembly& a,
                 Eigen::MatrixXd* jtj,
                 double* ressum,
                 Eigen::VectorXd* jtr = nullptr);

// The weighted residual sum of squares at the assembly's values; false if
// the motion cannot be integrated. No Jacobian: the cost of one
// integration.
bool SumOfSquares(const Assembly& a, double* ressum);

// Scales that make every Jacobian column of unit length, from J^T J in the
// coordinates of `old_scale` (columns that are exactly zero keep theirs).
std::vector<double> ColumnScales(const Eigen::MatrixXd& jtj,
                                 const std::vector<double>& old_scale);

// Free coordinates whose Jacobian column is zero for all practical purposes
// (1e10 times weaker than the strongest, in physical units): parameters the
// data cannot see at the current values, like a Magnus term without spin.
std::vector<bool> NullColumns(const Eigen::MatrixXd& jtj);

// Holds the given free coordinates constant: a whole block constant, part
// of one through a ceres::SubsetManifold.
void HoldCoordinates(const std::vector<bool>& hold, Assembly* a);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_ASSEMBLY_H_
