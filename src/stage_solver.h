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
// That of a run ended by its tolerance on the probable error.
inline constexpr char kToleranceTermination[] =
    "probable error changed by less than ";
// That of a run ended out of its reach (StageSettings::out_of_reach).
inline constexpr char kOutOfReachTermination[] = "out of reach of ";
// That of a run ended with a coordinate past its limit
// (StageSettings::limited), followed by "|name| > limit".
inline constexpr char kLimitTermination[] = "beyond its limit: ";

// A refit from a nearby model's solution stops once its bearing angle
// passes this many times the record's largest angle
// (StageSettings::limited, continuation.cc): the fade then lies outside the
// record, where the bearing moment is a stiffness and a cubic term, and
// the fit follows Cm_bearing growing as the angle's square, Cm_alpha taking
// its linear part, toward a minimum at an infinite angle (the nonlinear
// stiffness the catalog holds), 0.3 deg a step. Its values are refused
// there as outside the record's angles (effect_validation.cc) wherever it
// stops: the stop is where that bound begins. On draw 65's pair of runs
// with a pitch reading's gain error (outside the catalog), sets of a
// bearing moment and one more effect crawled so to their 50-iteration
// limit 27 times: with the stop at twice the largest angle 2306 -> 1548
// iterations, 13.8 -> 9.6 s (draws 65 and 66, 330 diagnoses, answered the
// same); at the largest angle 1479 and 7.6 s (draw 67's 165 the same).
inline constexpr double kBearingAngleStop = 1.0;

// A run asked only whether it reaches a probable error (stop_below) is
// stopped short of it once its probable error stands above it by more than
// this many times what its remaining iterations could take off at the pace
// of its last kOutOfReachPace successful ones (their largest fall). Along
// a ridge it crawls: a union of a nonlinear damping, a Magnus moment, a
// bearing moment and a calibration nonlinearity on a 3-s Table 6 record
// stood at 3.25 after five iterations, against a limit of 1.1, and took 45
// more, falling by 1e-4 to 5e-3 each, to end at 3.20 (0.33 s of a 4.7-s
// diagnosis). The answer (above or below) stays unless the pace grows
// more than tenfold; the value it stops at is not the minimum: the rest of
// a descent can speed up as Levenberg-Marquardt's trust region widens (in
// stage_solver_test, 8.52 where the whole descent went on to 5.40).
inline constexpr double kOutOfReachMargin = 10.0;
inline constexpr int kOutOfReachPace = 3;

struct StageOutcome {
  bool integrable = true;  // false: the motion blew up at the start values
  bool converged = false;
  int iterations = 0;
  int failed_evaluations = 0;  // rejected trial steps that blew up
  // Levenberg-Marquardt's accepted steps, and the Jacobians it integrated
  // (the start's and each accepted point's but the last's: stage_solver.cc).
  int accepted_steps = 0;
  int jacobians = 0;
  double ressum = 0.0;  // weighted residual sum of squares at the end
  // Whether Levenberg-Marquardt's Jacobians came from the coarser motion
  // (StageSettings::coarser_jacobians; in the last run of SolveStage).
  bool coarser_jacobians = false;
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

// A refit from a nearby model's solution (StageSettings::coarser_jacobians)
// takes Levenberg-Marquardt's Jacobians from the motion integrated with
// this many times the model's step (SegmentCostFunction::set_jacobian_step):
// its residuals, and so its answer, the minimum of their sum of squares,
// stay the model's. RK4's error grows as the step's fourth power: the
// Jacobian's is at most 4^4 = 256 times the motion's own truncation error,
// which the step is chosen to keep far below the noise (a relative 1e-5
// becomes 3e-3 in a Jacobian, which costs Levenberg-Marquardt's steps
// nothing they need). The start's Jacobian (the coordinates' scales, the
// columns the data cannot see) and every Jacobian after the run (error
// bars, score tests) are the model's. Draw 50 of tools/diagnose_suite
// (165 diagnoses): every verdict and added effect the same, the final
// values within 0.006 of their errors and the errors within 0.7%; alone,
// three 3-s runs at the default step (0.001 s) 0.80x the time, at the
// suite's 0.002 s 0.8-0.86x, Table 6 records (0.01 s, 6 steps a sample)
// 0.9-1.0x. Not for fits from guesses: the continuation stages of a Table 6
// record with an unmodelled roll damping crawl without converging, and
// where such a crawl stops depends on the last digits of its steps (with
// coarser Jacobians the nominal fit ended at a probable error of 12600
// instead of 946, and the diagnosis named a reading lag).
inline constexpr double kJacobianStepFactor = 4.0;
// ... when at the start each column the data see is within this of the
// model's own (relative to the column's norm); the model's Jacobians
// otherwise.
inline constexpr double kJacobianAgreement = 1e-2;

// What a stage solve needs besides the segments and the values.
struct StageSettings {
  double tolerance = 0.0;           // absolute, on the probable error
  double relative_tolerance = 0.0;  // times the probable error
  // On the drop of n ln(RSS) in an iteration (SolverOptions).
  double bic_tolerance = 0.0;
  // On the probable error itself (SolverOptions::stop_below; 0: none).
  double stop_below = 0.0;
  // Also stop once stop_below is out of reach (kOutOfReachMargin): for the
  // run whose iterations are bounded by max_iterations (the last stage).
  bool out_of_reach = false;
  int max_iterations = 50;
  // Levenberg-Marquardt's first trust region, in the scaling that gives
  // every free coordinate's Jacobian column unit norm (Ceres' radius is
  // the inverse of the damping added to that unit diagonal).
  double initial_radius = kStartRadius;
  // Levenberg-Marquardt's Jacobians from a coarser motion where they serve
  // (kJacobianStepFactor): for refits from a nearby model's solution.
  bool coarser_jacobians = false;
  // A free coordinate (global free order; -1: none) whose size, once past
  // `limit` (in its own units), stops the run: a refit from a nearby
  // model's solution limits its bearing angle (kBearingAngleStop).
  int limited = -1;
  double limit = 0.0;
  // A free coordinate (-1: none) whose size, once past that of `outgrown`,
  // stops the run: a refit from a nearby model's solution stops once
  // |Cm_bearing| passes |Cm_alpha|. That is the other end of the bearing
  // moment's ridge (kBearingAngleStop): a fit that wants a moment of
  // constant size shrinks the angle toward zero while Cm_bearing grows as
  // its inverse (Cm_bearing x bearing_angle, the saturated moment, held),
  // about 4% a step, and its values are refused past that point
  // (effect_validation.cc: |Cm_bearing| up to |Cm_alpha|) wherever it
  // stops. On draw 107's short run with a pitch reading's gain error
  // (outside the catalog), 35% of the 2237 iterations of the fits with a
  // bearing moment came after it.
  int outgrowing = -1;
  int outgrown = -1;
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
