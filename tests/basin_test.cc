// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/basin.h"

#include "fit3dof/config.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

// A small basin study of the Table 6 case: from the wide box the
// robust pipeline reaches the global minimum (tools: fit3dof basin runs
// 200 starts; the figures are in the notes of issue 5).
TEST(Basin, RobustPipelineReachesTheGlobalMinimumFromAWideBox) {
  const Case c =
      LoadConfig(testing::SourcePath("configs/report/table6_sigma0.02.yaml"));
  BasinOptions options;
  options.starts = testing::kSanitized ? 1 : 12;
  options.seed = 7;
  options.methods = {"robust", "levenberg_marquardt"};
  const BasinResult r = RunBasinStudy(c, options);
  std::printf("%s", FormatBasin(r).c_str());
  ASSERT_EQ(r.methods.size(), 2u);
  EXPECT_GE(r.methods[0].reached, options.starts);
  // Plain Levenberg-Marquardt from the same starts does far worse.
  if (!testing::kSanitized) {
    EXPECT_LT(r.methods[1].reached, r.methods[0].reached);
  }
}

}  // namespace
}  // namespace fit3dof
