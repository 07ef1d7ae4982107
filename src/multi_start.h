// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Restarts for a fit that ended far above the noise level (a local minimum
// is likely): from what the data say (linear-theory estimates of every free
// coefficient, nonlinear terms at zero, initial conditions from the data)
// and from a spread of points around that, each a whole continuation
// pipeline (continuation.h), in parallel within the process's thread budget
// (thread_budget.h). The best is kept.

#ifndef FIT3DOF_SRC_MULTI_START_H_
#define FIT3DOF_SRC_MULTI_START_H_

#include <vector>

#include "continuation.h"
#include "fit3dof/case.h"
#include "fit_problem.h"

namespace fit3dof {

struct MultiStartOutcome {
  int tried = 0;          // starts including the first attempt
  int reached = 0;        // of them, within 1% of the best probable error
  int iterations = 0;     // of every restart
  bool improved = false;  // a restart beat the first attempt
  PipelineOutcome best;   // when improved
  std::vector<double> values;
};

// Restarts (c.solver.starts of them) after `first`, the attempt from the
// configured starting values.
MultiStartOutcome RunMultiStart(const Case& c,
                                const FitProblem& problem,
                                const PipelineOutcome& first);

// Restarts of a fit whose bearing moment (Cm_bearing and bearing_angle
// free) ended with its angle beyond every angle of the record (`solution`,
// the first attempt's values): there the moment never fades
// (bearing_moment.h), a linear stiffness that Cm_alpha takes, and the fit
// stops on that ridge, its information matrix singular. A Table 6 record
// with a bearing moment at 1 deg, started from Cm_alpha -0.2 and Cm_q -2,
// ended at bearing_angle 3538 deg, probable error 2.0. From that solution
// with the angle at 0.06, 0.15 and 0.4 of the record's largest angle,
// Cm_bearing back at its configured start and Cm_alpha taking the rest of
// the unfaded stiffness (Cm_alpha + Cm_bearing kept); tried 0 when the
// angle stayed within the record's.
MultiStartOutcome RunBearingRestarts(const Case& c,
                                     const FitProblem& problem,
                                     const std::vector<double>& solution,
                                     const PipelineOutcome& first);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_MULTI_START_H_
