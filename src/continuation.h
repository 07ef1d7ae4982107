// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// One attempt at a fit from given values: growing windows of the record
// (about two periods of the motion first, doubling until the whole record
// is in), each solved from the previous window's answer, then the whole
// record under the report's rule. A fit that starts far off in frequency is
// not convex over 40 cycles; over two it is. The report's plain
// Gauss-Newton (solver.method) fits the whole record at once.

#ifndef FIT3DOF_SRC_CONTINUATION_H_
#define FIT3DOF_SRC_CONTINUATION_H_

#include <string>
#include <vector>

#include "fit3dof/case.h"
#include "fit3dof/fit.h"
#include "fit_problem.h"

namespace fit3dof {

struct PipelineOutcome {
  bool integrable = true;
  std::string failure;  // why the motion cannot be integrated
  bool converged = false;
  std::string termination;
  int iterations = 0;
  int failed_evaluations = 0;
  double probable_error = 0.0;  // over the whole record, Eq. 26
  std::vector<FitResult::Stage> stages;
};

// The windows (seconds after each segment's first sample) of the
// continuation, the whole record (infinity) last; only windows with enough
// residuals for `num_free` parameters.
std::vector<double> ContinuationWindows(
    const std::vector<PreparedSegment>& segments, int num_free);

// One attempt from `values` (global free order, updated in place) by the
// case's solver settings.
PipelineOutcome RunPipeline(const Case& c,
                            const FitProblem& problem,
                            std::vector<double>* values);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_CONTINUATION_H_
