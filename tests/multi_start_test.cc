// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Restarts of the robust pipeline (src/multi_start.h) as `fit` runs them.

#include <cmath>
#include <string>

#include "fit3dof/config.h"
#include "fit3dof/fit.h"
#include "fit3dof/parameters.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

// The Table 6 record with a bearing moment (Cm_bearing -0.000931 at 1 deg;
// the diagnose suite's, draw 4) fitted with the moment free from guesses
// well off (Cm_alpha -0.2, Cm_q -2): the pipeline's path reached the
// moment's unfaded side, the angle at 3538 deg and Cm_bearing merged into
// Cm_alpha, probable error 2.0 and warnings of a singular information
// matrix (below the multi-start's threshold of 3). Restarted with the
// angle within the record's, the fit finds the moment and the noise.
TEST(MultiStart, RestartsABearingMomentWhoseAngleLeftTheRecord) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "800 samples, four pipelines; the restarts run the "
                    "multi-start's code (fit_test's restarts): plain build";
  }
  Case c = LoadConfig(
      testing::SourcePath("tests/data/table6_bearing_moment_seed4.yaml"));
  c.parameters[FindParameter(c.model, "Cm_alpha")].value = -0.2;
  c.parameters[FindParameter(c.model, "Cm_q")].value = -2.0;
  const FitResult fit = Fit(c);
  EXPECT_TRUE(
      testing::InPipeline(fit, "bearing_angle beyond the record's angles"))
      << ::testing::PrintToString(fit.pipeline);
  EXPECT_LT(fit.probable_error, 1.1);
  const ParameterEstimate* moment = SharedEstimate(fit, "Cm_bearing");
  const ParameterEstimate* angle = SharedEstimate(fit, "bearing_angle");
  ASSERT_NE(moment, nullptr);
  ASSERT_NE(angle, nullptr);
  EXPECT_LT(std::abs(angle->value - 1.0), 3.0 * angle->standard_error)
      << angle->value << " +- " << angle->standard_error;
  EXPECT_LT(std::abs(moment->value + 0.000931), 3.0 * moment->standard_error)
      << moment->value << " +- " << moment->standard_error;
  const ParameterEstimate* stiffness = SharedEstimate(fit, "Cm_alpha");
  EXPECT_LT(std::abs(stiffness->value + 0.236), 3.0 * stiffness->standard_error)
      << stiffness->value << " +- " << stiffness->standard_error;
}

// Started where the fit finds the moment, the angle stays within the
// record and nothing restarts.
TEST(MultiStart, NoBearingRestartWhereTheAngleStaysWithinTheRecord) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "800 samples (profile_error_bar_test fits this config "
                    "under the sanitizers)";
  }
  const Case c = LoadConfig(
      testing::SourcePath("tests/data/table6_bearing_moment_seed4.yaml"));
  const FitResult fit = Fit(c);
  EXPECT_FALSE(
      testing::InPipeline(fit, "bearing_angle beyond the record's angles"))
      << ::testing::PrintToString(fit.pipeline);
}

}  // namespace
}  // namespace fit3dof
