// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// One solve of a FitProblem's segments from given values: Ceres'
// Levenberg-Marquardt stopped by the report's rule (the probable error,
// Eq. 26, changes by less than BOUND between two iterations), or the 1978
// program's undamped Gauss-Newton iteration. Both first scale the free
// coordinates to unit Jacobian columns.

#ifndef FIT3DOF_SRC_STAGE_SOLVER_H_
#define FIT3DOF_SRC_STAGE_SOLVER_H_

#include <memory>
#include <string>
#include <vector>

#include "fit_problem.h"

namespace fit3dof {

// The start of the termination of a run the BIC rule ended
// (StageSettings::bic_tolerance).
inline constexpr char kBicRuleTermination[] = "BIC fell by less than ";
// That of a run ended below StageSettings::stop_below.
inline constexpr char kBelowTermination[] = "probable error below ";

struct StageOutcome {
  bool integrable = true;  // false: the motion blew up at the start values
  bool converged = false;
  int iterations = 0;
  int failed_evaluations = 0;  // rejected trial steps that blew up
  double ressum = 0.0;         // weighted residual sum of squares at the end
  std::string termination;
  std::string failure;  // why the start values could not be integrated
};

// The first trust regions (StageSettings::initial_radius). From a guess,
// Ceres' default: a damping of 1e-4 leaves the directions the data see
// (unit diagonal) undamped and holds back only those they hardly see,
// where a Gauss-Newton step from afar wanders (a bearing moment's angle
// had gone to 10 deg and crawled back over 200 iterations). From the
// solution of a nearby model those directions are the straight ridges of
// parameters sharing one effect (Eq. 43: Cm_alpha, t1 and t3), along which
// each accepted step could only triple the radius: refits crawled 11-16
// iterations in steps growing 3-fold, a third of a diagnosis' time. There
// the Gauss-Newton step is taken at once, and a step that fails still
// shrinks the radius.
inline constexpr double kStartRadius = 1e4;
inline constexpr double kFromSolutionRadius = 1e8;

// What a stage solve needs besides the segments and the values.
struct StageSettings {
  double tolerance = 0.0;           // absolute, on the probable error
  double relative_tolerance = 0.0;  // times the probable error
  // On the drop of n ln(RSS) in an iteration (SolverOptions).
  double bic_tolerance = 0.0;
  // On the probable error itself (SolverOptions::stop_below; 0: none).
  double stop_below = 0.0;
  int max_iterations = 50;
  // Levenberg-Marquardt's first trust region, in the scaling that gives
  // every free coordinate's Jacobian column unit norm (Ceres' radius is
  // the inverse of the damping added to that unit diagonal).
  double initial_radius = kStartRadius;
};

// One Levenberg-Marquardt run from `values` (global free order, updated in
// place). A coordinate the data cannot see at the start is held where it
// is; when the run's answer lets the data see it, the run is repeated from
// there (up to three runs). `names` label the iteration log (-v=1).
StageOutcome SolveStage(const std::vector<PreparedSegment>& segments,
                        const FreeLayout& free,
                        const std::shared_ptr<const MotionModel>& model,
                        const std::vector<std::string>& names,
                        const StageSettings& settings,
                        std::vector<double>* values);

// The 1978 program's iteration: the full Gauss-Newton step, no damping, no
// step rejection, stopped by the same probable-error rule (relative
// tolerance unused).
StageOutcome SolveGaussNewton(const std::vector<PreparedSegment>& segments,
                              const FreeLayout& free,
                              const std::shared_ptr<const MotionModel>& model,
                              const StageSettings& settings,
                              std::vector<double>* values);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_STAGE_SOLVER_H_
