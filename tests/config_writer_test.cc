// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// CaseToYaml: every config in configs/ (and the example deck's case) loads
// back from what it writes as the same Case, number for number; names and
// paths that look like YAML syntax survive.

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "fit3dof/config.h"
#include "fit3dof/namelist.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

namespace fs = std::filesystem;

Case RoundTrip(const Case& c, const std::string& dir) {
  const std::string text = CaseToYaml(c);
  testing::WriteText(dir + "/again.yaml", text);
  return LoadConfig(dir + "/again.yaml");
}

std::vector<std::string> ConfigsUnder(const std::string& relative) {
  std::vector<std::string> paths;
  for (const auto& entry :
       fs::recursive_directory_iterator(testing::SourcePath(relative))) {
    const std::string path = entry.path().string();
    if (entry.path().extension() == ".yaml" &&
        entry.path().filename() != "manifest.yaml") {
      paths.push_back(path);
    }
  }
  return paths;
}

TEST(ConfigWriter, EveryConfigReadsBackAsTheSameCase) {
  const std::string dir = testing::ScratchDirectory("config_writer_all");
  const std::vector<std::string> paths = ConfigsUnder("configs");
  ASSERT_GE(paths.size(), 14u);
  for (const std::string& path : paths) {
    SCOPED_TRACE(path);
    const Case c = LoadConfig(path);
    EXPECT_TRUE(RoundTrip(c, dir) == c) << CaseToYaml(c);
  }
}

TEST(ConfigWriter, TheDeckCaseReadsBackAsTheSameCase) {
  const std::string dir = testing::ScratchDirectory("config_writer_deck");
  const Case c =
      LoadDeckCase(testing::SourcePath("configs/examples/deck/table6.nml"),
                   testing::SourcePath("configs/report/data/table6_clean.csv"));
  EXPECT_TRUE(RoundTrip(c, dir) == c) << CaseToYaml(c);
}

// The asymmetric image of a symmetric case keeps its symmetric relations as
// ties (model_conversion.h), written as such and read back.
TEST(ConfigWriter, TiesReadBack) {
  const std::string dir = testing::ScratchDirectory("config_writer_ties");
  const Case c = ToAsymmetric(
      LoadConfig(testing::SourcePath("configs/report/table6_motion.yaml")));
  const std::string text = CaseToYaml(c);
  EXPECT_NE(text.find("Cn_beta: {tied: Cm_alpha, factor: -1.0}"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("Cn_r: {tied: Cm_q, factor: 1.0}"), std::string::npos);
  EXPECT_TRUE(RoundTrip(c, dir) == c) << text;
}

TEST(ConfigWriter, NamesAndPathsThatLookLikeYamlSurvive) {
  const std::string dir = testing::ScratchDirectory("config_writer_quoting");
  Case c =
      LoadConfig(testing::SourcePath("configs/report/section5_1_fit.yaml"));
  c.name = "null";
  c.segments[0].name = "a: b # not a comment, [x], 'q' \"dq\"";
  c.segments[0].data_file = dir + "/data: #1, {run}.csv";
  c.segments[0].selection.t_start = 0.25;
  c.segments[0].outliers = OutlierPolicy::kReject;
  c.segments[0].initial[0].auto_start = true;
  c.segments[0].initial[0].free = true;
  c.parameters[0].value = 0.1 + 0.2;  // 0.30000000000000004 exactly
  c.noise.enabled = false;
  c.noise.sigma.theta = 0.01;  // kept although noise is off
  c.noise.seed = (1ull << 53) - 1;
  c.simulate.dt = 0.001;
  c.simulate.samples = 1001;
  c.solver.method = FitMethod::kGaussNewton;
  const Case again = RoundTrip(c, dir);
  EXPECT_EQ(again.name, "null");
  EXPECT_EQ(again.segments[0].name, c.segments[0].name);
  EXPECT_EQ(again.segments[0].data_file, c.segments[0].data_file);
  EXPECT_TRUE(again == c) << CaseToYaml(c);
}

TEST(ConfigWriter, EqualityNoticesEveryKindOfChange) {
  const Case c =
      LoadConfig(testing::SourcePath("configs/report/check_case_2.yaml"));
  Case d = c;
  d.source = "elsewhere.yaml";
  EXPECT_TRUE(d == c);
  d = c;
  d.body.Ix = std::nextafter(c.body.Ix, 1.0);
  EXPECT_FALSE(d == c);
  d = c;
  d.parameters.back().free = !d.parameters.back().free;
  EXPECT_FALSE(d == c);
  d = c;
  d.solver.starts += 1;
  EXPECT_FALSE(d == c);
  d = c;
  d.flow.dynamic_pressure *= 2;
  EXPECT_FALSE(d == c);
}

}  // namespace
}  // namespace fit3dof
