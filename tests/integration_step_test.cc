// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/integration_step.h"

#include <cmath>
#include <string>
#include <vector>

#include "fit3dof/config.h"
#include "fit3dof/parameters.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

// The short condition (3 s at 10 points per pitch cycle, 8 deg at
// 30 deg/s of spin, solver.step 2 ms) with a bearing moment saturating at
// 1 deg, fitted for Cm_alpha, Cm_q and the moment's size.
Case BearingRun(const std::string& name) {
  Case c = testing::ShortRun(testing::ScratchDirectory(name),
                             "  Cm_alpha_delta2: -1.13\n"
                             "  Cm_bearing: -0.02\n"
                             "  bearing_angle: 1.0\n",
                             7);
  for (const char* free : {"Cm_alpha", "Cm_q", "Cm_bearing"}) {
    c.parameters[FindParameter(c.model, free)].free = true;
  }
  return c;
}

// Every value of `fit` within a tenth of its standard error of `exact`'s,
// the fit of the same model at the config's step.
void ExpectWithinATenthOfTheirErrors(const FitResult& fit,
                                     const FitResult& exact) {
  ASSERT_EQ(fit.parameters.size(), exact.parameters.size());
  for (size_t i = 0; i < exact.parameters.size(); ++i) {
    const ParameterEstimate& e = exact.parameters[i];
    if (!(e.standard_error > 0.0)) continue;
    EXPECT_LE(std::abs(fit.parameters[i].value - e.value),
              0.1 * e.standard_error)
        << e.name;
  }
}

TEST(StepChiSquare, NoneAtTheConfigsStepAndGrowingAsTheStepToTheEighth) {
  const Case c = BearingRun("step_chi_square");
  const FitResult fit = Fit(c);
  const std::vector<TimeHistory> data = testing::FittedSamples(fit);
  EXPECT_EQ(StepChiSquare(c, data, fit, c.solver.step), 0.0);
  // RK4's error grows as the step to the 4th, its square to the 8th:
  // doubling the step multiplies the distance by about 256.
  const double at4 = StepChiSquare(c, data, fit, 4 * c.solver.step);
  const double at8 = StepChiSquare(c, data, fit, 8 * c.solver.step);
  EXPECT_GT(at4, 0.0);
  EXPECT_GT(at8 / at4, 64.0);
  EXPECT_LT(at8 / at4, 1024.0);
}

TEST(CoarsestStep, TheLastDoublingWithinTheLimit) {
  const Case c = BearingRun("coarsest_step");
  const FitResult fit = Fit(c);
  const std::vector<TimeHistory> data = testing::FittedSamples(fit);
  const double limit = kStepChiSquare / 16;
  const double step = CoarsestStep(c, data, fit, limit);
  EXPECT_GT(step, c.solver.step);
  EXPECT_LE(StepChiSquare(c, data, fit, step), limit);
  EXPECT_GT(StepChiSquare(c, data, fit, 2 * step), limit);
  // A limit nothing meets: the config's step.
  EXPECT_EQ(CoarsestStep(c, data, fit, 0.0), c.solver.step);
}

TEST(CoarsestStep, NoCoarserThanTheSamples) {
  Case c = BearingRun("coarsest_step_samples");
  const FitResult fit = Fit(c);
  // The samples 0.064 s apart: from 0.02 s one doubling at most.
  c.solver.step = 0.02;
  EXPECT_EQ(CoarsestStep(c, testing::FittedSamples(fit), fit, 1e300), 0.04);
}

// The promise of the search step: every value within a tenth of its
// standard error of the fit at the config's step.
TEST(FitSamples, AtASearchStepEveryValueWithinATenthOfItsError) {
  Case c = BearingRun("search_step_values");
  const FitResult exact = Fit(c);
  c.solver.search_step =
      CoarsestStep(c, testing::FittedSamples(exact), exact, kStepChiSquare);
  ASSERT_GT(c.solver.search_step, c.solver.step);
  const FitResult coarse = FitSamples(c, testing::FittedSamples(exact));
  ASSERT_EQ(coarse.step, c.solver.search_step);
  EXPECT_GT(coarse.step_chi_square, 0.0);
  EXPECT_LE(coarse.step_chi_square, kStepChiSquare);
  ExpectWithinATenthOfTheirErrors(coarse, exact);
}

// A search step too coarse for the fit's motion: fitted again at the
// finer step where the distance, shrinking as the step's 8th power, comes
// within the limit, and kept there.
TEST(FitSamples, ASearchStepTooCoarseFitsAgainAtAFinerOne) {
  Case c = BearingRun("search_step_too_coarse");
  const FitResult exact = Fit(c);
  const std::vector<TimeHistory> data = testing::FittedSamples(exact);
  c.solver.search_step = 32 * c.solver.step;  // about one step per sample
  ASSERT_GT(StepChiSquare(c, data, exact, c.solver.search_step),
            kStepChiSquare);
  const FitResult fit = FitSamples(c, data);
  EXPECT_LT(fit.step, c.solver.search_step);
  EXPECT_GT(fit.step, c.solver.step);
  EXPECT_LE(fit.step_chi_square, kStepChiSquare);
  ExpectWithinATenthOfTheirErrors(fit, exact);
}

// Where no coarser step serves, the fit at the config's step, exactly as
// without a search step.
TEST(FitSamples, NoStepServingTheFitAtTheConfigsStep) {
  Case c = BearingRun("search_step_none_serves");
  c.solver.step = 0.016;  // 4 substeps per sample
  const FitResult exact = Fit(c);
  const std::vector<TimeHistory> data = testing::FittedSamples(exact);
  c.solver.search_step = 2 * c.solver.step;
  ASSERT_GT(StepChiSquare(c, data, exact, c.solver.search_step),
            kStepChiSquare);
  const FitResult fit = FitSamples(c, data);
  EXPECT_EQ(fit.step, c.solver.step);
  ASSERT_EQ(fit.parameters.size(), exact.parameters.size());
  for (size_t i = 0; i < fit.parameters.size(); ++i) {
    EXPECT_EQ(fit.parameters[i].value, exact.parameters[i].value);
    if (fit.parameters[i].free) {
      EXPECT_EQ(fit.parameters[i].standard_error,
                exact.parameters[i].standard_error);
    }
  }
}

}  // namespace
}  // namespace fit3dof
