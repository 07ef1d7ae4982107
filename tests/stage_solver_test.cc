// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Levenberg-Marquardt's first trust region (stage_solver.h): a refit from
// the solution of a nearby model takes the Gauss-Newton step along a
// straight ridge at once, and reaches the minimum the cautious start
// reaches; one that starts far from the noise all the same takes the
// growing windows (continuation.h).

#include "stage_solver.h"

#include <cmath>
#include <string>
#include <vector>

#include "fit3dof/fit.h"
#include "fit3dof/parameters.h"
#include "fit_problem.h"
#include "format.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

// The short condition of tools/diagnose_suite (testing::ShortRun) with a
// tunnel stiffness (Eqs. 39 and 43) a few times the noise: Cm_alpha, t1
// and t3 share two effects, a ridge.
constexpr char kTunnelTerms[] =
    "  Cm_alpha_delta2: -1.13\n"
    "  tunnel_Cm_theta: 0.0015\n"
    "  tunnel_Cn_psi: -0.0005\n";

// The nominal fit (Cm_alpha and Cm_q free, no tunnel terms) of the short
// run, and the case that refits it with the tunnel stiffness free, from
// that solution.
struct Refit {
  Case c;
  std::vector<TimeHistory> data;
};

Refit RidgeRefit(const std::string& dir, std::uint64_t seed) {
  Case c = testing::ShortRun(dir, kTunnelTerms, seed);
  const int t1 = FindParameter(c.model, "tunnel_Cm_theta");
  const int t3 = FindParameter(c.model, "tunnel_Cn_psi");
  c.parameters[t1].value = c.parameters[t3].value = 0.0;
  c.parameters[FindParameter(c.model, "Cm_alpha")] = {-0.2, true, false};
  c.parameters[FindParameter(c.model, "Cm_q")] = {-2.0, true, false};
  const FitResult nominal = Fit(c);
  // Near the noise, where diagnose refits from a solution
  // (RefitFromSolution).
  EXPECT_LT(nominal.probable_error, 3.0);
  Refit r;
  for (const SegmentFit& f : nominal.segments) r.data.push_back(f.data);
  r.c = CaseAtSolution(c, nominal);
  r.c.parameters[t1].free = r.c.parameters[t3].free = true;
  r.c.solver.continuation = false;
  r.c.solver.multi_start = false;
  return r;
}

// SolveStage on the whole of `p` from *values.
StageOutcome Solve(const FitProblem& p,
                   const StageSettings& settings,
                   std::vector<double>* values) {
  return SolveStage(p.segments, p.free, p.model, p.names, settings, values);
}

TEST(StageSolver, ARefitFromASolutionTakesTheRidgeAtOnce) {
  int cautious_iterations = 0;
  int trusted_iterations = 0;
  for (int seed = 1; seed <= 3; ++seed) {
    const Refit r = RidgeRefit(
        testing::ScratchDirectory("stage_ridge_" + std::to_string(seed)), seed);
    const FitResult cautious = FitSamples(r.c, r.data);
    Case trusted_case = r.c;
    trusted_case.solver.from_solution = true;
    const FitResult trusted = FitSamples(trusted_case, r.data);
    ASSERT_TRUE(cautious.converged) << cautious.termination;
    ASSERT_TRUE(trusted.converged) << trusted.termination;
    // The same minimum, or further down the ridge: never a worse one.
    EXPECT_LT(trusted.sum_of_residuals,
              cautious.sum_of_residuals * (1.0 + 1e-4))
        << "seed " << seed;
    std::cout << "seed " << seed << ": " << cautious.iterations << " -> "
              << trusted.iterations << " iterations\n";
    cautious_iterations += cautious.iterations;
    trusted_iterations += trusted.iterations;
  }
  // Where the nominal fit stops short of the ridge's bottom, the cautious
  // start crawls there (13-14 iterations against 5 on two seeds of three).
  EXPECT_LE(2 * trusted_iterations, cautious_iterations);
}

// Ceres integrates the Jacobian at each accepted point before the
// iteration callback may stop the run there (stage_solver.cc); the run's
// rule is applied before it, to the trial step's cost, and at the point
// where the run stops the Jacobian is not integrated: a run integrates the
// start's and each accepted point's but the last's, one per accepted step
// (seeds 1-3, from the cautious start: 3, 14 and 13 steps). So too when
// the iteration limit ends the run.
TEST(StageSolver, TheJacobianAtThePointARunStopsIsNeverIntegrated) {
  for (int seed = 1; seed <= 3; ++seed) {
    const Refit r =
        RidgeRefit(testing::ScratchDirectory("stage_last_jacobian_" +
                                             std::to_string(seed)),
                   seed);
    const FitProblem problem = PrepareProblem(r.c, r.data);
    StageSettings settings;
    settings.tolerance = r.c.solver.tolerance;
    std::vector<double> values = problem.values;
    const StageOutcome run = Solve(problem, settings, &values);
    ASSERT_TRUE(run.converged) << run.termination;
    EXPECT_EQ(run.termination.rfind("probable error changed", 0), 0u)
        << run.termination;
    EXPECT_GE(run.accepted_steps, 1);
    EXPECT_EQ(run.jacobians, run.accepted_steps) << "seed " << seed;
    std::cout << "seed " << seed << ": " << run.accepted_steps
              << " accepted steps, " << run.jacobians << " Jacobians\n";

    settings.max_iterations = 1;
    values = problem.values;
    const StageOutcome one = Solve(problem, settings, &values);
    EXPECT_FALSE(one.converged) << one.termination;
    EXPECT_EQ(one.accepted_steps, 1);
    EXPECT_EQ(one.jacobians, 1);
  }
}

// A refit from a solution takes Levenberg-Marquardt's Jacobians from the
// motion at kJacobianStepFactor times the step (StageSettings::
// coarser_jacobians): its answer is the residuals' minimum, where the run
// with the model's own Jacobians ends, in as many iterations. Not where
// the coarser motion's Jacobian disagrees with the model's at the start:
// with the step a quarter of the sample interval, the coarser motion takes
// one RK4 step per sample (about 0.6 rad of the pitching motion), and the
// run keeps the model's Jacobians.
TEST(StageSolver, CoarserJacobiansWhereTheyAgreeReachTheSameMinimum) {
  for (int seed = 1; seed <= 3; ++seed) {
    const Refit r = RidgeRefit(
        testing::ScratchDirectory("stage_coarse_" + std::to_string(seed)),
        seed);
    Case at = r.c;
    at.solver.from_solution = true;
    const FitProblem problem = PrepareProblem(at, r.data);
    StageSettings settings;
    settings.tolerance = at.solver.tolerance;
    settings.initial_radius = kFromSolutionRadius;
    std::vector<double> exact = problem.values, coarse = problem.values;
    const StageOutcome model_jacobians = Solve(problem, settings, &exact);
    settings.coarser_jacobians = true;
    const StageOutcome coarser = Solve(problem, settings, &coarse);
    std::cout << "seed " << seed << ": " << model_jacobians.iterations << " -> "
              << coarser.iterations << " iterations, sum of squares "
              << model_jacobians.ressum << " -> " << coarser.ressum << "\n";
    EXPECT_FALSE(model_jacobians.coarser_jacobians);
    EXPECT_TRUE(coarser.coarser_jacobians);
    ASSERT_TRUE(coarser.converged) << coarser.termination;
    EXPECT_NEAR(
        coarser.ressum, model_jacobians.ressum, 1e-4 * model_jacobians.ressum);
    EXPECT_LE(coarser.iterations, model_jacobians.iterations + 1);

    const double interval = r.data[0].t[1] - r.data[0].t[0];
    at.solver.step = interval / 4.0;
    const FitProblem sparse = PrepareProblem(at, r.data);
    std::vector<double> values = sparse.values;
    const StageOutcome kept = Solve(sparse, settings, &values);
    EXPECT_FALSE(kept.coarser_jacobians) << "seed " << seed;
  }
}

// A refit from a nearby model's solution whose start is far from the
// noise after all (SolverOptions::far_start; diagnose's fits of a model
// with an effect taken out): Cm_alpha a fifth off its solution on an 8-s
// run of the short condition, the motion out of phase within a few
// cycles. Checked first, it takes the growing windows, and reaches the
// minimum the refit from the solution itself reaches.
TEST(StageSolver, ARefitThatStartsFarFromTheNoiseTakesTheWindows) {
  const std::string dir = testing::ScratchDirectory("stage_far_start");
  Case c = testing::ShortRun(dir, "", 1);
  std::vector<double> times;
  for (int i = 0; i <= 400; ++i) times.push_back(0.02 * i);
  c.segments[0].data_file =
      testing::WriteNoisyRecord(c, times, 1, dir + "/long.csv");
  c.parameters[FindParameter(c.model, "Cm_alpha")] = {-0.2, true, false};
  c.parameters[FindParameter(c.model, "Cm_q")] = {-2.0, true, false};
  const FitResult nominal = Fit(c);
  ASSERT_LT(nominal.probable_error, 3.0);
  std::vector<TimeHistory> data;
  for (const SegmentFit& f : nominal.segments) data.push_back(f.data);
  Case at = CaseAtSolution(c, nominal);
  at.solver.continuation = false;
  at.solver.multi_start = false;
  at.solver.from_solution = true;
  Case far = at;
  far.parameters[FindParameter(far.model, "Cm_alpha")].value *= 1.2;
  Case unchecked = far;
  far.solver.far_start = 30.0;
  const FitResult windows = FitSamples(far, data);
  const FitResult straight = FitSamples(unchecked, data);
  std::cout << "far start: " << windows.stages.size() << " stages, "
            << windows.iterations << " iterations, sum of squares "
            << windows.sum_of_residuals << "; unchecked "
            << straight.stages.size() << " stage, " << straight.iterations
            << " iterations, " << straight.sum_of_residuals << "; nominal "
            << nominal.sum_of_residuals << "\n";
  EXPECT_GT(windows.stages.size(), 1u);
  EXPECT_EQ(straight.stages.size(), 1u);
  EXPECT_NEAR(windows.sum_of_residuals,
              nominal.sum_of_residuals,
              1e-3 * nominal.sum_of_residuals);
}

// A fit asked only whether it reaches the noise (SolverOptions::stop_below;
// diagnose's union of a joint set's members) stops there: the short run's
// nominal fit from its guesses, stopped below 1.1 times the noise, ends
// there in fewer iterations than the whole descent takes, and no lower
// than its minimum.
TEST(StageSolver, AFitStopsOnceBelowTheProbableErrorAsked) {
  const std::string dir = testing::ScratchDirectory("stage_stop_below");
  Case c = testing::ShortRun(dir, "", 2);
  c.parameters[FindParameter(c.model, "Cm_alpha")] = {-0.2, true, false};
  c.parameters[FindParameter(c.model, "Cm_q")] = {-2.0, true, false};
  c.solver.multi_start = false;
  const FitResult whole = Fit(c);
  Case stopped = c;
  stopped.solver.stop_below = 1.1;
  const FitResult below = Fit(stopped);
  ASSERT_TRUE(whole.converged) << whole.termination;
  std::cout << "stopped below 1.1: " << below.iterations
            << " iterations, probable error " << below.probable_error << " ("
            << below.termination << "); the whole descent " << whole.iterations
            << ", " << whole.probable_error << "\n";
  EXPECT_EQ(below.termination.rfind(kBelowTermination, 0), 0u)
      << below.termination;
  EXPECT_LT(below.probable_error, 1.1);
  EXPECT_GE(below.probable_error, whole.probable_error);
  EXPECT_LT(below.iterations, whole.iterations);
}

// A bearing moment (bearing_moment.h) at 1.5 times the noise's size on the
// short run: from Cm_bearing = 0 and its angle at 1 deg, as diagnose adds
// it, the fit crawls along the ridge where Cm_bearing x bearing_angle
// holds (seed 1: 32 iterations). With diagnose's BIC rule
// (SolverOptions::bic_tolerance) it stops within a fraction of a BIC unit
// of the minimum (0.04) in fewer iterations (8); where the report's rule
// ends the fit at once (seeds 2, 3), the same fit.
TEST(StageSolver, TheBicRuleEndsACrawlAlongTheBearingRidge) {
  const std::string terms =
      "  Cm_alpha_delta2: -1.13\n"
      "  Cm_bearing: -0.006\n"
      "  bearing_angle: 1.0\n";
  int full_iterations = 0;
  int bic_iterations = 0;
  for (int seed = 1; seed <= 3; ++seed) {
    const std::string dir =
        testing::ScratchDirectory("stage_bearing_" + std::to_string(seed));
    Case c = testing::ShortRun(dir, terms, seed);
    c.parameters[FindParameter(c.model, "Cm_bearing")] = {0.0, true, false};
    c.parameters[FindParameter(c.model, "bearing_angle")] = {1.0, true, false};
    c.parameters[FindParameter(c.model, "Cm_alpha")] = {-0.2, true, false};
    c.parameters[FindParameter(c.model, "Cm_q")] = {-2.0, true, false};
    c.solver.continuation = false;
    c.solver.multi_start = false;
    c.solver.max_probable_error = 0.0;
    c.solver.profile_ridges = false;
    const FitResult full = Fit(c);
    c.solver.bic_tolerance = 0.01;
    const FitResult bic = Fit(c);
    if (bic.iterations < full.iterations) {
      EXPECT_NE(bic.termination.find("BIC fell by less than 0.01"),
                std::string::npos)
          << bic.termination;
    }
    const double n = 3.0 * full.points;
    const double above =
        n * std::log(bic.sum_of_residuals * bic.sum_of_residuals /
                     (full.sum_of_residuals * full.sum_of_residuals));
    EXPECT_LT(above, 1.0) << "seed " << seed;
    std::cout << "seed " << seed << ": " << full.iterations << " -> "
              << bic.iterations << " iterations, BIC +" << above << "\n";
    full_iterations += full.iterations;
    bic_iterations += bic.iterations;
  }
  EXPECT_LT(bic_iterations, full_iterations);
}

// The short run with a nonlinear stiffness and a bearing moment (seed 1),
// to be fitted without the stiffness: the bearing moment freed from
// Cm_bearing = 0 at 1 deg, as diagnose adds it, crawls along its ridge in
// the stiffness's place.
Case BearingInPlaceOfStiffness(const std::string& dir) {
  Case c = testing::ShortRun(dir,
                             "  Cm_alpha_delta2: -1.13\n"
                             "  Cm_bearing: -0.006\n"
                             "  bearing_angle: 1.0\n",
                             1);
  c.parameters[FindParameter(c.model, "Cm_alpha_delta2")] = {0.0, false, false};
  c.parameters[FindParameter(c.model, "Cm_bearing")] = {0.0, true, false};
  c.parameters[FindParameter(c.model, "bearing_angle")] = {1.0, true, false};
  c.solver.continuation = false;
  c.solver.multi_start = false;
  return c;
}

// A fit asked whether it reaches a probable error it cannot reach
// (SolverOptions::stop_below with the record's nonlinear stiffness left
// out, the bearing moment crawling along its ridge in its place) stops once
// the limit is out of reach (kOutOfReachMargin): in fewer iterations, with
// the same answer (above the limit) and a probable error no lower than the
// whole descent's (seed 1: 11 iterations at 8.52 against 54 at 5.40; the
// value is not the minimum).
TEST(StageSolver, AFitStopsOnceTheProbableErrorAskedIsOutOfReach) {
  Case c = BearingInPlaceOfStiffness(
      testing::ScratchDirectory("stage_out_of_reach"));
  c.solver.max_probable_error = 0.0;
  c.solver.profile_ridges = false;
  const FitResult whole = Fit(c);
  const double limit = 1.1;
  Case stopped = c;
  stopped.solver.stop_below = limit;
  const FitResult short_of = Fit(stopped);
  std::cout << "out of reach of " << limit << ": " << short_of.iterations
            << " iterations, probable error " << short_of.probable_error << " ("
            << short_of.termination << "); the whole descent "
            << whole.iterations << ", " << whole.probable_error << " ("
            << whole.termination << ")\n";
  EXPECT_EQ(short_of.termination.rfind(kOutOfReachTermination, 0), 0u)
      << short_of.termination;
  EXPECT_LT(short_of.iterations, whole.iterations);
  EXPECT_GT(whole.probable_error, limit);
  EXPECT_GE(short_of.probable_error, whole.probable_error);
}

// Without the record's nonlinear stiffness, a bearing moment freed from
// Cm_bearing = 0 at 1 deg runs toward an infinite angle, where it is a
// stiffness and a cubic term (stage_solver.h, kBearingAngleStop). With a
// limit on its angle the run stops at the first accepted point past it,
// in fewer iterations, and the angle there lies past the limit (outside
// the record, as the whole run's end does); within the limit nothing
// changes.
TEST(StageSolver, ARunStopsOnceItsBearingAngleLeavesTheRecord) {
  const Case c = BearingInPlaceOfStiffness(
      testing::ScratchDirectory("stage_bearing_limit"));
  std::vector<TimeHistory> data;
  for (const SegmentFit& f : Fit(c).segments) data.push_back(f.data);
  const FitProblem problem = PrepareProblem(c, data);
  const int angle = FreeShared(c, problem.free, "bearing_angle");
  ASSERT_GE(angle, 0);
  StageSettings settings;
  settings.tolerance = c.solver.tolerance;
  std::vector<double> whole = problem.values;
  const StageOutcome free_run = Solve(problem, settings, &whole);
  const double largest = LargestAngle(problem);
  std::cout << "without a limit: " << free_run.iterations
            << " iterations, bearing angle " << whole[angle]
            << " deg (the record's largest " << largest << ")\n";
  ASSERT_GT(std::abs(whole[angle]), kBearingAngleStop * largest);

  settings.limited = angle;
  settings.limit = kBearingAngleStop * largest;
  std::vector<double> stopped = problem.values;
  const StageOutcome limited = Solve(problem, settings, &stopped);
  std::cout << "limit " << settings.limit << ": " << limited.iterations
            << " iterations, bearing angle " << stopped[angle] << " ("
            << limited.termination << ")\n";
  EXPECT_EQ(limited.termination,
            kLimitTermination + std::string("|bearing_angle| > ") +
                FormatNumber("%g", settings.limit));
  EXPECT_GT(std::abs(stopped[angle]), settings.limit);
  EXPECT_LT(limited.iterations, free_run.iterations);

  // A limit the run never reaches leaves it as it was.
  settings.limit = 2.0 * std::abs(whole[angle]);
  std::vector<double> within = problem.values;
  const StageOutcome unlimited = Solve(problem, settings, &within);
  EXPECT_EQ(unlimited.iterations, free_run.iterations);
  EXPECT_EQ(within, whole);
}

// The short run with a pitch reading whose gain is off the yaw reading's
// (theta_gain, outside diagnose's catalog), fitted with a bearing moment
// freed from Cm_bearing = 0 at 1 deg, as diagnose adds it: the fit shrinks
// the angle toward zero, Cm_bearing growing as its inverse, past
// |Cm_alpha| (effect_validation.cc's bound). With Cm_bearing bounded by
// Cm_alpha (StageSettings::outgrowing) the run stops at the first accepted
// point past it, in fewer iterations, with Cm_bearing past |Cm_alpha|
// there (as the whole run's end has it).
TEST(StageSolver, ARunStopsOnceCmBearingOutgrowsCmAlpha) {
  Case c = testing::ShortRun(
      testing::ScratchDirectory("stage_outgrown"), "  theta_gain: -0.5\n", 1);
  c.parameters[FindParameter(c.model, "theta_gain")].value = 0.0;
  c.parameters[FindParameter(c.model, "Cm_alpha")] = {-0.2, true, false};
  c.parameters[FindParameter(c.model, "Cm_q")] = {-2.0, true, false};
  c.solver.continuation = false;
  c.solver.multi_start = false;
  std::vector<TimeHistory> data;
  for (const SegmentFit& f : Fit(c).segments) data.push_back(f.data);
  const FitResult nominal = FitSamples(c, data);
  Case bearing = CaseAtSolution(c, nominal);
  bearing.parameters[FindParameter(c.model, "Cm_bearing")] = {0.0, true, false};
  bearing.parameters[FindParameter(c.model, "bearing_angle")] = {
      1.0, true, false};
  const FitProblem problem = PrepareProblem(bearing, data);
  const int moment = FreeShared(bearing, problem.free, "Cm_bearing");
  const int stiffness = FreeShared(bearing, problem.free, "Cm_alpha");
  ASSERT_GE(moment, 0);
  ASSERT_GE(stiffness, 0);
  StageSettings settings;
  settings.tolerance = c.solver.tolerance;
  std::vector<double> whole = problem.values;
  const StageOutcome free_run = Solve(problem, settings, &whole);
  std::cout << "without a bound: " << free_run.iterations
            << " iterations, Cm_bearing " << whole[moment] << ", Cm_alpha "
            << whole[stiffness] << " (" << free_run.termination << ")\n";
  ASSERT_GT(std::abs(whole[moment]), std::abs(whole[stiffness]));

  settings.outgrowing = moment;
  settings.outgrown = stiffness;
  std::vector<double> stopped = problem.values;
  const StageOutcome bounded = Solve(problem, settings, &stopped);
  std::cout << "bounded: " << bounded.iterations << " iterations, Cm_bearing "
            << stopped[moment] << ", Cm_alpha " << stopped[stiffness] << " ("
            << bounded.termination << ")\n";
  EXPECT_EQ(bounded.termination,
            kLimitTermination + std::string("|Cm_bearing| > |Cm_alpha|"));
  EXPECT_GT(std::abs(stopped[moment]), std::abs(stopped[stiffness]));
  EXPECT_LT(bounded.iterations, free_run.iterations);
}

}  // namespace
}  // namespace fit3dof
