// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// `fit3dof fit` end to end: the built command, real files, exit codes.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "fit3dof/config.h"
#include "fit3dof/parameters.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The Table 6 config at 0.01 deg with its data path made absolute, with
// `edit` applied (from, to).
std::string Table6Config(const std::string& dir,
                         const std::string& from = "",
                         const std::string& to = "") {
  std::string text = testing::ReadText(
      testing::SourcePath("configs/report/table6_sigma0.01.yaml"));
  if (!from.empty()) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  }
  const std::string data = "file: data/table6_clean.csv";
  const size_t at = text.find(data);
  if (at != std::string::npos) {
    text.replace(
        at,
        data.size(),
        "file: " + testing::SourcePath("configs/report/data/table6_clean.csv"));
  }
  const std::string path = dir + "/config.yaml";
  testing::WriteText(path, text);
  return path;
}

TEST(FitCli, WritesReportFitComparisonAndTable) {
  const std::string dir = testing::ScratchDirectory("fit_cli_ok");
  const auto result = testing::RunFit3dof("fit " + Table6Config(dir) +
                                          " --out_dir=" + dir + "/out");
  ASSERT_EQ(result.exit_status, 0) << result.output;
  // The readable table: parameter, value, RMS error, units.
  EXPECT_NE(result.output.find("converged"), std::string::npos);
  EXPECT_NE(result.output.find("Cm_q_delta2"), std::string::npos);
  EXPECT_NE(result.output.find("1/rad^3"), std::string::npos);

  const json report = json::parse(testing::ReadText(dir + "/out/report.json"));
  for (const char* key : {"name",
                          "converged",
                          "iterations",
                          "points",
                          "free_parameters",
                          "probable_error",
                          "sum_of_residuals",
                          "rms_residual_deg",
                          "parameters",
                          "correlation",
                          "warnings"}) {
    EXPECT_TRUE(report.contains(key)) << key;
  }
  EXPECT_EQ(report["name"], "table6-sigma0.01");
  EXPECT_EQ(report["integration_step"], 0.01);  // the config's solver.step
  EXPECT_FALSE(report.contains("step_chi_square"));
  EXPECT_TRUE(report["converged"].get<bool>());
  EXPECT_EQ(report["points"], 800);
  EXPECT_EQ(report["free_parameters"], 10);
  const json& cma = report["parameters"]["Cm_alpha"];
  EXPECT_NEAR(cma["value"].get<double>(), -0.236, 2e-5);
  EXPECT_GT(cma["rms_error"].get<double>(), 0.0);
  EXPECT_TRUE(cma["free"].get<bool>());
  EXPECT_EQ(cma["units"], "1/rad");
  const json& clp = report["parameters"]["Cl_p"];
  EXPECT_FALSE(clp["free"].get<bool>());
  EXPECT_TRUE(clp["rms_error"].is_null());
  EXPECT_EQ(report["correlation"]["names"].size(), 10u);
  EXPECT_EQ(report["correlation"]["matrix"].size(), 10u);
  EXPECT_DOUBLE_EQ(report["correlation"]["matrix"][0][0].get<double>(), 1.0);
  // Eq. 26 from Eq. 32: E = S / sqrt(3 N - N_free).
  EXPECT_NEAR(
      report["probable_error"].get<double>(),
      report["sum_of_residuals"].get<double>() / std::sqrt(3.0 * 800 - 10),
      1e-9);

  const std::string csv = testing::ReadText(dir + "/out/fit.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "t,phi,phi_fit,theta,theta_fit,psi,psi_fit,segment");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 801);
  // Nothing half-written left behind.
  for (const auto& entry : fs::directory_iterator(dir + "/out")) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos)
        << entry.path();
  }
}

TEST(FitCli, NonConvergedFitSaysSoWritesWhatItHasExitsOne) {
  const std::string dir = testing::ScratchDirectory("fit_cli_noconv");
  const auto result = testing::RunFit3dof(
      "fit " + Table6Config(dir, "max_iterations: 50", "max_iterations: 2") +
      " --out_dir=" + dir + "/out");
  EXPECT_EQ(result.exit_status, 1) << result.output;
  EXPECT_NE(result.output.find("NOT CONVERGED"), std::string::npos)
      << result.output;
  const json report = json::parse(testing::ReadText(dir + "/out/report.json"));
  EXPECT_FALSE(report["converged"].get<bool>());
  EXPECT_NE(report["termination"].get<std::string>().find("NOT SATISFIED"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(dir + "/out/fit.csv"));
}

struct BadInput {
  const char* from;
  const char* to;
  const char* message;
};

class FitCliBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(FitCliBadInput, ExitsTwoWithAClearMessageAndNoOutput) {
  const BadInput& bad = GetParam();
  const std::string dir = testing::ScratchDirectory("fit_cli_bad");
  std::string config = Table6Config(dir, bad.from, bad.to);
  const auto result =
      testing::RunFit3dof("fit " + config + " --out_dir=" + dir + "/out");
  EXPECT_EQ(result.exit_status, 2) << result.output;
  EXPECT_NE(result.output.find(bad.message), std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(dir + "/out/report.json"));
}

INSTANTIATE_TEST_SUITE_P(
    FitCli,
    FitCliBadInput,
    ::testing::Values(
        BadInput{"file: data/table6_clean.csv",
                 "file: data/missing.csv",
                 "missing.csv"},
        BadInput{"Cm_alpha: {value: -0.2, free: true}",
                 "Cm_alfa: {value: -0.2, free: true}",
                 "unknown parameter of the symmetric model (did you mean "
                 "Cm_alpha?)"},
        BadInput{"sigma: {phi: 0.01,",
                 "sigma: {phi: -0.01,",
                 "sigma.phi: must be positive (deg) or auto"},
        BadInput{
            "data: {file:", "data: {t_end: 0.07, file:", "too few points"}));

// From Cm_q_delta2 = 3000 some of Levenberg-Marquardt's trial steps make the
// motion blow up. They are rejected quietly: the fit converges and nothing
// (no residual dump from Ceres) reaches the log.
TEST(FitCli, BlownUpTrialStepsAreRejectedQuietly) {
  const std::string dir = testing::ScratchDirectory("fit_cli_blowup");
  const std::string config =
      Table6Config(dir,
                   "Cm_q_delta2: {value: 0.0, free: true}",
                   "Cm_q_delta2: {value: 3000.0, free: true}");
  const std::string command = std::string(FIT3DOF_BINARY) + " fit " + config +
                              " --out_dir=" + dir + "/out 2>" + dir +
                              "/stderr.txt >/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const json report = json::parse(testing::ReadText(dir + "/out/report.json"));
  EXPECT_TRUE(report["converged"].get<bool>());
  EXPECT_GT(report["failed_evaluations"].get<int>(), 0);
  EXPECT_NEAR(
      report["parameters"]["Cm_q_delta2"]["value"].get<double>(), 98.5, 2.0);
  EXPECT_LT(testing::ReadText(dir + "/stderr.txt").size(), 200u)
      << testing::ReadText(dir + "/stderr.txt");
}

TEST(FitCli, AllFrozenIsBadInput) {
  const std::string dir = testing::ScratchDirectory("fit_cli_frozen");
  std::string text = testing::ReadText(
      testing::SourcePath("configs/report/table6_motion.yaml"));
  text += "data: {file: " +
          testing::SourcePath("configs/report/data/table6_clean.csv") + "}\n";
  testing::WriteText(dir + "/frozen.yaml", text);
  const auto result = testing::RunFit3dof(
      "fit " + dir + "/frozen.yaml --out_dir=" + dir + "/out");
  EXPECT_EQ(result.exit_status, 2) << result.output;
  EXPECT_NE(result.output.find("every parameter is frozen"), std::string::npos)
      << result.output;
}

// diagnose --absent names catalog effects or probes; anything else is bad
// input, refused before any fit and before any output is written.
TEST(FitCli, DiagnoseAbsentTakesCatalogEffectsAndProbesOnly) {
  const std::string dir = testing::ScratchDirectory("fit_cli_absent");
  const auto result = testing::RunFit3dof(
      "diagnose " + Table6Config(dir) + " --out_dir=" + dir +
      "/out --absent=magnus,pitch_friction,tunnel_buzz");
  EXPECT_EQ(result.exit_status, 2) << result.output;
  EXPECT_NE(result.output.find("(--absent): 'tunnel_buzz' is not an effect "
                               "of the catalog"),
            std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("nor a probe (one of: reading_drift"),
            std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(dir + "/out/diagnosis.json"));
}

// diagnose says the step its search integrated at, and each step's
// report.json the step of its own fit: the nominal fit at the config's
// step, the search's at the coarser one within 0.01 of it.
TEST(FitCli, DiagnoseSaysTheStepItsSearchIntegratedAt) {
  const std::string dir = testing::ScratchDirectory("fit_cli_search_step");
  Case c = testing::ShortRun(dir,
                             "  Cm_alpha_delta2: -1.13\n"
                             "  Cm_bearing: -0.02\n"
                             "  bearing_angle: 1.0\n",
                             3);
  c.parameters[FindParameter(c.model, "Cm_alpha")].free = true;
  c.parameters[FindParameter(c.model, "Cm_q")].free = true;
  c.parameters[FindParameter(c.model, "Cm_bearing")].value = 0.0;
  testing::WriteText(dir + "/fit.yaml", CaseToYaml(c));
  for (const bool exact : {false, true}) {
    const std::string out = dir + (exact ? "/exact" : "/out");
    const auto result =
        testing::RunFit3dof("diagnose " + dir + "/fit.yaml --out_dir=" + out +
                            (exact ? " --exact_step" : ""));
    ASSERT_LE(result.exit_status, 1) << result.output;
    const json d = json::parse(testing::ReadText(out + "/diagnosis.json"));
    const double step = d["search_step"].get<double>();
    if (exact) {
      EXPECT_EQ(step, 0.002);
    } else {
      EXPECT_GE(step, 0.008);
    }
    const json first =
        json::parse(testing::ReadText(out + "/step0/report.json"));
    EXPECT_EQ(first["integration_step"], 0.002);
    int at_search_step = 0;
    for (int i = 1; fs::exists(out + "/step" + std::to_string(i)); ++i) {
      const json r = json::parse(testing::ReadText(
          out + "/step" + std::to_string(i) + "/report.json"));
      if (r["integration_step"].get<double>() != step) continue;
      ++at_search_step;
      if (!exact) EXPECT_LE(r["step_chi_square"].get<double>(), 0.01);
    }
    EXPECT_GE(at_search_step, 1);
  }
}

}  // namespace
}  // namespace fit3dof
