// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The discrepancy workflow against data with hidden effects: each catalog
// effect at a realistic size (Table 7 for the tunnel terms) in the Table 6
// motion with 0.01 deg noise, diagnosed from a config without it.

#include "fit3dof/diagnose.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "diagnose_internal.h"
#include "fit3dof/config.h"
#include "fit3dof/model_conversion.h"
#include "fit3dof/noise.h"
#include "fit3dof/simulator.h"
#include "format.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

// The effect ids of `items` (DiagnosisStep or CandidateFit), each once.
template <typename T>
std::set<std::string> EffectIds(const std::vector<T>& items) {
  std::set<std::string> ids;
  for (const T& item : items) ids.insert(item.effect);
  return ids;
}

// The effect ids of every tie of `d` (the first and the later ones).
std::set<std::string> TiedIds(const Diagnosis& d) {
  std::set<std::string> tied = EffectIds(d.ambiguous);
  for (const auto& tie : d.later_ties) {
    for (const CandidateFit& k : tie) tied.insert(k.effect);
  }
  return tied;
}

// Whether `fits` (a diagnosis's rejected or not_excluded) list `effect`
// with `why` in its reason.
bool ListedWith(const std::vector<CandidateFit>& fits,
                const std::string& effect,
                const std::string& why) {
  return std::any_of(fits.begin(), fits.end(), [&](const CandidateFit& k) {
    return k.effect == effect && k.rejected.find(why) != std::string::npos;
  });
}

// The parameters of `c` named in `values` (name-value pairs) set to theirs.
template <typename Values>
void SetValues(Case* c, const Values& values) {
  for (const auto& [name, value] : values) {
    const int position = FindParameter(c->model, name);
    CHECK_GE(position, 0) << name << " is not a parameter of the model";
    c->parameters[position].value = value;
  }
}

// The linear Table 6 motion (no cubic terms): the base the effects hide in.
Case Truth() {
  Case c = LoadConfig(testing::SourcePath("configs/report/table6_motion.yaml"));
  c.parameters[FindParameter(c.model, "Cm_alpha_delta2")].value = 0.0;
  c.parameters[FindParameter(c.model, "Cm_q_delta2")].value = 0.0;
  return c;
}

// A fit config for `data`: Cm_alpha and Cm_q free from the report's
// guesses, initial conditions from the data, sigma = the noise.
Case FitConfig(const Case& truth, const std::string& data) {
  Case c = truth;
  for (ParameterSetting& p : c.parameters) p = ParameterSetting{};
  c.parameters[FindParameter(c.model, "Cm_alpha")] = {-0.2, true, false};
  c.parameters[FindParameter(c.model, "Cm_q")] = {0.0, true, false};
  Segment s;
  s.name = "run";
  s.data_file = data;
  for (int j = 0; j < 6; ++j) s.initial[j].free = true;
  c.segments = {s};
  c.sigma = {0.01, 0.01, 0.01};
  c.noise = NoiseOptions{};
  c.solver.step = 0.01;
  c.source = data;
  return c;
}

std::string Simulate(const Case& truth,
                     const std::string& path,
                     std::uint64_t seed) {
  std::vector<double> times;
  for (int i = 0; i < 800; ++i) times.push_back(0.06 * i);
  Case c = truth;
  c.solver.step = 0.002;
  return testing::WriteNoisyRecord(c, times, seed, path);
}

struct Hidden {
  std::string effect;
  std::map<std::string, double> values;
  bool asymmetric = false;  // the truth (and the fit config) in body axes
  std::string label;        // the test's name when not the effect's
};

class DiagnoseHidden : public ::testing::TestWithParam<Hidden> {};

TEST_P(DiagnoseHidden, NamesTheEffectRecoversItAndReachesTheNoise) {
  const Hidden& hidden = GetParam();
  // The sanitized build diagnoses one of the catalog, a symmetric effect
  // (the asymmetric program's equations run there in
  // NamesABodyFixedYawAsymmetry..., which switches a symmetric config to
  // body axes; the plain build checks the whole catalog, in both).
  if (testing::PlainBuildOnly() && hidden.effect != "flow_angularity") {
    GTEST_SKIP() << "the plain build diagnoses every effect";
  }
  const std::string dir =
      testing::ScratchDirectory("diagnose_" + hidden.effect);
  Case truth = Truth();
  Case fit_base = FitConfig(truth, dir + "/data.csv");
  if (hidden.asymmetric) {
    truth = ToAsymmetric(truth);
    fit_base = ToAsymmetric(fit_base);
  }
  Case with_effect =
      hidden.effect == "product_of_inertia" ? ToAsymmetric(truth) : truth;
  SetValues(&with_effect, hidden.values);
  Simulate(with_effect, dir + "/data.csv", 21);
  const Diagnosis d = Diagnose(fit_base, DiagnoseOptions());
  ASSERT_FALSE(d.steps.empty()) << FormatDiagnosis(d, fit_base.sigma);
  EXPECT_EQ(d.steps[0].effect, hidden.effect)
      << "ranking: " << d.steps[0].ranking[0].effect << " "
      << d.steps[0].ranking[0].score;
  for (const ParameterEstimate& e : d.steps[0].parameters) {
    const auto it = hidden.values.find(e.name);
    const double truth_value = it == hidden.values.end() ? 0.0 : it->second;
    EXPECT_LT(std::abs(e.value - truth_value), 3.0 * e.rms_error)
        << e.name << " = " << e.value << " +- " << e.rms_error << " (truth "
        << truth_value << ")";
  }
  EXPECT_TRUE(d.final.at_noise_level) << d.verdict_text;
  EXPECT_EQ(VerdictToString(d.verdict), std::string("explained"));
  EXPECT_EQ(d.steps.size(), 1u) << FormatDiagnosis(d, fit_base.sigma);
  EXPECT_NEAR(d.final.rms_deg.theta, 0.01, 0.001);
  EXPECT_NEAR(d.final.rms_deg.psi, 0.01, 0.001);
  std::printf("%s: score %.0f, theta residual %.3g -> %.3g deg\n",
              hidden.effect.c_str(),
              d.steps[0].score,
              d.initial.rms_deg.theta,
              d.final.rms_deg.theta);
}

INSTANTIATE_TEST_SUITE_P(
    Catalog,
    DiagnoseHidden,
    ::testing::Values(
        Hidden{"tunnel_stiffness",
               {{"tunnel_Cm_theta", 0.016}, {"tunnel_Cn_psi", -0.0056}}},
        Hidden{"tunnel_damping",
               {{"tunnel_Cm_thetadot", -1.65}, {"tunnel_Cn_psidot", 2.24}}},
        Hidden{"flow_angularity", {{"theta_T", -0.134}, {"psi_T", 0.152}}},
        Hidden{"product_of_inertia", {{"Izx", 0.002}}},
        Hidden{"roll_torque", {{"Cl_0", -5.7e-6}}},
        Hidden{"magnus", {{"Cm_p_alpha", 0.5}}},
        Hidden{"nonlinear_stiffness", {{"Cm_alpha_delta2", 5.81}}},
        Hidden{"nonlinear_damping", {{"Cm_q_delta2", 98.5}}},
        Hidden{"roll_damping", {{"Cl_p", -0.0081}}},
        Hidden{"trim_moment",
               {{"Cm_0", 0.002}, {"Cn_0", -0.0015}},
               true,
               "trim_moment_body_axes"},
        // From a symmetric config: the symmetric program's own body-fixed
        // trim terms (issue 12: it was named a 0.64-deg roll interaction).
        Hidden{"trim_moment", {{"Cm_0", 0.002}, {"Cn_0", -0.0015}}},
        // Section 5.2's bearing effects: a bearing stiffness of 4% of
        // Cm_alpha fading beyond 1 deg, a cubic calibration error of 0.02
        // deg at 5 deg.
        Hidden{"bearing_moment",
               {{"Cm_bearing", -0.01}, {"bearing_angle", 1.0}}},
        // Near the noise (no continuation in the refit), the angle away
        // from where diagnose starts it (1 deg): it does nothing while
        // Cm_bearing is zero, and had been held there, reported as
        // 1 +- 0.11 deg, Cm_bearing 11 standard errors off (stage_solver.h).
        Hidden{"bearing_moment",
               {{"Cm_bearing", -0.002}, {"bearing_angle", 0.5}},
               false,
               "bearing_moment_half_degree"},
        Hidden{"calibration_nonlinearity",
               {{"theta_cal3", 0.02}, {"psi_cal3", -0.02}}},
        Hidden{"roll_interaction",
               {{"theta_cos_phi", 0.05},
                {"theta_sin_phi", -0.03},
                {"psi_cos_phi", 0.04},
                {"psi_sin_phi", 0.02}}}),
    [](const ::testing::TestParamInfo<Hidden>& info) {
      return info.param.label.empty() ? info.param.effect : info.param.label;
    });

// A batch of dir/config.yaml (a record with a flow angularity) run plain
// and with `diagnose: true`: the plain run converges (its iteration met
// the rule, restarts confirm the minimum) but its residuals are
// structured, exit 0, and the summary says so; the diagnosed run names the
// angularity and writes its diagnosis.
void ExpectBatchDiagnoses(const std::string& dir) {
  testing::WriteText(
      dir + "/manifest.yaml",
      "runs:\n  - {name: plain, config: config.yaml}\n"
      "  - {name: diagnosed, config: config.yaml, diagnose: true}\n");
  const auto batch = testing::RunFit3dof(
      "batch " + dir + "/manifest.yaml --progress=false --out_dir=" + dir +
      "/out");
  EXPECT_EQ(batch.exit_status, 0) << batch.output;
  const std::string summary = testing::ReadText(dir + "/out/summary.csv");
  EXPECT_NE(summary.find(
                "diagnosed,converged,white,added flow_angularity; explained"),
            std::string::npos)
      << summary;
  EXPECT_NE(summary.find("plain,converged,\"structured: theta (Ljung-Box Q "),
            std::string::npos)
      << summary;
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/diagnosed/diagnosis.json"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/diagnosed/step1/fit.csv"));
}

// A probe that ties in two groups (on a 3-s coning run a friction about
// each axis tied with a Magnus moment and again, beside it, with a
// nonlinear damping) is listed once in diagnosis.json's ambiguous_between
// and ambiguous_outside_catalog; ambiguous_groups keeps both ties.
TEST(Diagnose, ListsAnEffectTiedTwiceOnce) {
  Diagnosis d;
  d.verdict = Verdict::kAmbiguous;
  d.ambiguous = {CandidateFit{"magnus"}, CandidateFit{"axis_friction"}};
  d.later_ties = {
      {CandidateFit{"nonlinear_damping"}, CandidateFit{"axis_friction"}}};
  const nlohmann::json j = nlohmann::json::parse(DiagnosisJson(d, Truth()));
  EXPECT_EQ(j["ambiguous_between"],
            nlohmann::json({"magnus", "axis_friction", "nonlinear_damping"}));
  EXPECT_EQ(j["ambiguous_outside_catalog"], nlohmann::json({"axis_friction"}));
  EXPECT_EQ(j["ambiguous_groups"].size(), 2u);
  // What separates each group, in their order (none set here: empty).
  EXPECT_EQ(j["groups_separated_by"], nlohmann::json({"", ""}));
  d.separated_by = "a run at another spin rate";
  d.later_separated_by = {"a run at another amplitude"};
  const nlohmann::json k = nlohmann::json::parse(DiagnosisJson(d, Truth()));
  EXPECT_EQ(k["groups_separated_by"],
            nlohmann::json(
                {"a run at another spin rate", "a run at another amplitude"}));
}

// The workflow in a batch (diagnose: true) and on the command line.
TEST(Diagnose, RunsInABatchAndOnTheCommandLine) {
  const std::string dir = testing::ScratchDirectory("diagnose_batch");
  Case truth = Truth();
  truth.parameters[FindParameter(truth.model, "theta_T")].value = -0.134;
  truth.parameters[FindParameter(truth.model, "psi_T")].value = 0.152;
  Simulate(truth, dir + "/data.csv", 9);
  testing::WriteText(dir + "/config.yaml",
                     CaseToYaml(FitConfig(Truth(), dir + "/data.csv")));
  // The batch half runs in the plain build only: under the sanitizers it
  // would be the command line's diagnosis below again, in another process
  // (batch_test runs the batch's own code sanitized).
  if (!testing::PlainBuildOnly()) ExpectBatchDiagnoses(dir);

  const auto cli = testing::RunFit3dof(
      "diagnose " + dir + "/config.yaml --out_dir=" + dir + "/cli");
  EXPECT_EQ(cli.exit_status, 0) << cli.output;
  EXPECT_NE(cli.output.find("missing effect: flow angularity"),
            std::string::npos)
      << cli.output;
  EXPECT_NE(cli.output.find("(noise 0.01, 0.01 deg)"), std::string::npos)
      << cli.output;
  // diagnosis.json for scripts: the verdict, the effects added, the final
  // model's values (a step's own under step_parameters).
  const nlohmann::json j =
      nlohmann::json::parse(testing::ReadText(dir + "/cli/diagnosis.json"));
  EXPECT_EQ(j["verdict"], "explained");
  EXPECT_EQ(j["effects_added"], nlohmann::json::array({"flow_angularity"}));
  EXPECT_TRUE(j["ambiguous_between"].empty());
  EXPECT_TRUE(j["ambiguous_outside_catalog"].empty());
  EXPECT_TRUE(j["partial"].empty());
  EXPECT_TRUE(j["not_excluded"].is_array());
  EXPECT_EQ(j["outside_catalog_at_noise_level"], false);
  EXPECT_TRUE(j["outside_catalog_beside"].empty());
  const auto& final_theta_t = j["final_parameters"]["theta_T"];
  EXPECT_NEAR(final_theta_t["value"].get<double>(),
              -0.134,
              3.0 * final_theta_t["standard_error"].get<double>());
  EXPECT_EQ(j["steps"][0]["parameters"]["theta_T"], final_theta_t);
  EXPECT_TRUE(j["steps"][0]["step_parameters"].contains("theta_T"));
  // final.yaml reruns: it loads, with the added effect free.
  const Case final_case = LoadConfig(dir + "/cli/final.yaml");
  EXPECT_TRUE(
      final_case.parameters[FindParameter(final_case.model, "theta_T")].free);
}

TEST(Diagnose, FindsTwoHiddenEffects) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "two steps of the paths the catalog runs; plain build";
  }
  const std::string dir = testing::ScratchDirectory("diagnose_two");
  Case truth = Truth();
  truth.parameters[FindParameter(truth.model, "t1")].value = 0.016;
  truth.parameters[FindParameter(truth.model, "t3")].value = -0.0056;
  truth.parameters[FindParameter(truth.model, "theta_T")].value = -0.134;
  truth.parameters[FindParameter(truth.model, "psi_T")].value = 0.152;
  Simulate(truth, dir + "/data.csv", 5);
  const Diagnosis d =
      Diagnose(FitConfig(Truth(), dir + "/data.csv"), DiagnoseOptions());
  const std::set<std::string> found = EffectIds(d.steps);
  EXPECT_TRUE(found.count("tunnel_stiffness"))
      << FormatDiagnosis(d, ChannelValues{0.01, 0.01, 0.01});
  EXPECT_TRUE(found.count("flow_angularity"))
      << FormatDiagnosis(d, ChannelValues{0.01, 0.01, 0.01});
  EXPECT_TRUE(d.final.at_noise_level) << d.verdict_text;
}

// Forward selection is greedy: with a Magnus moment and a nonlinear
// damping hidden together, a tunnel damping can explain most of both at the
// first step and the two true effects the rest. The backward check drops
// what the others make redundant: the final model holds the two, with the
// truth within 3 standard errors.
TEST(Diagnose, DropsAnEffectTheOthersMakeRedundant) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "three steps and a pruning round; plain build";
  }
  const std::string dir = testing::ScratchDirectory("diagnose_prune");
  Case truth = Truth();
  const std::map<std::string, double> hidden = {{"Cm_p_alpha", 0.148},
                                                {"Cm_q_delta2", 29.15}};
  SetValues(&truth, hidden);
  Simulate(truth, dir + "/data.csv", 11);
  const Diagnosis d =
      Diagnose(FitConfig(Truth(), dir + "/data.csv"), DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(VerdictToString(d.verdict), std::string("explained")) << text;
  const std::set<std::string> found = EffectIds(d.steps);
  EXPECT_EQ(found, (std::set<std::string>{"magnus", "nonlinear_damping"}))
      << text;
  for (const ParameterEstimate& e : d.final_parameters) {
    if (!hidden.count(e.name)) continue;
    EXPECT_LT(std::abs(e.value - hidden.at(e.name)), 3.0 * e.standard_error)
        << e.name << "\n"
        << text;
  }
  // A pruned step is reported with why, its terms out of the final model.
  for (const DiagnosisStep& s : d.pruned) {
    EXPECT_NE(s.note.find("redundant"), std::string::npos) << text;
    for (const ParameterEstimate& e : s.parameters) {
      EXPECT_FALSE(e.free) << e.name << "\n" << text;
      EXPECT_EQ(e.value, 0.0) << e.name << "\n" << text;
    }
  }
  EXPECT_EQ(&d.FinalFit(), &d.fits[d.final_fit]);
  EXPECT_TRUE(d.final.at_noise_level) << text;
}

// On clean data it adds nothing (at least 95% of noise seeds).
TEST(Diagnose, AddsNothingToCleanData) {
  const std::string dir = testing::ScratchDirectory("diagnose_clean");
  int added = 0;
  const int kSeeds = testing::kSanitized ? 1 : 20;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    Simulate(Truth(), dir + "/data.csv", 100 + seed);
    const Diagnosis d =
        Diagnose(FitConfig(Truth(), dir + "/data.csv"), DiagnoseOptions());
    added += !d.steps.empty();
    EXPECT_TRUE(d.final.at_noise_level)
        << "seed " << seed << ": " << d.verdict_text;
    // A clean record's twins (a tunnel stiffness and Cm_alpha, Eq. 43) are
    // the nominal fit's convention, not a doubt of the diagnosis.
    EXPECT_TRUE(d.near_twins.empty()) << "seed " << seed;
    if (seed == 1 && d.steps.empty()) {
      // The final model is the nominal fit, the user's own, as `fit` gives
      // it: not refitted (Reported takes on only what the search's BIC
      // rule ended).
      const FitResult plain = Fit(FitConfig(Truth(), dir + "/data.csv"));
      EXPECT_EQ(d.FinalFit().sum_of_residuals, plain.sum_of_residuals);
      EXPECT_EQ(d.FinalFit().iterations, plain.iterations);
    }
    if (d.model_standard_errors.empty()) {
      EXPECT_EQ(FormatDiagnosis(d, {0.01, 0.01, 0.01}).find("widened"),
                std::string::npos);
    }
  }
  std::printf("clean data: effects added in %d of %d seeds\n", added, kSeeds);
  EXPECT_LE(added, kSeeds / 20);
}

// A sigma that is not the noise: clean data whose noise (0.01 deg) is 1.5
// times the configured sigma leaves white residuals too large, which the
// verdict says (it had called them structured); with sigma twice the
// noise they are at the noise level, and the verdict says how far below
// sigma they are and what could hide there.
TEST(Diagnose, SaysWhenSigmaIsNotTheNoise) {
  const std::string dir = testing::ScratchDirectory("diagnose_sigma");
  Simulate(Truth(), dir + "/data.csv", 31);
  Case small = FitConfig(Truth(), dir + "/data.csv");
  small.sigma = {0.0067, 0.0067, 0.0067};
  const Diagnosis d = Diagnose(small, DiagnoseOptions());
  EXPECT_TRUE(d.steps.empty()) << d.verdict_text;
  EXPECT_TRUE(d.final.white) << d.verdict_text;
  EXPECT_FALSE(d.final.at_noise_level);
  EXPECT_EQ(VerdictToString(d.verdict), std::string("not_explained"));
  EXPECT_NE(d.verdict_text.find("the residuals pass the whiteness test"),
            std::string::npos)
      << d.verdict_text;
  // The test's limit is said with it: 0.3, or more on a short record.
  EXPECT_GE(d.final.whiteness_limit, 0.3);
  EXPECT_NE(d.verdict_text.find("each below the limit " +
                                FormatNumber("%.2f", d.final.whiteness_limit)),
            std::string::npos)
      << d.verdict_text;
  EXPECT_NE(d.verdict_text.find("the noise may be larger than configured"),
            std::string::npos)
      << d.verdict_text;
  EXPECT_EQ(d.verdict_text.find("structured"), std::string::npos)
      << d.verdict_text;

  Case large = FitConfig(Truth(), dir + "/data.csv");
  large.sigma = {0.02, 0.02, 0.02};
  const Diagnosis e = Diagnose(large, DiagnoseOptions());
  EXPECT_EQ(VerdictToString(e.verdict), std::string("noise_level"));
  EXPECT_TRUE(e.final.below_sigma);
  EXPECT_NE(e.verdict_text.find("sigma is larger than the noise"),
            std::string::npos)
      << e.verdict_text;

  Case right = FitConfig(Truth(), dir + "/data.csv");
  const Diagnosis f = Diagnose(right, DiagnoseOptions());
  EXPECT_EQ(f.verdict_text, "residuals at noise level");
  EXPECT_FALSE(f.final.below_sigma);
}

}  // namespace
}  // namespace fit3dof

namespace fit3dof {
namespace {

// The issue's short record: the Section 5.3 sharp cone, 3 s at 10 points
// per cycle of its 1.55-Hz motion, 8 deg of coning, spinning at
// `spin` deg/s, with a body-fixed trim moment that leaves residuals of
// about 1.4 times the noise.
Case ShortTruth(double spin) {
  Case c = LoadConfig(testing::SourcePath("configs/report/table6_motion.yaml"));
  for (ParameterSetting& p : c.parameters) p = ParameterSetting{};
  c.body = {0.3491, 0.6667, 0.0301, 0.2583, 0.2583};
  c.flow = {2900.0, 460.0};
  const std::vector<std::pair<std::string, double>> values = {
      {"Cm_alpha", -0.23},
      {"Cm_q", -5.5},
      {"Cm_alpha_delta2", -1.13},
      {"Cm_0", 4.4e-5},
      {"Cn_0", -3.3e-5},
      {"phidot0", spin},
      {"theta0", 8.0}};
  SetValues(&c, values);
  return c;
}

std::string SimulateShort(const Case& truth,
                          const std::string& path,
                          std::uint64_t seed) {
  Case c = truth;
  c.solver.step = 0.002;
  return testing::WriteNoisyRecord(c, testing::ShortRecordTimes(), seed, path);
}

// ShortTruth without its trim moment.
Case UntrimmedShortTruth(double spin) {
  Case truth = ShortTruth(spin);
  truth.parameters[FindParameter(truth.model, "Cm_0")].value = 0.0;
  truth.parameters[FindParameter(truth.model, "Cn_0")].value = 0.0;
  return truth;
}

// One 3-s run without trim at 30 deg/s (`path`, noise seed `seed`) whose
// truth has the parameter `name` at `value`: a hidden fault's record.
std::vector<std::string> ShortRunWith(const std::string& path,
                                      const std::string& name,
                                      double value,
                                      std::uint64_t seed) {
  Case truth = UntrimmedShortTruth(30.0);
  truth.parameters[FindParameter(truth.model, name)].value = value;
  return {SimulateShort(truth, path, seed)};
}

// *c in the asymmetric program with the body's own yaw stiffness: Cn_beta
// untied from -Cm_alpha and `factor` times it. Returns Cn_beta.
double UntieBodyYawStiffness(Case* c, double factor) {
  *c = ToAsymmetric(*c);
  ParameterSetting& cn_beta = c->parameters[FindParameter(c->model, "Cn_beta")];
  cn_beta.tied_to = -1;
  cn_beta.value *= factor;
  return cn_beta.value;
}

// Two 3-s runs without trim, 30 deg/s at 8 deg and 60 deg/s at 4 deg,
// each truth changed by `hide` before it is simulated (noise seeds `seed`
// and seed + 1); the files, dir/run0.csv and dir/run1.csv.
std::vector<std::string> TwoShortRuns(const std::string& dir,
                                      std::uint64_t seed,
                                      const std::function<void(Case*)>& hide) {
  std::vector<std::string> files;
  for (const auto& [spin, angle] : {std::pair{30.0, 8.0}, {60.0, 4.0}}) {
    Case truth = UntrimmedShortTruth(spin);
    truth.parameters[FindParameter(truth.model, "theta0")].value = angle;
    hide(&truth);
    const std::string path =
        dir + "/run" + std::to_string(files.size()) + ".csv";
    files.push_back(SimulateShort(truth, path, seed + files.size()));
  }
  return files;
}

// A fit config of the short records: Cm_alpha and Cm_q free, the cubic
// stiffness known, no trim.
Case ShortConfig(const std::vector<std::string>& files) {
  Case c = ShortTruth(30.0);
  for (const char* name : {"Cm_0", "Cn_0", "phidot0", "theta0"}) {
    c.parameters[FindParameter(c.model, name)] = ParameterSetting{};
  }
  c.parameters[FindParameter(c.model, "Cm_alpha")] = {-0.2, true, false};
  c.parameters[FindParameter(c.model, "Cm_q")] = {-2.0, true, false};
  c.segments.clear();
  for (size_t i = 0; i < files.size(); ++i) {
    Segment s;
    s.name = "run" + std::to_string(i + 1);
    s.data_file = files[i];
    for (int j = 0; j < 6; ++j) s.initial[j].free = true;
    c.segments.push_back(s);
  }
  c.sigma = {0.01, 0.01, 0.01};
  c.solver.step = 0.002;
  c.source = files[0];
  return c;
}

// The diagnosis, with the default options, of a suite record kept in
// tests/data (`file`, under that directory) fitted from ShortConfig.
Diagnosis DiagnoseRecord(const std::string& file) {
  return Diagnose(ShortConfig({testing::SourcePath("tests/data/" + file)}),
                  DiagnoseOptions());
}

// The diagnosis, with the default options, of a config kept in tests/data
// (`file`, under that directory; its data files beside it).
Diagnosis DiagnoseConfig(const std::string& file) {
  return Diagnose(LoadConfig(testing::SourcePath("tests/data/" + file)),
                  DiagnoseOptions());
}

// The same with the catalog's own forms only (DiagnoseOptions::other_forms
// off): what the search does with a calibration error that is not a cube
// when it can name only the cube.
Diagnosis DiagnoseConfigOwnForms(const std::string& file) {
  DiagnoseOptions options;
  options.other_forms = false;
  return Diagnose(LoadConfig(testing::SourcePath("tests/data/" + file)),
                  options);
}

// `parameters` hold each of `truths` (name -> true value) within 3
// standard errors; `context` follows a failure's message.
void ExpectCovers(const std::vector<ParameterEstimate>& parameters,
                  const std::map<std::string, double>& truths,
                  const std::string& context) {
  for (const auto& [name, value] : truths) {
    const ParameterEstimate* e = SharedEstimate(parameters, name);
    ASSERT_NE(e, nullptr) << name << "\n" << context;
    EXPECT_LT(std::abs(e->value - value), 3.0 * e->standard_error)
        << name << " = " << e->value << " +- " << e->standard_error << "\n"
        << context;
  }
}

// `d`'s final model holds each of `truths` within 3 standard errors.
void ExpectFinalCovers(const Diagnosis& d,
                       const std::map<std::string, double>& truths,
                       const std::string& context) {
  ExpectCovers(d.FinalFit().parameters, truths, context);
}

// `d` names exactly `effects` (`explained`) and its final model holds each
// of `truths` within 3 standard errors; `context` follows a failure's
// message.
void ExpectNamedExactly(const Diagnosis& d,
                        const std::set<std::string>& effects,
                        const std::map<std::string, double>& truths,
                        const std::string& context) {
  EXPECT_EQ(d.verdict, Verdict::kExplained) << context;
  EXPECT_EQ(EffectIds(d.steps), effects) << context;
  ExpectFinalCovers(d, truths, context);
}

// At one slow spin (90 deg of roll in the record) a body-fixed trim moment
// and a roll-synchronous reading error leave the same signature: the
// verdict says so, adds neither, and names what would separate them.
// Two runs at different spin rates, diagnosed together, do separate them.
TEST(Diagnose, AmbiguityIsAVerdictAndTwoSpinRatesSeparate) {
  const std::string dir = testing::ScratchDirectory("diagnose_ambiguous");
  const std::string slow =
      SimulateShort(ShortTruth(30.0), dir + "/slow.csv", 3);
  const Diagnosis one = Diagnose(ShortConfig({slow}), DiagnoseOptions());
  const std::string text = FormatDiagnosis(one, {0.01, 0.01, 0.01});
  EXPECT_EQ(VerdictToString(one.verdict), std::string("ambiguous")) << text;
  EXPECT_TRUE(one.steps.empty()) << text;
  const std::set<std::string> pair = EffectIds(one.ambiguous);
  EXPECT_TRUE(pair.count("trim_moment")) << text;
  EXPECT_NE(one.separated_by.find("spin"), std::string::npos) << text;
  const nlohmann::json j =
      nlohmann::json::parse(DiagnosisJson(one, ShortConfig({slow})));
  EXPECT_EQ(j["verdict"], "ambiguous");
  // The pair, and over 90 deg of roll a drift in time as well: the one
  // tied explanation outside the catalog.
  EXPECT_GE(j["ambiguous_between"].size(), 2u);
  std::set<std::string> outside;
  for (const std::string id : j["ambiguous_between"]) {
    if (FindEffect(id) == nullptr) outside.insert(id);
  }
  EXPECT_FALSE(outside.empty()) << j.dump();
  EXPECT_EQ(j["ambiguous_outside_catalog"].get<std::set<std::string>>(),
            outside)
      << j.dump();

  if (testing::PlainBuildOnly()) return;  // the second half: plain build
  const std::string fast =
      SimulateShort(ShortTruth(400.0), dir + "/fast.csv", 4);
  const Diagnosis two = Diagnose(ShortConfig({slow, fast}), DiagnoseOptions());
  const std::string both = FormatDiagnosis(two, {0.01, 0.01, 0.01});
  EXPECT_EQ(VerdictToString(two.verdict), std::string("explained")) << both;
  ASSERT_EQ(two.steps.size(), 1u) << both;
  EXPECT_EQ(two.steps[0].effect, "trim_moment") << both;
}

// Over 90 deg of roll a pitch reading drifting 0.05 deg in 3 s and a
// roll-synchronous reading error look alike: the reading error is not
// adopted, and the verdict names the drift outside the catalog as its
// rival (or finds nothing that explains the record).
TEST(Diagnose, ARollLockedEffectTiesWithADriftOnLessThanARevolution) {
  const std::string dir = testing::ScratchDirectory("diagnose_short_drift");
  SimulateShort(UntrimmedShortTruth(30.0), dir + "/clean.csv", 12);
  TimeHistory data = ReadTimeHistory(dir + "/clean.csv");
  for (int i = 0; i < data.size(); ++i) data.theta[i] += 0.016 * data.t[i];
  WriteTimeHistory(dir + "/data.csv", data);
  const Diagnosis d =
      Diagnose(ShortConfig({dir + "/data.csv"}), DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_TRUE(d.steps.empty()) << text;
  const std::string verdict = VerdictToString(d.verdict);
  if (verdict == "ambiguous") {
    // The rival is a drift: the fitted probe (theta_drift near the truth)
    // or, when the probe falls short, the roll-locked rule's unfitted one.
    ASSERT_EQ(d.ambiguous.size(), 2u) << text;
    const CandidateFit& rival = d.ambiguous[1];
    if (rival.effect == "reading_drift") {
      ASSERT_EQ(rival.parameters.size(), 2u) << text;
      for (const ParameterEstimate& e : rival.parameters) {
        if (e.name == "theta_drift") {
          EXPECT_NEAR(e.value, 0.016, 3.0 * e.standard_error) << text;
        }
      }
      EXPECT_NE(d.separated_by.find("second run"), std::string::npos) << text;
    } else {
      EXPECT_EQ(rival.effect, "drift_in_time") << text;
      EXPECT_NE(d.separated_by.find("revolution of roll"), std::string::npos)
          << text;
      EXPECT_NE(text.find("drift_in_time (outside the catalog, not fitted)"),
                std::string::npos)
          << text;
    }
  } else {
    EXPECT_EQ(verdict, "not_explained") << text;
  }
  // The final model is the nominal fit.
  EXPECT_EQ(&d.FinalFit(), &d.fits.front());
}

// tools/diagnose_suite's `short` trim moment (draw 10), kept as
// tests/data/short_trim_moment_seed10.csv: over 90 deg of roll the fitted
// drift of the readings came out 0.4 lower in BIC than the trim moment,
// and with no margin for a drift against a roll-locked effect the record
// was not explained. A difference that small is no evidence either way
// (DiagnoseOptions::drift_bic): the two tie, the trim moment among the
// tied effects, nothing added.
TEST(Diagnose, ADriftBarelyBetterThanATrimMomentTiesWithIt) {
  const Diagnosis d = DiagnoseRecord("short_trim_moment_seed10.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  const std::set<std::string> tied = EffectIds(d.ambiguous);
  EXPECT_TRUE(tied.count("trim_moment")) << text;
  EXPECT_TRUE(tied.count("reading_drift")) << text;
}

// A drift of the readings has two parameters, as a trim moment has: over
// less than a revolution of roll it beats the trim moment by what the fit
// shows, not by a roll reading error's spare parameters, and needs the
// ambiguity margin (ProbeMargin). On draw 159's cone with a tunnel
// stiffness, a roll reading error and a flow angularity
// (tests/data/coning_stiffness_roll_error_angularity_draw159.yaml, 57 deg
// of roll, sigma: auto) the drift came 4.0 below the trim moment after the
// stiffness's tie had lowered BIC by 73-79: the record was `not_explained`
// with nothing named, the true model's fit 0.8 above the drift's. The trim
// moment and the drift tie; the stiffness stays in its tie.
TEST(Diagnose, ADriftAheadOfATrimMomentByLessThanTheMarginTiesWithIt) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_stiffness_roll_error_angularity_draw159.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  const std::set<std::string> tied = TiedIds(d);
  EXPECT_TRUE(tied.count("tunnel_stiffness")) << text;
  EXPECT_TRUE(tied.count("trim_moment")) << text;
  EXPECT_TRUE(tied.count("reading_drift")) << text;
  // The fitted drift is the drift in time: not listed twice.
  EXPECT_FALSE(tied.count("drift_in_time")) << text;
  // Each tie says what would separate it, the later ones too.
  ASSERT_EQ(d.later_separated_by.size(), d.later_ties.size()) << text;
  for (size_t i = 0; i < d.later_ties.size(); ++i) {
    if (!FindFit(d.later_ties[i], "reading_drift")) continue;
    EXPECT_NE(d.later_separated_by[i].find("a revolution of roll"),
              std::string::npos)
        << text;
    EXPECT_NE(
        d.verdict_text.find(d.later_separated_by[i] + " would separate them"),
        std::string::npos)
        << text;
  }
}

// tools/diagnose_suite --vary-conditions' `short` roll reading error at
// 1.48 times the noise (draw 136), kept as
// tests/data/short_roll_interaction_vary136.yaml: 34 samples over 109 deg
// of roll, too short to confirm a roll-locked effect out of sample (the
// reading error and a trim moment lower BIC by 36 and 40, and each
// predicts the held-out odd runs worse). Whatever the answer, it is not
// silent about the true effect: added, tied, or named among the
// roll-locked contenders the record cannot confirm, with what would
// (the verdict had said only that the noise may be larger than
// configured).
TEST(Diagnose, ARollLockedEffectTheRecordCannotConfirmIsNamed) {
  const Diagnosis d = DiagnoseConfig("short_roll_interaction_vary136.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  const std::vector<TimeHistory> data = FittedData(d.FinalFit());
  EXPECT_NEAR(RollSpan(data), 109.0, 1.0) << text;
  EXPECT_FALSE(RollSeparates(data)) << text;
  std::set<std::string> named = EffectIds(d.ambiguous);
  for (const DiagnosisStep& s : d.steps) named.insert(s.effect);
  if (named.count("roll_interaction")) return;
  EXPECT_EQ(d.verdict, Verdict::kNotExplained) << text;
  EXPECT_NE(d.verdict_text.find("roll_interaction by"), std::string::npos)
      << text;
  EXPECT_NE(d.verdict_text.find("a record spanning a revolution of roll"),
            std::string::npos)
      << text;
}

// tools/diagnose_suite --vary's `short` roll reading error beside a
// nonlinear damping of 3.5 times |Cm_q| at 8 deg (draw 13), kept as
// tests/data/short_roll_nonlinear_damping_vary13.csv. The damping drags
// Cm_q alone and ranks last of the round's four contenders; the three
// ranked before it, roll-locked, fail alone only to predict the held-out
// part. A joint set drawn from contenders after the lead alone had none
// to draw: the record ended `not_explained`, Cm_q 145 of its errors off.
// Drawn from those before it too (JointPool), the damping is added with a
// roll-locked effect, the reading error among those tied, and Cm_q and
// the damping's term come within 3 errors of the truth.
TEST(Diagnose, AJointSetDrawsOnContendersRankedAboveItsLead) {
  const Diagnosis d = DiagnoseRecord("short_roll_nonlinear_damping_vary13.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_NE(d.verdict, Verdict::kNotExplained) << text;
  std::set<std::string> named = EffectIds(d.ambiguous);
  for (const DiagnosisStep& s : d.steps) named.insert(s.effect);
  EXPECT_TRUE(named.count("nonlinear_damping")) << text;
  EXPECT_TRUE(named.count("roll_interaction")) << text;
  ExpectFinalCovers(d, {{"Cm_q", -5.5}, {"Cm_q_delta2", 982.87}}, text);
}

// On a 3-s coning run the Magnus moment acts along the motion as Cm_q
// does: its score at every round's solution was spanned by Cm_q (novelty
// about 1e-5), so no round refitted it and it was never tried beside the
// final model. That model (a tunnel damping, a tie of the angularity and
// the reading error) reached the noise with Cm_q at -2.15 +- 0.03, 106 of
// its errors from the truth. Tried there as a near twin (NearTwins), the
// Magnus moment is not excluded, and the final error bars cover the
// truth.
TEST(Diagnose, NearTwinsOfTheFreeParametersAreTriedBesideTheFinalModel) {
  const Diagnosis d =
      DiagnoseConfig("coning_damping_magnus_angularity_vary14.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_TRUE(EffectIds(d.not_excluded).count("magnus")) << text;
  EXPECT_NE(std::find(d.near_twins.begin(), d.near_twins.end(), "magnus"),
            d.near_twins.end())
      << text;
  EXPECT_NE(text.find("near twin"), std::string::npos) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}}, text);
}

// The same with the Magnus moment an exact twin (under the score's rank
// drop) once the tunnel damping is in: on draw 112's 4-s coning run of
// another body, sigma: auto (tests/data/coning_damping_magnus_angularity_
// vary112.yaml), its novelty at the final model was 4.6e-7 (5.1e-5 with
// the damping's terms held). Left out as exact twins are (Eq. 43's tunnel
// terms, twins on every record), it was nowhere in the answer, and Cm_q
// ended -1.24 +- 0.27 against -4.05, 10.5 errors off.
TEST(Diagnose, AnExactTwinNotOnTheTunnelRidgeIsTriedBesideTheFinalModel) {
  const Diagnosis d =
      DiagnoseConfig("coning_damping_magnus_angularity_vary112.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_TRUE(EffectIds(d.not_excluded).count("magnus")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("tunnel_damping")) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.2118}, {"Cm_q", -4.045}}, text);
}

// A candidate scored within a few percent of the last one a round
// refits is refitted too: the ranking there is within the linearization's
// error. On draw 113's 3-s coning run with a tunnel damping, a Magnus
// moment and a flow angularity (tests/data/coning_damping_magnus_
// angularity_vary113.yaml) the damping scored 33.86 at the first round,
// sixth, 0.8% under the roll torque's 34.12; refitted it lowers BIC by
// 33.3 (the roll torque 38.5: on the cone its evidence is the roll part
// of Eq. 39, a steady roll torque). Never refitted, it was left out of
// the tie the answer names (a roll torque, a roll damping or a trim
// moment), and the true model came 28.6 lower in BIC than that answer.
TEST(Diagnose, ACandidateScoredAtTheCutIsRefittedToo) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_damping_magnus_angularity_vary113.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("tunnel_damping")) << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("roll_torque")) << text;
}

// An engineer who knows the tunnel has no Magnus moment in it says so
// (`--absent magnus`): the effect is never tried, so the near twin no
// longer widens Cm_q's error bar (the other effects not excluded hardly
// do), and the text and diagnosis.json say what was declared absent.
TEST(Diagnose, EffectsKnownAbsentAreNeverTried) {
  DiagnoseOptions options;
  options.absent = {"magnus"};
  const Case c = LoadConfig(testing::SourcePath(
      "tests/data/coning_damping_magnus_angularity_vary14.yaml"));
  const Diagnosis d = Diagnose(c, options);
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_TRUE(d.near_twins.empty()) << text;
  std::set<std::string> tried = EffectIds(d.not_excluded);
  for (const auto& ids :
       {EffectIds(d.steps), EffectIds(d.ambiguous), EffectIds(d.rejected)}) {
    tried.insert(ids.begin(), ids.end());
  }
  EXPECT_FALSE(tried.count("magnus")) << text;
  // The Magnus moment had widened it 120-fold (+- 1.9 against 0.016).
  const ParameterEstimate* cm_q = SharedEstimate(d.FinalFit(), "Cm_q");
  ASSERT_NE(cm_q, nullptr);
  const auto own = d.model_standard_errors.find("Cm_q");
  if (own != d.model_standard_errors.end()) {
    EXPECT_LT(cm_q->standard_error, 2.0 * own->second) << text;
  }
  EXPECT_NE(text.find("known absent, not tried: magnus"), std::string::npos)
      << text;
  const nlohmann::json json = nlohmann::json::parse(DiagnosisJson(d, c));
  EXPECT_EQ(json["effects_known_absent"], nlohmann::json::array({"magnus"}));
}

// On a 3-s run with a nonlinear damping at 0.9 of its bound, Cm_q takes
// it (its near twin, novelty 0.0014): the nominal fit reaches the noise
// level with Cm_q 61 of its errors off, and the search had stopped there.
// The damping's score stands 11 above ln(n), so the near twins get one
// round (HiddenTwins): the damping is named, and Cm_q and its term come
// within 3 errors of the truth.
TEST(Diagnose, ANearTwinHiddenAtTheNoiseLevelGetsARound) {
  const Diagnosis d = DiagnoseRecord("short_nonlinear_damping_vary15.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  std::set<std::string> named = EffectIds(d.ambiguous);
  for (const DiagnosisStep& s : d.steps) named.insert(s.effect);
  EXPECT_TRUE(named.count("nonlinear_damping")) << text;
  ExpectFinalCovers(d, {{"Cm_q", -5.5}, {"Cm_q_delta2", 277.19}}, text);
}

// A clean 48-s Table 6 record whose noise holds a line at the spin
// frequency: a product of inertia, a near twin of the initial conditions
// alone (novelty 0.0006), scores 24.2 there, and had been added at 5.0 of
// its errors. It moves no coefficient (TwinShifts), so the search at the
// noise level gives it no round: the answer is the noise level.
TEST(Diagnose, ATwinOfTheInitialConditionsAloneGetsNoRoundAtTheNoise) {
  const Diagnosis d = DiagnoseConfig("clean_table6_draw67.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(VerdictToString(d.verdict), std::string("noise_level")) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
}

// `d` (printed as `text`) adds nothing, ends not_explained and names the
// probe `probe` outside the catalog, each of its parameters in `truths`
// (name -> true value) within 3 standard errors of its truth.
void ExpectOutsideCatalog(const Diagnosis& d,
                          const std::string& text,
                          const std::string& probe,
                          const std::map<std::string, double>& truths) {
  EXPECT_EQ(VerdictToString(d.verdict), std::string("not_explained")) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  ASSERT_EQ(d.outside_catalog.effect, probe) << text;
  const std::vector<ParameterEstimate>& fitted = d.outside_catalog.parameters;
  for (const auto& [name, truth] : truths) {
    const auto it = std::find_if(
        fitted.begin(), fitted.end(), [&](const ParameterEstimate& e) {
          return e.name == name;
        });
    ASSERT_NE(it, fitted.end()) << name << "\n" << text;
    EXPECT_NEAR(it->value, truth, 3.0 * it->standard_error) << name << "\n"
                                                            << text;
  }
  // The probe is the hidden fault's own model: with it the residuals
  // reach the noise, and the report says so.
  EXPECT_TRUE(d.outside_at_noise_level) << text;
  EXPECT_NE(text.find("residuals at the noise level with it"),
            std::string::npos)
      << text;
}

// The same, for a probe's one parameter `name`.
void ExpectOutsideCatalog(const Diagnosis& d,
                          const std::string& text,
                          const std::string& probe,
                          const std::string& name,
                          double truth) {
  ExpectOutsideCatalog(d, text, probe, {{name, truth}});
}

// The same drift in two runs (30 deg/s and 8 deg, 60 deg/s and 4 deg): a
// roll-synchronous reading error cannot follow it in both, the probe
// outside the catalog (theta_drift, psi_drift) can. Nothing is adopted,
// the verdict is not_explained and names the drift with its fitted rate.
TEST(Diagnose, TwoRunsNameADriftOfTheReadingsOutsideTheCatalog) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe's path as ALaggingPitchReading...'s; plain build";
  }
  const std::string dir = testing::ScratchDirectory("diagnose_two_drifts");
  const std::vector<std::string> files = TwoShortRuns(dir, 21, [](Case* c) {
    c->parameters[FindParameter(c->model, "theta_drift")].value = 0.02;
  });
  const Diagnosis d = Diagnose(ShortConfig(files), DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectOutsideCatalog(d, text, "reading_drift", "theta_drift", 0.02);
  EXPECT_EQ(&d.FinalFit(), &d.fits.front());
  EXPECT_NE(d.verdict_text.find("drift of the pitch and yaw readings"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("outside the catalog, not adopted: reading_drift"),
            std::string::npos)
      << text;
  const nlohmann::json j =
      nlohmann::json::parse(DiagnosisJson(d, ShortConfig(files)));
  EXPECT_EQ(j["outside_catalog"]["effect"], "reading_drift");
  EXPECT_TRUE(j["effects_added"].empty());
}

// A dynamic pressure rising 1.2% over one 3-s run (30 deg/s, 8 deg): the
// stiffness grows in time, as a bearing moment's grows while the amplitude
// decays, and a bearing moment had been adopted for it. The second probe
// outside the catalog (q_drift) explains it better: nothing is adopted,
// the verdict is not_explained and names the drift with its rate.
TEST(Diagnose, ADriftingDynamicPressureIsNotExplainedByTheCatalog) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe's path as ALaggingPitchReading...'s; plain build";
  }
  const std::string dir = testing::ScratchDirectory("diagnose_q_drift");
  const std::vector<std::string> files =
      ShortRunWith(dir + "/run0.csv", "q_drift", 0.004, 5);
  const Diagnosis d = Diagnose(ShortConfig(files), DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectOutsideCatalog(d, text, "pressure_drift", "q_drift", 0.004);
  EXPECT_EQ(&d.FinalFit(), &d.fits.front());
  EXPECT_EQ(d.outside_catalog.parameters.size(), 1u) << text;
  EXPECT_NE(d.verdict_text.find("a dynamic pressure drifting during the run"),
            std::string::npos)
      << text;
}

// A flow 3.5% softer in the tunnel's yaw plane than in its pitch plane
// (Cn_beta_flow = -0.008 against Cm_alpha = -0.23), acting through the
// model's normal force: Eq. 39's tunnel stiffness carries a roll torque
// this has not, and on two runs from a pitch-plane start (30 and 60 deg/s)
// a Magnus moment had been adopted for it (the spin turns the pitching into
// yaw either way). The third probe outside the catalog explains it:
// nothing is adopted, the verdict is not_explained with its value.
TEST(Diagnose, AFlowStifferInOnePlaneIsNotAMagnusMoment) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe's path as ALaggingPitchReading...'s; plain build";
  }
  const std::string dir = testing::ScratchDirectory("diagnose_flow_planes");
  const std::vector<std::string> files = TwoShortRuns(dir, 41, [](Case* c) {
    c->parameters[FindParameter(c->model, "Cn_beta_flow")].value = -0.008;
  });
  const Diagnosis d = Diagnose(ShortConfig(files), DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectOutsideCatalog(d, text, "flow_yaw_stiffness", "Cn_beta_flow", -0.008);
  EXPECT_EQ(d.outside_catalog.parameters.size(), 1u) << text;
}

// A pitch reading lagging 6 ms (a filter in the signal conditioning) on one
// 3-s run in circular coning (8 deg, the pitch plane turning at 78 deg/s):
// the pitch channel's phase lags the yaw channel's, as a tunnel damping
// stronger in pitch than in yaw makes it, and tunnel damping had been
// adopted for it, residuals at the noise. The fourth probe outside the
// catalog fits the lag: not_explained, the lag within 3 errors.
TEST(Diagnose, ALaggingPitchReadingIsNotATunnelDamping) {
  const std::string dir = testing::ScratchDirectory("diagnose_reading_lag");
  Case truth = UntrimmedShortTruth(30.0);
  SetValues(
      &truth,
      std::map<std::string, double>{{"psidot0", 78.0}, {"theta_lag", 0.006}});
  const std::vector<std::string> files = {
      SimulateShort(truth, dir + "/run0.csv", 7)};
  const Diagnosis d = Diagnose(ShortConfig(files), DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectOutsideCatalog(d, text, "reading_lag", "theta_lag", 0.006);
}

// A pitch reading whose gain is 5% off the yaw reading's (a calibration
// slope) on two 3-s runs (30 and 60 deg/s): a cubic calibration error and
// a bearing moment between them had been adopted for it. The fifth probe
// fits the gain: not_explained, the gain within 3 errors.
TEST(Diagnose, APitchReadingsGainIsNotACalibrationNonlinearity) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe's path as ALaggingPitchReading...'s; plain build";
  }
  const std::string dir = testing::ScratchDirectory("diagnose_reading_gain");
  const std::vector<std::string> files = TwoShortRuns(dir, 51, [](Case* c) {
    c->parameters[FindParameter(c->model, "theta_gain")].value = 0.05;
  });
  const Diagnosis d = Diagnose(ShortConfig(files), DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectOutsideCatalog(d, text, "reading_gain", "theta_gain", 0.05);
  EXPECT_EQ(d.outside_catalog.parameters.size(), 1u) << text;
}

// Dry friction in the bearing (Cm_friction = 2.8e-4: a moment of constant
// size against the pitch-yaw rate) on one 3-s run pitching in one plane:
// its damping grows as the amplitude falls, as a nonlinear damping with a
// positive Cm_q_delta2 does, and that (474 +- 40) had been adopted for it,
// residuals at the noise. The sixth probe fits the friction (BIC 16.6
// lower): not_explained, its value within 3 errors. (At 2e-4 the two tie:
// `ambiguous`, neither added.)
TEST(Diagnose, DryFrictionInTheBearingIsNotANonlinearDamping) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe's path as ALaggingPitchReading...'s; plain build";
  }
  const std::string dir = testing::ScratchDirectory("diagnose_friction");
  const std::vector<std::string> files =
      ShortRunWith(dir + "/run0.csv", "Cm_friction", 2.8e-4, 9);
  const Diagnosis d = Diagnose(ShortConfig(files), DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectOutsideCatalog(d, text, "bearing_friction", "Cm_friction", 2.8e-4);
}

// tools/diagnose_suite's `short` tunnel damping (t2 = -1.27, t4 = 1.72;
// draw 2), kept as tests/data/short_tunnel_damping_seed2.csv. The axis
// friction probe fitted it 3.4 better, with Cm_axis_friction = -1.7e-5 +-
// 1.9e-6: a friction that drives the motion, no friction at all. The tie
// it made had left the record `ambiguous`. A probe whose lag or friction
// has the wrong sign is no answer (WrongSign): the damping is named.
TEST(Diagnose, AFrictionThatDrivesTheMotionIsNoAnswer) {
  const Diagnosis d = DiagnoseRecord("short_tunnel_damping_seed2.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kExplained) << text;
  EXPECT_EQ(EffectIds(d.steps), std::set<std::string>({"tunnel_damping"}))
      << text;
  for (const auto& [name, truth] :
       {std::pair{"tunnel_Cm_thetadot", -1.268}, {"tunnel_Cn_psidot", 1.722}}) {
    const ParameterEstimate* e = SharedEstimate(d.FinalFit(), name);
    ASSERT_NE(e, nullptr) << name << "\n" << text;
    EXPECT_NEAR(e->value, truth, 3.0 * e->standard_error) << name << "\n"
                                                          << text;
  }
}

// tools/diagnose_suite's `coning` pitch reading lag (6.69 ms, the yaw
// reading none; draw 34), kept as tests/data/coning_pitch_lag_draw34.yaml.
// The reading-lag probe fitted both lags, psi_lag -0.00105 +- 0.00051 s,
// and was refused for it (WrongSign); a tunnel damping, 32 of BIC behind,
// was named. A term past zero against its sign, the other not, is held
// at zero (SignHeld): the pitch lag alone reaches the noise.
TEST(Diagnose, AProbeTermPastItsSignIsHeldAtZero) {
  const Diagnosis d = DiagnoseConfig("coning_pitch_lag_draw34.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectOutsideCatalog(d, text, "reading_lag", "theta_lag", 0.00669);
  const ParameterEstimate* yaw =
      SharedEstimate(d.outside_catalog.parameters, "psi_lag");
  ASSERT_NE(yaw, nullptr) << text;
  EXPECT_FALSE(yaw->free) << text;
  EXPECT_EQ(yaw->value, 0.0) << text;
  EXPECT_NE(text.find("psi_lag = 0 s (held)"), std::string::npos) << text;
}

// Dry friction about each of the pitch and yaw axes alone
// (Cm_axis_friction = 1e-4, on both axes) on one 3-s run pitching in
// one plane: the small yaw rate is damped by the friction's full size,
// which a tunnel damping of opposite signs in yaw and pitch imitates
// (without the probes: t4 = -19.5 +- 2.2, t2 = +10.9 +- 2, `explained`,
// residuals at the noise); the ball's friction (the sixth probe) does not.
// The seventh probe fits it: not_explained, its values within 3 errors.
// (At 5e-5 it ties with the tunnel damping: `ambiguous`, neither added.)
TEST(Diagnose, DryFrictionAboutEachAxisIsNotATunnelDamping) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe's path as ALaggingPitchReading...'s; plain build";
  }
  const std::string dir = testing::ScratchDirectory("diagnose_axis_friction");
  const std::vector<std::string> files =
      ShortRunWith(dir + "/run0.csv", "Cm_axis_friction", 1e-4, 9);
  DiagnoseOptions options;
  const Diagnosis d = Diagnose(ShortConfig(files), options);
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectOutsideCatalog(d, text, "axis_friction", "Cm_axis_friction", 1e-4);
  // Without the probes the catalog's nearest effect is adopted for it.
  options.probes = false;
  const Diagnosis without = Diagnose(ShortConfig(files), options);
  EXPECT_FALSE(without.steps.empty())
      << FormatDiagnosis(without, {0.01, 0.01, 0.01});
}

// tools/diagnose_suite's `short` dry friction about the pitch axis alone
// (draw 4), kept as tests/data/short_pitch_friction_seed4.csv, with the
// probe that models it declared absent: a fault no probe models. The
// ball's friction lowers BIC most at the first round (115.9), but a
// nonlinear damping and a body yaw asymmetry together explain the record
// 31.9 below it, and they had been adopted (Cm_q -9.9 +- 0.29, truth -5.5;
// the nominal fit's -8.8). The probe is weighed with what the catalog adds
// beside it as well: with a tunnel damping or a body asymmetry beside it
// the record is explained 38 below them. Not explained; nothing added.
TEST(Diagnose, AProbeIsWeighedWithWhatTheCatalogAddsBesideIt) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  const Case c = ShortConfig(
      {testing::SourcePath("tests/data/short_pitch_friction_seed4.csv")});
  DiagnoseOptions options;
  options.absent = {"pitch_friction"};
  const Diagnosis d = Diagnose(c, options);
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(VerdictToString(d.verdict), std::string("not_explained")) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_EQ(d.outside_catalog.effect, "bearing_friction") << text;
  EXPECT_NE(d.verdict_text.find("beside it"), std::string::npos) << text;
  const nlohmann::json j = nlohmann::json::parse(DiagnosisJson(d, c));
  EXPECT_FALSE(j["outside_catalog_beside"].empty()) << text;
  EXPECT_EQ(j["outside_catalog_beside"],
            nlohmann::json(d.outside_catalog_beside));
}

// The same case on draw 7 (tests/data/short_pitch_friction_seed7.csv),
// the pitch axis's friction probe again absent: with a tunnel damping
// beside it the ball's friction explains the record only 2.4 below the
// nonlinear damping and body yaw asymmetry the catalog answers with, short
// of the 10 that would make it the answer. The catalog's answer is taken,
// and the verdict says that the probe's model explains the record alike
// and what would separate them (outside_catalog_alike): it had said
// nothing of it.
TEST(Diagnose, AProbesModelThatExplainsTheRecordAlikeIsNamed) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe's path as ALaggingPitchReading...'s; plain build";
  }
  const Case c = ShortConfig(
      {testing::SourcePath("tests/data/short_pitch_friction_seed7.csv")});
  DiagnoseOptions options;
  options.absent = {"pitch_friction"};
  const Diagnosis d = Diagnose(c, options);
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_TRUE(d.outside_catalog.effect.empty()) << text;
  ASSERT_GE(d.outside_catalog_alike.size(), 2u) << text;
  EXPECT_EQ(d.outside_catalog_alike[0], "bearing_friction") << text;
  EXPECT_NE(d.verdict_text.find("alike: dry (Coulomb) friction"),
            std::string::npos)
      << text;
  EXPECT_NE(d.verdict_text.find("another amplitude"), std::string::npos)
      << text;
  const nlohmann::json j = nlohmann::json::parse(DiagnosisJson(d, c));
  EXPECT_EQ(j["outside_catalog_alike"],
            nlohmann::json(d.outside_catalog_alike));
}

// A probe's model that holds every effect of the catalog's answer beside
// the probe is that answer with one term more: no other explanation. On
// draw 125's pair of 3-s runs with a tunnel damping, a Magnus moment and a
// flow angularity (tests/data/pair_damping_magnus_angularity_vary125.yaml),
// a flow stiffer in yaw outdid every catalog effect at the first step; the
// three together explain the record 383 lower, and the flow probe beside
// all three came within 10 of them. The verdict had named it "alike", with
// what would separate them; it now says the probe is not needed beside
// them, nor excluded, and names nothing alike.
TEST(Diagnose, AProbeBesideTheWholeCatalogAnswerIsNoAlikeModel) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_damping_magnus_angularity_vary125.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kExplained) << text;
  EXPECT_EQ(
      EffectIds(d.steps),
      (std::set<std::string>{"flow_angularity", "magnus", "tunnel_damping"}))
      << text;
  EXPECT_TRUE(d.outside_catalog_alike.empty()) << text;
  EXPECT_EQ(d.verdict_text.find("alike"), std::string::npos) << text;
  const auto probe =
      std::find_if(d.rejected.begin(), d.rejected.end(), [](const auto& k) {
        return k.effect == "flow_yaw_stiffness";
      });
  ASSERT_NE(probe, d.rejected.end()) << text;
  EXPECT_NE(probe->rejected.find("beside every effect of the catalog's "
                                 "answer"),
            std::string::npos)
      << text;
  EXPECT_NE(probe->rejected.find("not needed, nor excluded"), std::string::npos)
      << text;
}

// A probe that stands in for one step of the catalog's answer is searched
// beside the catalog's effects, not only fitted beside its final model:
// on draw 176's coning run with a Magnus moment, a nonlinear damping and
// a calibration error (tests/data/coning_magnus_damping_calibration_
// vary176.yaml), the ball's dry friction outdid every catalog effect at
// the first step. Beside the three effects it is not needed (BIC +5), but
// in the nonlinear damping's place, a damping that grows with the
// amplitude as the friction's describing function falls, it comes within
// 10 of them: with the Magnus moment beside it the probe explains the
// record alike, which the verdict names, with what would separate them.
TEST(Diagnose, AProbeThatStandsInForAStepIsSearchedBeside) {
  const Diagnosis d =
      DiagnoseConfig("coning_magnus_damping_calibration_vary176.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kExplained) << text;
  EXPECT_EQ(EffectIds(d.steps),
            (std::set<std::string>{
                "calibration_nonlinearity", "magnus", "nonlinear_damping"}))
      << text;
  EXPECT_EQ(d.outside_catalog_alike,
            (std::vector<std::string>{"bearing_friction", "magnus"}))
      << text;
  EXPECT_NE(d.verdict_text.find("another amplitude"), std::string::npos)
      << text;
}

// Dry friction about the pitch axis alone, which the ball's friction and
// the friction of both axes did not model: on the 3-s runs of draws 4 and
// 7 it had got a nonlinear damping and a body asymmetry (the two tests
// above), and on the circular cone of draw 23 (tests/data/coning_pitch_
// friction_draw23.yaml) a tunnel damping, `explained` with Cm_q moved from
// 3.5 to 12.2 of its errors off the truth: there the friction's describing
// function is a damping of the pitch axis alone, which Eq. 39's t2 and t4
// give with Cm_q shifted by half of it. The eighth probe fits it: not
// explained, nothing added, the friction within 3 errors of the truth;
// with that probe declared absent the tunnel damping is named again.
TEST(Diagnose, AFrictionAboutThePitchAxisAloneIsNamed) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe's path as ALaggingPitchReading...'s; plain build";
  }
  const Diagnosis d = DiagnoseConfig("coning_pitch_friction_draw23.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectOutsideCatalog(d, text, "pitch_friction", "Cm_pitch_friction", 6.31e-5);
  const Diagnosis short_run = DiagnoseRecord("short_pitch_friction_seed4.csv");
  EXPECT_EQ(short_run.outside_catalog.effect, "pitch_friction")
      << FormatDiagnosis(short_run, {0.01, 0.01, 0.01});
  EXPECT_TRUE(short_run.steps.empty())
      << FormatDiagnosis(short_run, {0.01, 0.01, 0.01});
  DiagnoseOptions options;
  options.absent = {"pitch_friction"};
  const Diagnosis without = Diagnose(
      LoadConfig(
          testing::SourcePath("tests/data/coning_pitch_friction_draw23.yaml")),
      options);
  EXPECT_EQ(EffectIds(without.steps), std::set<std::string>({"tunnel_damping"}))
      << FormatDiagnosis(without, {0.01, 0.01, 0.01});
}

// The same friction on draw 122's cone (tests/data/coning_pitch_friction_
// draw122.yaml, sigma: auto): the pitch friction probe came 0.5 of BIC
// behind a tunnel damping, which was named `explained` with no word of
// the friction (draw 120's probe, 5.4 ahead, had tied with it). A probe
// behind a step's effect by less than probe_behind_bic (no evidence
// either way) is named beside it: the damping stands, as the catalog
// comes first, and the verdict and diagnosis.json say what else explains
// the record alike and what would separate them.
TEST(Diagnose, AProbeJustBehindAStepIsNamedBesideIt) {
  const Case config = LoadConfig(
      testing::SourcePath("tests/data/coning_pitch_friction_draw122.yaml"));
  const Diagnosis d = Diagnose(config, DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kExplained) << text;
  ASSERT_EQ(d.steps.size(), 1u) << text;
  const DiagnosisStep& step = d.steps[0];
  EXPECT_EQ(step.effect, "tunnel_damping") << text;
  EXPECT_EQ(step.outside_alike.effect, "pitch_friction") << text;
  EXPECT_GE(step.outside_alike_bic, 0.0) << text;
  EXPECT_LT(step.outside_alike_bic, DiagnoseOptions().probe_behind_bic) << text;
  EXPECT_NE(d.verdict_text.find("alike: dry (Coulomb) friction about the "
                                "pitch axis alone"),
            std::string::npos)
      << text;
  EXPECT_NE(d.verdict_text.find("a run at another amplitude"),
            std::string::npos)
      << text;
  const nlohmann::json j = nlohmann::json::parse(DiagnosisJson(d, config));
  EXPECT_EQ(j["outside_catalog_alike"], nlohmann::json({"pitch_friction"}));
  EXPECT_EQ(j["steps"][0]["outside_alike"]["effect"], "pitch_friction");
  // Declared absent, the probe is never fitted and nothing is said of it.
  DiagnoseOptions options;
  options.absent = {"pitch_friction"};
  const Diagnosis without = Diagnose(config, options);
  ASSERT_FALSE(without.steps.empty()) << text;
  EXPECT_TRUE(without.steps[0].outside_alike.effect.empty())
      << FormatDiagnosis(without, {0.01, 0.01, 0.01});
}

// A probe outside the catalog alike beside the last step (no evidence
// either way) widens the final error bars to cover its model, as a
// catalog answer alike widens a probe's (WidenForCatalogAlike): on draw
// 151's cone with a dynamic pressure falling 1.75% over the run
// (tests/data/coning_q_drift_vary151.yaml) a bearing moment on its ridge
// came 1.2 below the pressure-drift probe and the final Cm_q was 3.5 of
// its errors off, the nominal fit's 3.1.
TEST(Diagnose, AProbeAlikeBesideTheLastStepWidensTheFinalErrorBars) {
  const Diagnosis d = DiagnoseConfig("coning_q_drift_vary151.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  ASSERT_FALSE(d.steps.empty()) << text;
  EXPECT_EQ(d.steps.back().outside_alike.effect, "pressure_drift") << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.1464}, {"Cm_q", -5.984}}, text);
  const std::vector<std::string>& pipeline = d.FinalFit().pipeline;
  EXPECT_TRUE(std::any_of(
      pipeline.begin(),
      pipeline.end(),
      [](const std::string& line) {
        return line.find("pressure_drift (outside the catalog, alike)") !=
               std::string::npos;
      }))
      << text;
}

// A widening of the final error bars never narrows them: the profile
// along a bearing moment's ridge starts from the model's own error bars,
// not from ones a probe alike (or a tie) widened first, which start it
// elsewhere on the curved ridge. On draw 149's 3-s run with a bearing
// moment fading at half a degree (tests/data/short_bearing_at_half_degree_
// vary149.yaml) the pressure-drift probe alike had narrowed the final
// Cm_alpha from 0.049 to 0.019; declared absent, nothing is said of it and
// the error bars are the profile's alone.
TEST(Diagnose, AProbeAlikeNeverNarrowsTheProfilesErrorBars) {
  const Case config = LoadConfig(testing::SourcePath(
      "tests/data/short_bearing_at_half_degree_vary149.yaml"));
  const Diagnosis d = Diagnose(config, DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  DiagnoseOptions options;
  options.absent = {"pressure_drift"};
  const Diagnosis without = Diagnose(config, options);
  ASSERT_FALSE(d.steps.empty()) << text;
  ASSERT_FALSE(without.steps.empty()) << text;
  EXPECT_EQ(d.steps.back().outside_alike.effect, "pressure_drift") << text;
  EXPECT_TRUE(without.steps.back().outside_alike.effect.empty()) << text;
  for (const char* name : {"Cm_alpha", "Cm_q"}) {
    const ParameterEstimate* with_probe = SharedEstimate(d.FinalFit(), name);
    const ParameterEstimate* alone = SharedEstimate(without.FinalFit(), name);
    ASSERT_NE(with_probe, nullptr) << name;
    ASSERT_NE(alone, nullptr) << name;
    EXPECT_GE(with_probe->standard_error, 0.999 * alone->standard_error)
        << name << "\n"
        << text;
  }
  ExpectFinalCovers(d, {{"Cm_alpha", -0.3372}, {"Cm_q", -2.827}}, text);
}

// The same friction on draw 141's cone of another body
// (tests/data/coning_pitch_friction_vary141.yaml): the two probes ranked
// first by their score were a reading lag, 34 of BIC behind a tunnel
// damping, and the yaw axis' friction, ahead of it but driving the motion
// (refused for its sign), and the damping was named alone, `explained`.
// A probe refused for its sign that fits better than every one of the
// right sign by more than ambiguity_bic sends the search on to the next
// two: the pitch axis' friction, 6.0 ahead of the damping, ties with it.
TEST(Diagnose, AProbeOfTheWrongSignThatFitsBestSendsTheSearchOn) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe's path as ALaggingPitchReading...'s; plain build";
  }
  const Case config = LoadConfig(
      testing::SourcePath("tests/data/coning_pitch_friction_vary141.yaml"));
  const Diagnosis d = Diagnose(config, DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  const nlohmann::json j = nlohmann::json::parse(DiagnosisJson(d, config));
  EXPECT_EQ(j["ambiguous_between"].get<std::set<std::string>>(),
            (std::set<std::string>{"tunnel_damping", "pitch_friction"}))
      << text;
  EXPECT_EQ(j["ambiguous_outside_catalog"], nlohmann::json({"pitch_friction"}))
      << text;
  EXPECT_NE(d.verdict_text.find("a run at another amplitude"),
            std::string::npos)
      << text;
}

// tools/diagnose_suite's `short` reading error at the second harmonic of
// roll (draw 22: theta_m += -0.0281 cos(2 phi + 0.7), psi_m += -0.0225
// sin(2 phi + 0.2)), kept as tests/data/short_second_roll_harmonic_
// draw22.csv. Section 5.2's reading error varies with roll "with no
// apparent symmetry"; the catalog's roll interaction keeps the first
// harmonics, and with a flow angularity beside it (six terms) had
// followed the second harmonic over the run's quarter revolution (on two
// runs, on every draw). The probe (four terms) fits it: not explained,
// nothing added, each term within 3 errors of the truth.
TEST(Diagnose, AReadingErrorAtTheSecondRollHarmonicIsNamed) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe's path as ALaggingPitchReading...'s; plain build";
  }
  const Diagnosis d = DiagnoseRecord("short_second_roll_harmonic_draw22.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  const double a = -0.028074;
  ExpectOutsideCatalog(d,
                       text,
                       "second_roll_harmonic",
                       {{"theta_cos_2phi", a * std::cos(0.7)},
                        {"theta_sin_2phi", -a * std::sin(0.7)},
                        {"psi_cos_2phi", 0.8 * a * std::sin(0.2)},
                        {"psi_sin_2phi", 0.8 * a * std::cos(0.2)}});
  EXPECT_EQ(d.outside_catalog.parameters.size(), 4u) << text;
}

// tools/diagnose_suite's `coning` tunnel stiffness + nonlinear damping +
// body yaw asymmetry (draw 26), kept as tests/data/coning_stiffness_
// damping_asymmetry_draw26.yaml. The friction about each axis reaches the
// noise alone (BIC 65.9 below the nominal fit) and outdid each catalog
// effect alone (26.3 at most); a noise-level probe had been taken for the
// last word, `not_explained` with Cm_q 31.7 of its errors off. Searched
// without probes, the catalog's effects explain the record 18.7 below the
// probe's model: that answer is taken (a nonlinear damping added, the
// asymmetry in a tie, the stiffness not excluded) and its error bars
// cover the truth.
TEST(Diagnose, ACatalogAnswerBelowAProbeAtTheNoiseIsTaken) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe's path as ALaggingPitchReading...'s; plain build";
  }
  const Diagnosis d =
      DiagnoseConfig("coning_stiffness_damping_asymmetry_draw26.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_NE(VerdictToString(d.verdict), std::string("not_explained")) << text;
  EXPECT_TRUE(d.outside_catalog.effect.empty()) << text;
  std::set<std::string> named = EffectIds(d.steps);
  for (const CandidateFit& k : d.ambiguous) named.insert(k.effect);
  for (const CandidateFit& k : d.not_excluded) named.insert(k.effect);
  for (const char* id :
       {"tunnel_stiffness", "nonlinear_damping", "asymmetric_body"}) {
    EXPECT_EQ(named.count(id), 1u) << id << "\n" << text;
  }
  ExpectFinalCovers(d, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}}, text);
}

// tools/diagnose_suite's `pair` tunnel damping (draw 22), kept as
// tests/data/pair_tunnel_damping_draw22.yaml: a damping stronger in yaw
// (t4 -2.89) than in pitch (t2 +2.13) on two runs pitching in one plane,
// whose small yaw rates the yaw axis's dry friction damps alike; the probe
// comes 10.3 below the damping, and fitted on either run each model
// predicts the other alike. The verdict is the probe's, `not_explained`,
// and the final model the nominal fit's, whose Cm_q (-3.39 +- 0.015) was
// 137 of its errors from the truth (-5.5) the damping's model holds
// (-5.14 +- 0.64). Its error bars now cover that model at its Akaike
// weight against the probe's (0.035): Cm_q +- 0.35.
TEST(Diagnose, ACatalogEffectAProbeOutdidWidensTheFinalErrorBars) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe's path as ALaggingPitchReading...'s; plain build";
  }
  const Diagnosis d = DiagnoseConfig("pair_tunnel_damping_draw22.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_FALSE(d.outside_catalog.effect.empty()) << text;
  EXPECT_EQ(d.outdone_by_probe, std::vector<std::string>({"tunnel_damping"}))
      << text;
  const ParameterEstimate* cm_q = SharedEstimate(d.FinalFit(), "Cm_q");
  ASSERT_NE(cm_q, nullptr) << text;
  ASSERT_EQ(d.model_standard_errors.count("Cm_q"), 1u) << text;
  EXPECT_GT(cm_q->standard_error, 10.0 * d.model_standard_errors.at("Cm_q"))
      << text;
  EXPECT_LT(std::abs(cm_q->value + 5.5), 10.0 * cm_q->standard_error) << text;
  const nlohmann::json j = nlohmann::json::parse(DiagnosisJson(
      d,
      LoadConfig(
          testing::SourcePath("tests/data/pair_tunnel_damping_draw22.yaml"))));
  EXPECT_EQ(j["outdone_by_probe"], nlohmann::json({"tunnel_damping"}));
}

// tools/diagnose_suite's `short` calibration error growing as the angle's
// signed square (draw 24), kept as tests/data/short_calibration_signed_
// square_draw24.csv: the catalog's cube is named for it, and with the gain
// it leaves open beside it Cm_alpha had been 3.5 of its errors off. The
// cube leaves the signed square open too (OpenForms): fitted beside the
// final model, it is not excluded, and the final error bars cover it.
TEST(Diagnose, ACalibrationErrorsSignedSquareIsLeftOpenBesideTheCube) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe's path as ALaggingPitchReading...'s; plain build";
  }
  const Diagnosis d =
      DiagnoseRecord("short_calibration_signed_square_draw24.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(EffectIds(d.steps),
            std::set<std::string>({"calibration_nonlinearity"}))
      << text;
  EXPECT_TRUE(std::any_of(
      d.open_terms.begin(),
      d.open_terms.end(),
      [](const CandidateFit& k) { return k.effect == "calibration_square"; }))
      << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.23}}, text);
}

// tools/diagnose_suite's calibration error growing as the angle's signed
// square less its line over -8..8 deg (theta_cal2 = t, psi_cal2 = -t,
// cal_range 8), another form than the catalog's cube. On draw 53's coning
// run (tests/data/coning_calibration_signed_square_draw53.csv, t =
// -0.0822) the cube named for it left a difference of the two readings'
// gains, an elliptical look, and a tunnel stiffness, a body asymmetry and
// a pitch gain tied beside it (`ambiguous`, 4 draws of 14); on the `pair`
// records of draws 24 and 26-28 (t = -0.125, 0.137, 0.127, -0.128) the
// cube dragged the coefficients or left its bounds, and the records ended
// `not_explained` (the tests with the catalog's own forms only, below).
// The effect's other form (Effect::other_form, tried where the record
// favors it by 10 in BIC; its range held at the readings' largest angle)
// names each: `explained`, the square within 3 of its errors.
TEST(Diagnose, ACalibrationErrorsSignedSquareIsNamedInItsOtherForm) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "two runs; plain build";
  const std::vector<std::pair<Diagnosis, double>> records = {
      {DiagnoseRecord("coning_calibration_signed_square_draw53.csv"), -0.0822},
      {DiagnoseConfig("pair_calibration_signed_square_draw24.yaml"), -0.125},
      {DiagnoseConfig("pair_calibration_signed_square_draw26.yaml"), 0.137},
      {DiagnoseConfig("pair_calibration_signed_square_draw27.yaml"), 0.127},
      {DiagnoseConfig("pair_calibration_signed_square_draw28.yaml"), -0.128}};
  for (const auto& [d, t] : records) {
    const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
    ExpectNamedExactly(d,
                       {"calibration_nonlinearity"},
                       {{"Cm_alpha", -0.23},
                        {"Cm_q", -5.5},
                        {"theta_cal2", t},
                        {"psi_cal2", -t}},
                       text);
    const ParameterEstimate* range = SharedEstimate(d.FinalFit(), "cal_range");
    ASSERT_NE(range, nullptr) << text;
    EXPECT_NEAR(range->value, 8.0, 0.5) << text;
    const ParameterEstimate* cube = SharedEstimate(d.FinalFit(), "theta_cal3");
    ASSERT_NE(cube, nullptr) << text;
    EXPECT_FALSE(cube->free) << text;
  }
}

// A calibration range the config gives is the bench's and is kept
// (HoldCalibrationRange). Draw 161's `pair` signed square
// (tests/data/pair_calibration_signed_square_draw161.yaml, t = 0.1147,
// sigma: auto) was calibrated over -8..8 deg, and its readings reach 9.7
// deg: with the range held there, the two lines' difference was left, a
// pitch gain off the yaw gain, and after the calibration a bearing moment,
// a tunnel stiffness and that gain tied (BIC lower by 48-52). Given
// `cal_range: 8`, the calibration alone explains the record.
TEST(Diagnose, TheConfigsCalibrationRangeIsTheBenchsOwn) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "two runs; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_calibration_signed_square_draw161.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  const double t = 0.1147;
  ExpectNamedExactly(d,
                     {"calibration_nonlinearity"},
                     {{"Cm_alpha", -0.1415},
                      {"Cm_q", -6.818},
                      {"theta_cal2", t},
                      {"psi_cal2", -t}},
                     text);
  const ParameterEstimate* range = SharedEstimate(d.FinalFit(), "cal_range");
  ASSERT_NE(range, nullptr) << text;
  EXPECT_EQ(range->value, 8.0) << text;
}

// The same form on draw 142's pair (tests/data/pair_calibration_signed_
// square_vary142.yaml, t = 0.0718, sigma: auto). The record put the signed
// square only 5.3 below the cube in BIC, and the cube, fitting the yaw
// reading's error over the 0.76 deg that yaw spans with psi_cal3 = 7.4 +-
// 1.7, went past its bound (0.0256 deg against 0.0254): nothing was
// added, the pitch error taken for noise (`noise_level`, theta's noise
// held at 0.0257 deg). A form lower in BIC at all stands in for an own
// form out of its bounds: the calibration is named in the other form.
// Nor does it go back to the cube beside the later steps (BackToOwnForms)
// while the cube lies outside its bounds there: it had, and the pitch
// noise was held again with the cube's residual in it (0.0131 deg).
TEST(Diagnose, AnOtherFormLowerInBicStandsInForAnOwnFormOutOfItsBounds) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "two runs; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_calibration_signed_square_vary142.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(d,
                     {"calibration_nonlinearity"},
                     {{"Cm_alpha", -0.1955}, {"Cm_q", -6.121}},
                     text);
  const ParameterEstimate* square = SharedEstimate(d.FinalFit(), "theta_cal2");
  ASSERT_NE(square, nullptr) << text;
  EXPECT_TRUE(square->free) << text;
  EXPECT_GT(square->value, 0.0) << text;
  EXPECT_TRUE(d.noise_held) << text;
  EXPECT_LT(DiagnosedNoise(d, {}).theta, 0.012) << text;  // simulated: 0.01
}

// tools/diagnose_suite's `pair` Magnus moment + nonlinear damping + cubic
// calibration error (draw 52; tests/data/pair_magnus_damping_calibration_
// draw52.yaml). With the Magnus moment alone beside it the signed square
// came 11.2 ahead of the cube in BIC and was taken; once the damping was
// in, the cube was 8.3 lower, but the form stayed, and the cube's terms,
// which the suite judges, were not in the final model. An effect in its
// other form goes back to its own where the record no longer favors the
// other by the round's margin (BackToOwnForms): the cube is named, within
// 3 of its errors.
TEST(Diagnose, AnEffectInItsOtherFormGoesBackWhenLaterStepsFavorItsOwn) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "two runs; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_magnus_damping_calibration_draw52.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_TRUE(EffectIds(d.steps).count("calibration_nonlinearity")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("nonlinear_damping")) << text;
  ExpectFinalCovers(
      d, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}, {"theta_cal3", -0.0394}}, text);
  const ParameterEstimate* square = SharedEstimate(d.FinalFit(), "theta_cal2");
  ASSERT_NE(square, nullptr) << text;
  EXPECT_FALSE(square->free) << text;
}

// tools/diagnose_suite's `pair` signed-square calibration error (draws 27
// and 26), kept as tests/data/pair_calibration_signed_square_draw27.yaml
// and _draw26.yaml: the cube is named, and Cm_alpha was -0.23028 +- 3.9e-5
// (7.3 of its errors off) and -0.23034 +- 4.3e-5 (7.9). The gain the cube
// leaves open lowers BIC by 35 and 28 beside it, but moved the cube past
// its bound (0.256 +- 0.016 and 0.277 +- 0.017 deg at 8.1 deg, bound
// 0.242); with the form beside it the cube is not judged alone (the two
// are one calibration curve), and the final error bars cover the gain's
// model. Draw 26's cube itself came in through the third search
// (AThirdSearchJudgesEveryBoundWithinItsErrors). With the catalog's own
// forms only: the effect's other form names these records
// (ACalibrationErrorsSignedSquareIsNamedInItsOtherForm).
TEST(Diagnose, AnOpenFormThatMovesTheNamedOneAlongItsRidgeIsWeighed) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe's path as ALaggingPitchReading...'s; plain build";
  }
  for (const char* file : {"pair_calibration_signed_square_draw27.yaml",
                           "pair_calibration_signed_square_draw26.yaml"}) {
    const Diagnosis d = DiagnoseConfigOwnForms(file);
    const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
    EXPECT_EQ(EffectIds(d.steps),
              std::set<std::string>({"calibration_nonlinearity"}))
        << file << "\n"
        << text;
    const auto gain = std::find_if(
        d.open_terms.begin(), d.open_terms.end(), [](const CandidateFit& k) {
          return k.effect == "reading_gain";
        });
    ASSERT_NE(gain, d.open_terms.end()) << file << "\n" << text;
    EXPECT_GT(gain->bic_drop, 10.0) << file << "\n" << text;
    EXPECT_NE(text.find("lowers BIC beside it"), std::string::npos) << text;
    ExpectFinalCovers(d, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}}, text);
  }
}

// A pitch reading drifting 0.015 deg/s on one 3-s run: over its 90 deg of
// roll a roll-synchronous reading error follows it nearly as well, with
// twice the parameters. A roll-locked effect on less than a revolution is
// a drift in time already, so the fitted drift need not beat it by the
// ambiguity margin: when it does better by drift_bic (2), the verdict is
// not_explained (it had been `ambiguous` on 8 seeds of 8; now
// not_explained on all 8).
TEST(Diagnose, OneRunNamesADriftOfThePitchReading) {
  const std::string dir = testing::ScratchDirectory("diagnose_pitch_drift");
  for (std::uint64_t seed : {3, 4}) {
    const std::vector<std::string> files =
        ShortRunWith(dir + "/run0.csv", "theta_drift", 0.015, seed);
    const Diagnosis d = Diagnose(ShortConfig(files), DiagnoseOptions());
    const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
    EXPECT_EQ(VerdictToString(d.verdict), std::string("not_explained")) << text;
    EXPECT_TRUE(d.steps.empty()) << text;
    EXPECT_EQ(d.outside_catalog.effect, "reading_drift") << text;
  }
}

// A yaw stiffness 0.3% off the pitch one in the body (the asymmetric
// program's Cn_beta untied from Cm_alpha) in two 3-s runs (30 deg/s and 8
// deg, 60 deg/s and 4 deg). The switch to the asymmetric program keeps the
// symmetric relations tied (model_conversion.h), so a product of inertia
// costs I_zx alone and cannot hide the asymmetry behind freed images (it
// had ended "explained: a Magnus moment" with Cn_beta free under I_zx's
// name); the asymmetric body is named, Cn_beta within 3 errors of the
// truth, and every step reports its values as the final (asymmetric)
// model has them (it had printed "a Magnus moment ()").
TEST(Diagnose, NamesABodyFixedYawAsymmetryInTheAsymmetricProgram) {
  const std::string dir = testing::ScratchDirectory("diagnose_yaw_stiffness");
  double truth = 0.0;
  const std::vector<std::string> files = TwoShortRuns(
      dir, 31, [&truth](Case* c) { truth = UntieBodyYawStiffness(c, 1.003); });
  const Diagnosis d = Diagnose(ShortConfig(files), DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.FinalFit().model, ModelKind::kAsymmetric) << text;
  EXPECT_EQ(VerdictToString(d.verdict), std::string("explained")) << text;
  ASSERT_EQ(d.steps.size(), 1u) << text;
  EXPECT_EQ(d.steps[0].effect, "asymmetric_body") << text;
  bool found = false;
  for (const ParameterEstimate& e : d.final_parameters) {
    if (e.name != "Cn_beta") continue;
    found = true;
    EXPECT_TRUE(e.free) << text;
    EXPECT_NEAR(e.value, truth, 3.0 * e.standard_error) << text;
  }
  EXPECT_TRUE(found) << text;
  for (const DiagnosisStep& s : d.steps) {
    EXPECT_FALSE(s.parameters.empty()) << s.effect << "\n" << text;
  }
  EXPECT_EQ(text.find("()"), std::string::npos) << text;
  // With the body's own yaw stiffness free, a tunnel stiffness is one
  // combination with it and Cm_alpha (Eq. 43): an exact twin, which no
  // fit beside the model weighs (it had widened Cm_alpha 2700-fold).
  EXPECT_EQ(std::count(d.near_twins.begin(),
                       d.near_twins.end(),
                       std::string("tunnel_stiffness")),
            0)
      << text;
}

// The true Cm_alpha and Cm_q of the short runs.
const std::map<std::string, double> kShortCoefficients = {{"Cm_alpha", -0.23},
                                                          {"Cm_q", -5.5}};

// `d` explains the record with the true effects `truth`, named or in a
// tie, adds none other, and its final model covers the true Cm_alpha and
// Cm_q (-0.23, -5.5) within 3 standard errors.
void ExpectTruthAddedOrTied(const Diagnosis& d,
                            const std::set<std::string>& truth) {
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_TRUE(d.verdict == Verdict::kExplained ||
              d.verdict == Verdict::kAmbiguous)
      << text;
  std::set<std::string> named;
  for (const DiagnosisStep& s : d.steps) {
    EXPECT_TRUE(truth.count(s.effect)) << s.effect << "\n" << text;
    named.insert(s.effect);
  }
  for (const std::string& id : TiedIds(d)) named.insert(id);
  for (const std::string& id : truth) {
    EXPECT_TRUE(named.count(id)) << id << "\n" << text;
  }
  ExpectFinalCovers(d, kShortCoefficients, text);
}

// `d` names a tunnel damping and a Magnus moment and either a flow
// angularity (`explained`) or a tie of the angularity with a roll reading
// error (`ambiguous`, neither added): over the quarter revolution of roll
// of a 3-s run at 30 deg/s a first harmonic of roll holds an offset, and
// the two fit alike but for the reading error's two more terms (TieGap).
// The model with the angularity holds each of `truths` within 3 standard
// errors: the final one; or the tie's alternative with it; or, the tie
// being the last step, the final model the truths but the angularity's
// (theta_T, psi_T), which its fit at the tie holds. A final model in the
// asymmetric program (a body asymmetry taken and dropped again) holds the
// Magnus moment as Cm_p_beta.
void ExpectDampingMagnusWithAngularityOrItsTwin(
    const Diagnosis& d,
    std::map<std::string, double> truths,
    const std::string& text) {
  const auto magnus = truths.find("Cm_p_alpha");
  if (magnus != truths.end() &&
      SharedEstimate(d.FinalFit(), "Cm_p_alpha") == nullptr) {
    truths["Cm_p_beta"] = magnus->second;
    truths.erase(magnus);
  }
  if (d.verdict == Verdict::kExplained) {
    ExpectNamedExactly(
        d, {"flow_angularity", "magnus", "tunnel_damping"}, truths, text);
    return;
  }
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.steps),
            (std::set<std::string>{"magnus", "tunnel_damping"}))
      << text;
  EXPECT_EQ(EffectIds(d.ambiguous),
            (std::set<std::string>{"flow_angularity", "roll_interaction"}))
      << text;
  const auto with_angularity = std::find_if(
      d.alternatives.begin(),
      d.alternatives.end(),
      [](const AlternativeModel& m) { return m.effect == "flow_angularity"; });
  if (with_angularity != d.alternatives.end()) {
    EXPECT_TRUE(with_angularity->check.at_noise_level) << text;
    ExpectCovers(with_angularity->parameters, truths, text);
    return;
  }
  std::map<std::string, double> offsets;
  for (const char* name : {"theta_T", "psi_T"}) {
    const auto truth = truths.find(name);
    if (truth == truths.end()) continue;
    offsets.insert(*truth);
    truths.erase(truth);
  }
  ExpectFinalCovers(d, truths, text);
  const auto tied = std::find_if(
      d.ambiguous.begin(), d.ambiguous.end(), [](const CandidateFit& k) {
        return k.effect == "flow_angularity";
      });
  ASSERT_NE(tied, d.ambiguous.end()) << text;
  ExpectCovers(tied->parameters, offsets, text);
}

// tools/diagnose_suite's `short` roll reading error alone (draw 65:
// theta 0.0162 cos phi + 0.0097 sin phi, psi -0.0129 cos phi - 0.0065 sin
// phi deg), kept as tests/data/short_roll_error_draw65.csv: 47 samples over
// 90 deg of roll. It was named a flow angularity, `explained`: the
// angularity lowered BIC 11.6 more than the reading error, of which 9.9
// were the reading error's two more terms. Judged by the fits alone
// (TieGap), the two tie: `ambiguous`, neither added, a run at another spin
// rate named to separate them; the reading error's fit holds the truth.
TEST(Diagnose, ARollReadingErrorOverAQuarterRevolutionTiesWithAnAngularity) {
  const Diagnosis d = DiagnoseRecord("short_roll_error_draw65.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_EQ(EffectIds(d.ambiguous),
            (std::set<std::string>{"flow_angularity", "roll_interaction"}))
      << text;
  EXPECT_NE(text.find("a run at another spin rate would separate them"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("a first harmonic of roll holds an offset"),
            std::string::npos)
      << text;
  const auto error = std::find_if(
      d.ambiguous.begin(), d.ambiguous.end(), [](const CandidateFit& k) {
        return k.effect == "roll_interaction";
      });
  ASSERT_NE(error, d.ambiguous.end()) << text;
  ExpectCovers(error->parameters,
               {{"theta_cos_phi", 0.016186},
                {"theta_sin_phi", 0.0097114},
                {"psi_cos_phi", -0.012949},
                {"psi_sin_phi", -0.0064743}},
               text);
  ExpectFinalCovers(d, kShortCoefficients, text);
}

// A calibration error in another form than the catalog's cube: each
// reading errs by `size` times the angle's signed square (deg^2 / 25)
// less its linear part over a calibration from -8 to 8 deg (the report's
// linear calibration fit takes that into the gain), pitch and yaw with
// opposite signs. The cube named for it matches its third harmonic but
// not its fundamental: a gain error of the amplitude, which the known
// cubic stiffness turns into a Cm_alpha 5-8 of its errors off (the
// diagnose suite's form cases). The cube's form leaves that gain open
// (Effect::leaves_open); freed beside the final model, where the record
// cannot exclude it, the final error bars cover that fit too. Seeds: the
// suite's short condition at 1.3 times the noise.
TEST(Diagnose, ACalibrationErrorOfAnotherFormLeavesTheGainOpen) {
  constexpr double kSize = 0.06;
  auto reading = [](double angle) {
    return kSize * (angle * std::abs(angle) - 6.0 * angle) / 25.0;
  };
  const std::vector<std::uint64_t> seeds =
      testing::kSanitized ? std::vector<std::uint64_t>{1}
                          : std::vector<std::uint64_t>{1, 2, 3};
  int opened = 0;
  for (const std::uint64_t seed : seeds) {
    const std::string dir = testing::ScratchDirectory(
        "diagnose_signed_square_" + std::to_string(seed));
    const Case truth = UntrimmedShortTruth(30.0);
    Case simulated = truth;
    simulated.solver.step = 0.002;
    TimeHistory data =
        SimulateAt(simulated, simulated.Values(), testing::ShortRecordTimes());
    for (int i = 0; i < data.size(); ++i) {
      data.theta[i] += reading(data.theta[i]);
      data.psi[i] -= reading(data.psi[i]);
    }
    NoiseOptions noise;
    noise.enabled = true;
    noise.sigma = {0.01, 0.01, 0.01};
    noise.seed = seed;
    AddNoise(noise, &data);
    WriteTimeHistory(dir + "/data.csv", data);
    const Diagnosis d =
        Diagnose(ShortConfig({dir + "/data.csv"}), DiagnoseOptions());
    const std::string text = "seed " + std::to_string(seed) + "\n" +
                             FormatDiagnosis(d, {0.01, 0.01, 0.01});
    // Named, or not explained: never another effect.
    for (const DiagnosisStep& s : d.steps) {
      EXPECT_EQ(s.effect, "calibration_nonlinearity") << text;
    }
    ExpectFinalCovers(d, kShortCoefficients, text);
    if (EffectIds(d.open_terms).count("reading_gain")) {
      ++opened;
      EXPECT_NE(text.find("left open, the final error bars cover it: "
                          "reading_gain"),
                std::string::npos)
          << text;
    }
  }
  EXPECT_GE(opened, 1);
}

// Three effects on one short run (a Magnus moment, a nonlinear damping, a
// calibration nonlinearity): at the first step an asymmetric body lowers
// BIC as much as the Magnus moment does. Followed first, it leaves the
// record unexplained whatever comes after; the other branch of the tie,
// the Magnus moment, explains the record with the other two, and is what
// the diagnosis gives, the branch left named among the rejected (without
// the second branch: not_explained). The noise decides which branches get
// through: of seeds 1-24 of this record, most end `ambiguous` (either
// branch explains it with the other two: at one spin rate the two are
// alike), a few end not_explained (neither does); seed 21 is one where
// only the second does.
TEST(Diagnose, FollowsTheOtherBranchOfATieThatLeavesTheRecordUnexplained) {
  const std::string dir = testing::ScratchDirectory("diagnose_tie_branch");
  Case truth = ShortTruth(30.0);
  const std::vector<std::pair<std::string, double>> hidden = {
      {"Cm_0", 0.0},
      {"Cn_0", 0.0},
      {"Cm_p_alpha", 2.9},
      {"Cm_q_delta2", 494.0},
      {"theta_cal3", 0.027},
      {"psi_cal3", -0.027}};
  SetValues(&truth, hidden);
  const std::string data = SimulateShort(truth, dir + "/data.csv", 21);
  // Fitted jointly (Jointly), the body yaw asymmetry with the nonlinear
  // damping and the calibration error reaches the noise as well: a tie
  // with the Magnus moment. The branches are what this test is about.
  DiagnoseOptions branches;
  branches.joint_sets = false;
  const Diagnosis d = Diagnose(ShortConfig({data}), branches);
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(VerdictToString(d.verdict), std::string("explained")) << text;
  const std::set<std::string> added = EffectIds(d.steps);
  EXPECT_TRUE(added.count("magnus")) << text;
  EXPECT_FALSE(added.count("asymmetric_body")) << text;
  const bool left =
      ListedWith(d.rejected, "asymmetric_body", "whatever followed it");
  bool outdone = false;
  for (const CandidateFit& k : d.rejected) {
    outdone |=
        k.rejected.find("catalog's effects together") != std::string::npos;
  }
  EXPECT_TRUE(left) << text;
  // On the Magnus branch a reading lag had outdone the Magnus moment at the
  // first step, and only the catalog's three effects together (CatalogAlone)
  // kept the record from `not_explained`. That lag was a lead (theta_lag =
  // -0.033 +- 0.0092 s), no filter's: a probe of the wrong sign is no
  // answer (WrongSign), and the catalog's search goes on undisturbed.
  EXPECT_FALSE(outdone) << text;
  EXPECT_TRUE(d.outside_catalog.effect.empty()) << text;
  // The joint answer (AdoptsEffectsThatEarnTheirPlaceOnlyTogether covers
  // joint sets in the sanitized build): plain build only, for time.
  if (testing::PlainBuildOnly()) return;
  ExpectTruthAddedOrTied(
      Diagnose(ShortConfig({data}), DiagnoseOptions()),
      {"magnus", "nonlinear_damping", "calibration_nonlinearity"});
}

// tools/diagnose_suite's `short` bearing moment + calibration error + roll
// torque (Cm_bearing = -0.02 at 1 deg, theta_cal3 = -psi_cal3 = 0.0371,
// Cl_0 = -2.28e-7; draw 0), kept as tests/data/short_bearing_calibration_
// roll_torque_seed0.csv. A drifting dynamic pressure (a probe with no
// sign to check) lowers BIC most at the second step, but the catalog's
// effects together explain the record 130 below it (CatalogAlone): the
// bearing moment and the calibration error are added, the roll torque
// ties with the roll damping and a tunnel damping (one spin rate), and
// the probe is reported as outdone.
TEST(Diagnose, TheCatalogsEffectsTogetherOutdoAProbeThatLedARound) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe's path as ALaggingPitchReading...'s; plain build";
  }
  const Diagnosis d =
      DiagnoseRecord("short_bearing_calibration_roll_torque_seed0.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(
      EffectIds(d.steps),
      std::set<std::string>({"bearing_moment", "calibration_nonlinearity"}))
      << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("roll_torque")) << text;
  EXPECT_TRUE(d.outside_catalog.effect.empty()) << text;
  EXPECT_TRUE(
      ListedWith(d.rejected, "pressure_drift", "catalog's effects together"))
      << text;
  for (const auto& [name, truth] : {std::pair{"Cm_bearing", -0.02},
                                    {"theta_cal3", 0.0371},
                                    {"psi_cal3", -0.0371}}) {
    const ParameterEstimate* e = SharedEstimate(d.FinalFit(), name);
    ASSERT_NE(e, nullptr) << name << "\n" << text;
    EXPECT_NEAR(e->value, truth, 3.0 * e->standard_error) << name << "\n"
                                                          << text;
  }
}

// A roll-synchronous reading error ties with a trim moment on one slow
// run, and a Magnus moment is needed whichever of them is in the model:
// the Magnus moment is adopted, the pair stays ambiguous, and the complete
// model with each is reported. (Before, a trim moment that the search
// followed had been named with the Magnus moment: a confident wrong
// answer.)
TEST(Diagnose, AdoptsWhatATieLeavesUndisputed) {
  const std::string dir = testing::ScratchDirectory("diagnose_after_tie");
  Case truth = UntrimmedShortTruth(30.0);
  const std::vector<std::pair<std::string, double>> hidden = {
      {"Cm_p_alpha", 3.0},
      {"theta_cos_phi", 0.03},
      {"theta_sin_phi", -0.02},
      {"psi_cos_phi", 0.025},
      {"psi_sin_phi", 0.012}};
  SetValues(&truth, hidden);
  const std::string data = SimulateShort(truth, dir + "/data.csv", 31);
  const Case config = ShortConfig({data});
  const Diagnosis d = Diagnose(config, DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(VerdictToString(d.verdict), std::string("ambiguous")) << text;
  ASSERT_EQ(d.steps.size(), 1u) << text;
  EXPECT_EQ(d.steps[0].effect, "magnus") << text;
  const std::set<std::string> tied = EffectIds(d.ambiguous);
  EXPECT_TRUE(tied.count("roll_interaction")) << text;
  ASSERT_EQ(d.alternatives.size(), 2u) << text;
  bool checked = false;
  for (const AlternativeModel& a : d.alternatives) {
    // The other may be a drift in time (over 89 deg of roll), fitted as a
    // drift of the readings: a straight line, short of the noise.
    if (a.effect != "roll_interaction") continue;
    EXPECT_TRUE(a.check.at_noise_level) << text;
    for (const ParameterEstimate& e : a.parameters) {
      if (e.name != "Cm_p_alpha") continue;
      EXPECT_NEAR(e.value, 3.0, 3.0 * e.standard_error) << text;
      checked = true;
    }
  }
  EXPECT_TRUE(checked) << text;
  const nlohmann::json j = nlohmann::json::parse(DiagnosisJson(d, config));
  EXPECT_EQ(j["effects_added"], nlohmann::json({"magnus"}));
  EXPECT_EQ(j["alternatives"].size(), 2u);
}

// Three effects near the noise on one slow run: a tunnel stiffness (seen
// there only through the roll it drives, as a roll torque or a tunnel
// damping would drive it), a roll-synchronous reading error and a flow
// angularity (over 90 deg of roll both alike a trim moment). Each tie the
// record leaves open is reported, and nothing in doubt is added.
TEST(Diagnose, ReportsEveryTieTheRecordLeavesOpen) {
  const std::string dir = testing::ScratchDirectory("diagnose_two_ties");
  Case truth = UntrimmedShortTruth(30.0);
  const std::vector<std::pair<std::string, double>> hidden = {
      {"t1", 0.00046},
      {"t3", -0.00016},
      {"theta_cos_phi", 0.0129},
      {"theta_sin_phi", -0.0077},
      {"psi_cos_phi", 0.0103},
      {"psi_sin_phi", 0.0051},
      {"theta_T", -0.0076},
      {"psi_T", 0.0086}};
  SetValues(&truth, hidden);
  const std::string data = SimulateShort(truth, dir + "/data.csv", 41);
  const Case config = ShortConfig({data});
  const Diagnosis d = Diagnose(config, DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(VerdictToString(d.verdict), std::string("ambiguous")) << text;
  const std::set<std::string> truths = {
      "tunnel_stiffness", "roll_interaction", "flow_angularity"};
  for (const DiagnosisStep& s : d.steps) {
    EXPECT_TRUE(truths.count(s.effect)) << s.effect << "\n" << text;
  }
  EXPECT_FALSE(d.later_ties.empty()) << text;
  const nlohmann::json j = nlohmann::json::parse(DiagnosisJson(d, config));
  std::set<std::string> named(j["effects_added"].begin(),
                              j["effects_added"].end());
  named.insert(j["ambiguous_between"].begin(), j["ambiguous_between"].end());
  EXPECT_TRUE(named.count("tunnel_stiffness")) << text;
  // The reading error as itself or as its roll-locked twin.
  EXPECT_TRUE(named.count("roll_interaction") || named.count("trim_moment"))
      << text;
  EXPECT_EQ(j["ambiguous_groups"].size(), 1 + d.later_ties.size());
}

// Two runs at 30 and 60 deg/s, far below the pitch frequency, cannot tell a
// roll-synchronous reading error from a trim moment: with a nonlinear
// damping beside the reading error, the damping is adopted and the
// reading error is never replaced by a trim moment (it had been on 2
// noise seeds of 8 in the suite's generator, its rival refused at the
// first step while the damping was still missing).
TEST(Diagnose, SlowRunsNeverNameOneOfTheRollLockedTwins) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "the roll-locked tie's path as in "
                    "ARollLockedEffectTiesWithADrift...; plain build";
  }
  const std::string dir = testing::ScratchDirectory("diagnose_twins");
  const int seeds = 3;
  for (int seed = 0; seed < seeds; ++seed) {
    const std::vector<std::string> files = TwoShortRuns(
        dir + "/" + std::to_string(seed), 50 + 10 * seed, [](Case* c) {
          const std::vector<std::pair<std::string, double>> hidden = {
              {"theta_cos_phi", 0.0145},
              {"theta_sin_phi", -0.0087},
              {"psi_cos_phi", 0.0116},
              {"psi_sin_phi", 0.0058},
              {"Cm_q_delta2", 150.0}};
          SetValues(c, hidden);
        });
    const Diagnosis d = Diagnose(ShortConfig(files), DiagnoseOptions());
    const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
    const std::set<std::string> added = EffectIds(d.steps);
    EXPECT_FALSE(added.count("trim_moment")) << seed << "\n" << text;
    EXPECT_TRUE(added.count("nonlinear_damping")) << seed << "\n" << text;
    if (d.verdict == Verdict::kAmbiguous) {
      std::set<std::string> tied;
      for (const CandidateFit& a : d.ambiguous) tied.insert(a.effect);
      EXPECT_TRUE(tied.count("roll_interaction")) << seed << "\n" << text;
    } else {
      EXPECT_EQ(d.verdict, Verdict::kExplained) << seed << "\n" << text;
    }
  }
}

// A coning run (3 s, 8 deg, the pitch plane turning at 78 deg/s) with a
// roll reading error (0.012 deg) and a nonlinear damping (Cm_q_delta2 =
// 98.5), each near the detection limit: tools/diagnose_suite's record of
// that case (draw 0), kept as tests/data/coning_roll_error_nonlinear_
// damping.csv. At the first step a trim moment ties with a flow
// angularity; followed, it leaves the damping predicting nothing held out
// and the record unexplained. The other branch explains the record with a
// tie of its own (a flow angularity or the reading error) and the damping
// added: that is the answer (it had been not_explained), the trim moment
// among the rejected.
TEST(Diagnose, TakesTheOtherBranchOfATieWhenItEndsAmbiguous) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "FollowsTheOtherBranchOfATie...'s path; plain build";
  }
  Case c = ShortConfig({testing::SourcePath(
      "tests/data/coning_roll_error_nonlinear_damping.csv")});
  // Fitted jointly, a trim moment with the damping reaches the noise as
  // well: a tie with the reading error. The branches are what this test is
  // about.
  DiagnoseOptions branches;
  branches.joint_sets = false;
  const Diagnosis d = Diagnose(c, branches);
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  const std::set<std::string> tied = EffectIds(d.ambiguous);
  EXPECT_TRUE(tied.count("roll_interaction")) << text;
  EXPECT_FALSE(tied.count("trim_moment")) << text;
  ASSERT_EQ(d.steps.size(), 1u) << text;
  EXPECT_EQ(d.steps[0].effect, "nonlinear_damping") << text;
  // The complete model with each tied effect explains the record.
  ASSERT_EQ(d.alternatives.size(), 2u) << text;
  for (const auto& a : d.alternatives) {
    EXPECT_TRUE(a.check.at_noise_level) << a.effect << "\n" << text;
  }
  for (const ParameterEstimate& e : d.final_parameters) {
    if (e.name == "Cm_q_delta2")
      EXPECT_NEAR(e.value, 98.5, 3 * e.standard_error);
    if (e.name == "Cm_q") EXPECT_NEAR(e.value, -5.5, 3 * e.standard_error);
  }
  EXPECT_TRUE(ListedWith(d.rejected, "trim_moment", "whatever followed it"))
      << text;
  ExpectTruthAddedOrTied(Diagnose(c, DiagnoseOptions()),
                         {"roll_interaction", "nonlinear_damping"});
}

// An effect outside the catalog (a pitch reading that drifts 0.05 deg
// over the Table 6 record) ends not_explained, with at most one effect
// added, and the residuals described (the trend) for the engineer.
TEST(Diagnose, SaysWhenNoCatalogEffectExplains) {
  const std::string dir = testing::ScratchDirectory("diagnose_drift");
  Simulate(Truth(), dir + "/clean.csv", 8);
  TimeHistory data = ReadTimeHistory(dir + "/clean.csv");
  for (int i = 0; i < data.size(); ++i) data.theta[i] += 0.001 * data.t[i];
  WriteTimeHistory(dir + "/data.csv", data);
  const Diagnosis d =
      Diagnose(FitConfig(Truth(), dir + "/data.csv"), DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(VerdictToString(d.verdict), std::string("not_explained")) << text;
  // Nothing is adopted: the final model is the nominal fit, and whatever
  // lowered the residual on the way is reported as partial.
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_EQ(d.fits.size(), 1 + d.partial.size());
  EXPECT_EQ(&d.FinalFit(), &d.fits.front());
  ASSERT_EQ(d.final_parameters.size(), d.fits.front().parameters.size());
  for (size_t i = 0; i < d.final_parameters.size(); ++i) {
    EXPECT_EQ(d.final_parameters[i].value, d.fits.front().parameters[i].value);
  }
  if (!d.partial.empty()) {
    EXPECT_NE(d.verdict_text.find("not adopted"), std::string::npos) << text;
    EXPECT_NE(text.find("explains part, not adopted"), std::string::npos);
  }
  EXPECT_NE(d.residual_description.find("trend in time"), std::string::npos)
      << text;
}

// A tunnel stiffness, a body yaw asymmetry (Cn_beta 0.2% off -Cm_alpha) and
// a nonlinear damping on one 3-s run at 30 deg/s. On this run the tunnel
// stiffness shows through the roll it drives, as a roll torque would; at the
// first step, with the other two still missing, the roll torque lowers BIC
// by more than 10 below it (no tie), and the search used to end
// "explained" by a roll torque, the asymmetry and the damping (noise seeds
// 1 and 7 of 1-8; the others tie the roll torque with a tunnel damping).
// Swapped in with the other two in (rival_bic), the tunnel stiffness
// explains the record as well: the two are ambiguous (on 6 seeds of 8 the
// tunnel stiffness is among the tied).
TEST(Diagnose, SwapsInARivalThatLostWhileAnEffectWasMissing) {
  const std::string dir = testing::ScratchDirectory("diagnose_wide_rival");
  Case truth = UntrimmedShortTruth(30.0);
  const std::vector<std::pair<std::string, double>> hidden = {
      {"t1", 0.00064}, {"t3", -0.00022}, {"Cm_q_delta2", 930.0}};
  SetValues(&truth, hidden);
  UntieBodyYawStiffness(&truth, 1.002);
  const std::string data = SimulateShort(truth, dir + "/data.csv", 1);
  const Diagnosis d = Diagnose(ShortConfig({data}), DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(VerdictToString(d.verdict), std::string("ambiguous")) << text;
  EXPECT_TRUE(TiedIds(d).count("tunnel_stiffness")) << text;
  for (const DiagnosisStep& s : d.steps) {
    EXPECT_NE(s.effect, "roll_torque") << text;
  }
}

// tools/diagnose_suite's `pair` bearing moment at half a degree (draw 11),
// kept as tests/data/pair_bearing_half_degree_seed11.yaml. On this noise
// draw the best fit puts the angle at 9.0 +- 12.8 deg, past the records'
// 8.0 (0.11 lower in the sum of residuals than near the truth): a moment
// that fades only beyond the record is a stiffness, on a ridge with
// Cm_alpha (Effect::on_ridge). The second search judges its bounds within
// two errors, moving the angle toward the 1 deg it starts at rather than
// toward zero (Shrunk): it is named, not left `not_explained` with the
// nominal Cm_alpha 12 of its errors off.
TEST(Diagnose, ABearingAngleOnTheRidgeIsJudgedWithinItsErrors) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "two runs; plain build";
  const Diagnosis d = DiagnoseConfig("pair_bearing_half_degree_seed11.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(d,
                     {"bearing_moment"},
                     {{"Cm_alpha", -0.23},
                      {"Cm_q", -5.5},
                      {"Cm_bearing", -0.00559},
                      {"bearing_angle", 0.5}},
                     text);
}

// Draw 128's record of the same case, kept as
// tests/data/pair_bearing_half_degree_vary128.yaml: here the angle is
// fitted at 0.98 +- 2.4 deg, not determined, and a pitch reading gain
// (a probe outside the catalog, one parameter) came 15.1 below the
// bearing moment's two, 8.9 below the true model's own fit with the angle
// held at the truth. Charged only for the saturated moment the record
// determines (DeterminedBic), the bearing moment ties with the probe:
// `ambiguous`, not `not_explained` with the nominal Cm_alpha 9.7 of its errors
// off.
TEST(Diagnose, AProbeIsWeighedAgainstWhatTheRecordDeterminesOfAnEffect) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  const Diagnosis d = DiagnoseConfig("pair_bearing_half_degree_vary128.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.ambiguous),
            (std::set<std::string>{"bearing_moment", "reading_gain"}))
      << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_TRUE(d.outside_catalog.effect.empty()) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}}, text);
}

// Whether `fit` holds Cm_bearing's error bar from its profile.
bool Profiled(const FitResult& fit) {
  return testing::InPipeline(fit, "Cm_bearing's error bar from its profile");
}

// A bearing moment on one 3-s run, where its angle is not determined:
// Cm_bearing lies on the ridge Cm_bearing x bearing_angle = const, and its
// linear error bar sees only the ridge's width (profile_error_bar_test).
// The search fits without profiles; every fit it reports with the bearing
// moment in (the final model, the partial one that an open tie leaves, the
// alternatives) gets Cm_bearing's error bar from its profile, covering the
// truth. At 30 deg/s the bearing moment explains the record, or ties with
// a dynamic pressure drift (the record shows the stiffness changing, not
// whether with time or amplitude).
TEST(Diagnose, ReportsTheBearingMomentWithItsProfileErrorBar) {
  constexpr double kMoment = -0.02;
  int reported = 0;
  for (const std::uint64_t seed : {1, 3}) {
    const std::string dir = testing::ScratchDirectory(
        "diagnose_bearing_ridge_" + std::to_string(seed));
    Case truth = UntrimmedShortTruth(30.0);
    SetValues(&truth,
              std::map<std::string, double>{{"Cm_bearing", kMoment},
                                            {"bearing_angle", 1.0}});
    const std::string data = SimulateShort(truth, dir + "/data.csv", seed);
    const Diagnosis d = Diagnose(ShortConfig({data}), DiagnoseOptions());
    const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
    EXPECT_TRUE(d.verdict == Verdict::kExplained ||
                d.verdict == Verdict::kAmbiguous)
        << text;
    // The final model's coefficients cover the truth, also when the tie
    // leaves the bearing moment out of it (WidenForTie).
    ExpectFinalCovers(
        d, kShortCoefficients, "seed " + std::to_string(seed) + "\n" + text);
    std::vector<const FitResult*> fits = {&d.FinalFit()};
    if (!d.partial.empty()) fits.push_back(&d.fits[d.partial_fit]);
    for (const AlternativeModel& a : d.alternatives) {
      if (a.fit >= 0) fits.push_back(&d.fits[a.fit]);
    }
    for (const FitResult* fit : fits) {
      const ParameterEstimate* moment = SharedEstimate(*fit, "Cm_bearing");
      const ParameterEstimate* angle = SharedEstimate(*fit, "bearing_angle");
      if (moment == nullptr || !moment->free ||
          angle->standard_error < std::abs(angle->value)) {
        continue;
      }
      ++reported;
      EXPECT_TRUE(Profiled(*fit))
          << "seed " << seed << ": " << ::testing::PrintToString(fit->pipeline);
      EXPECT_LT(std::abs(moment->value - kMoment), 3.0 * moment->standard_error)
          << "seed " << seed << ": " << moment->value << " +- "
          << moment->standard_error;
    }
  }
  EXPECT_GE(reported, 2);
}

// The search at a coarser integration step (DiagnoseOptions::
// coarse_search) names what the search at the config's step names, its
// final values within a tenth of their errors of that search's.
TEST(Diagnose, SearchesAtACoarserStepAndNamesTheSame) {
  const std::string dir = testing::ScratchDirectory("diagnose_search_step");
  Case truth = UntrimmedShortTruth(30.0);
  SetValues(&truth,
            std::map<std::string, double>{{"Cm_bearing", -0.02},
                                          {"bearing_angle", 1.0}});
  const Case c = ShortConfig({SimulateShort(truth, dir + "/data.csv", 1)});
  DiagnoseOptions options;
  const Diagnosis coarse = Diagnose(c, options);
  options.coarse_search = false;
  const Diagnosis exact = Diagnose(c, options);
  const std::string text = FormatDiagnosis(coarse, {0.01, 0.01, 0.01}) +
                           FormatDiagnosis(exact, {0.01, 0.01, 0.01});
  EXPECT_EQ(exact.search_step, c.solver.step);
  EXPECT_GE(coarse.search_step, 4 * c.solver.step);
  int at_search_step = 0;
  for (const FitResult& fit : coarse.fits) {
    if (fit.step == coarse.search_step) ++at_search_step;
  }
  EXPECT_GE(2 * at_search_step, static_cast<int>(coarse.fits.size()));
  EXPECT_EQ(coarse.verdict, exact.verdict) << text;
  ASSERT_EQ(coarse.steps.size(), exact.steps.size()) << text;
  for (size_t i = 0; i < exact.steps.size(); ++i) {
    EXPECT_EQ(coarse.steps[i].effect, exact.steps[i].effect) << text;
  }
  for (const char* name : {"Cm_alpha", "Cm_q"}) {
    const ParameterEstimate* a = SharedEstimate(coarse.FinalFit(), name);
    const ParameterEstimate* b = SharedEstimate(exact.FinalFit(), name);
    EXPECT_LE(std::abs(a->value - b->value), 0.1 * b->standard_error)
        << name << "\n"
        << text;
  }
}

// Three effects that each, alone, drag a coefficient the others bias: on
// a 3-s run with a Magnus moment, a nonlinear damping and a calibration
// error, the fit without them has Cm_q near -1 (truth -5.5), and the
// damping alone moves it by hundreds of its errors while lowering the
// probable error 1.2-fold; the drag rule refused it and the record ended
// `not_explained` with Cm_q 280 errors off. Together they explain the
// record to the noise (Jointly): all three are named, and the final model
// covers the truth.
TEST(Diagnose, AdoptsEffectsThatEarnTheirPlaceOnlyTogether) {
  const std::string dir = testing::ScratchDirectory("diagnose_joint");
  Case truth = UntrimmedShortTruth(30.0);
  const std::map<std::string, double> hidden = {{"Cm_p_alpha", 2.65},
                                                {"Cm_q_delta2", 985.0},
                                                {"theta_cal3", 0.029},
                                                {"psi_cal3", -0.029}};
  SetValues(&truth, hidden);
  const std::string data = SimulateShort(truth, dir + "/data.csv", 1);
  const Diagnosis d = Diagnose(ShortConfig({data}), DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(VerdictToString(d.verdict), std::string("explained")) << text;
  std::set<std::string> found;
  bool together = false;
  for (const DiagnosisStep& s : d.steps) {
    found.insert(s.effect);
    together = together || s.note.find("together") != std::string::npos;
  }
  EXPECT_EQ(found,
            (std::set<std::string>{
                "magnus", "nonlinear_damping", "calibration_nonlinearity"}))
      << text;
  EXPECT_TRUE(together) << text;
  std::map<std::string, double> truths = kShortCoefficients;
  truths.insert(hidden.begin(), hidden.end());
  ExpectFinalCovers(d, truths, text);
}

// A 3-s coning run (one mode of motion) with a tunnel damping, a Magnus
// moment and a flow angularity. The damping and Cm_q absorb the Magnus
// moment, and the model without it reaches the noise with Cm_q near -3.8
// +- 0.01 (truth -5.5). The Magnus moment beside that model is neither
// needed nor excluded, so the final error bars must cover the truth.
TEST(Diagnose, ErrorBarsCoverAnEffectTheRecordCannotExclude) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  const std::string dir = testing::ScratchDirectory("diagnose_not_excluded");
  Case truth = UntrimmedShortTruth(30.0);
  const std::map<std::string, double> hidden = {{"psidot0", 78.0},
                                                {"Cm_p_alpha", 50.5},
                                                {"tunnel_Cm_thetadot", -0.058},
                                                {"tunnel_Cn_psidot", 0.079},
                                                {"theta_T", -0.009},
                                                {"psi_T", 0.010}};
  SetValues(&truth, hidden);
  const std::string data = SimulateShort(truth, dir + "/data.csv", 3);
  const Diagnosis d = Diagnose(ShortConfig({data}), DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  bool magnus = false;
  for (const auto* fits : {&d.not_excluded, &d.ambiguous}) {
    for (const CandidateFit& k : *fits) magnus |= k.effect == "magnus";
  }
  for (const DiagnosisStep& s : d.steps) magnus |= s.effect == "magnus";
  EXPECT_TRUE(magnus) << text;
  // The final model's own error stays on record beside the widened one.
  EXPECT_LT(d.model_standard_errors.at("Cm_q"),
            SharedEstimate(d.FinalFit(), "Cm_q")->standard_error)
      << text;
  if (!d.not_excluded.empty()) {
    EXPECT_NE(text.find("not excluded, the final error bars cover it"),
              std::string::npos)
        << text;
  }
  ExpectFinalCovers(d, kShortCoefficients, text);
}

// tools/diagnose_suite's `coning` Magnus moment + nonlinear damping +
// calibration error (draw 3), kept as tests/data/coning_magnus_damping_
// calibration_seed3.csv. On one mode of motion at one amplitude the Magnus
// moment ties with a tunnel damping, the calibration error is added beside
// either, and the nonlinear damping is neither needed nor excluded. The
// complete model with the Magnus moment, refitted without the damping,
// gave Cm_p_alpha = 81 +- 6 (truth 53.5): its error bars must cover the
// damping the record cannot exclude, as the final model's do.
TEST(Diagnose, AlternativesErrorBarsCoverAnEffectTheRecordCannotExclude) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("coning_magnus_damping_calibration_seed3.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("magnus")) << text;
  // The damping is not excluded, or added beside the calibration error:
  // the joint set's refits land within their tolerance of the minimum, and
  // where one lands nearer (as with Levenberg-Marquardt's Jacobians from
  // the coarser motion, stage_solver.h) the damping earns its place.
  EXPECT_TRUE(EffectIds(d.not_excluded).count("nonlinear_damping") ||
              EffectIds(d.steps).count("nonlinear_damping"))
      << text;
  // Nothing is added (the tie's final model is the one before it, short of
  // the noise): beside it a body asymmetry had lowered BIC by 77.6 and was
  // reported "not needed beside the final model, nor excluded". Each
  // effect is listed beside the search's model first, and one that lowers
  // BIC is not called "not needed".
  EXPECT_FALSE(d.final.at_noise_level) << text;
  for (const CandidateFit& k : d.not_excluded) {
    EXPECT_NE(k.rejected.find("search's model"), std::string::npos) << text;
    if (k.bic_drop > 0.0) {
      EXPECT_EQ(k.rejected.find("not needed"), std::string::npos) << text;
    }
  }
  bool checked = false;
  for (const AlternativeModel& a : d.alternatives) {
    if (a.effect != "magnus") continue;
    const ParameterEstimate* magnus =
        SharedEstimate(a.parameters, "Cm_p_alpha");
    ASSERT_NE(magnus, nullptr) << text;
    EXPECT_NEAR(magnus->value, 53.5, 3.0 * magnus->standard_error) << text;
    checked = true;
  }
  EXPECT_TRUE(checked) << text;
}

// tools/diagnose_suite's `pair` roll reading error + Magnus moment (draw
// 0), kept as tests/data/pair_roll_error_magnus.yaml: the Magnus moment
// ties with a probe outside the catalog (a flow stiffer in one plane), the
// reading error is added beside either, and effects are not excluded. The
// probe's complete model is widened too, with the probe's bounds (a first
// build of that dereferenced the catalog entry a probe does not have).
TEST(Diagnose, AProbesAlternativeIsWidenedWithTheProbesBounds) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "two runs; plain build";
  const Diagnosis d = DiagnoseConfig("pair_roll_error_magnus.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.steps), std::set<std::string>({"roll_interaction"}))
      << text;
  EXPECT_FALSE(d.not_excluded.empty()) << text;
  std::set<std::string> alternatives;
  for (const AlternativeModel& a : d.alternatives) {
    alternatives.insert(a.effect);
    EXPECT_TRUE(a.check.at_noise_level) << a.effect << "\n" << text;
    if (a.effect != "magnus") continue;
    const ParameterEstimate* magnus =
        SharedEstimate(a.parameters, "Cm_p_alpha");
    ASSERT_NE(magnus, nullptr) << text;
    EXPECT_NEAR(magnus->value, 2.61, 3.0 * magnus->standard_error) << text;
  }
  EXPECT_EQ(alternatives,
            std::set<std::string>({"magnus", "flow_yaw_stiffness"}))
      << text;
}

// tools/diagnose_suite's `short` tunnel damping + Magnus moment + flow
// angularity (draw 0), kept as tests/data/short_damping_magnus_angularity.
// csv. At the first round a body yaw asymmetry lowers BIC most but
// predicts nothing held out, and the tunnel damping, next, drags Cm_q
// alone. The Magnus moment, taken alone, left nothing after it that
// earned its place, and the other branch of its tie added the body
// asymmetry, a false effect. The damping's joint set (Jointly, from the
// first dragged contender ahead of every earned one) explains the record:
// Magnus added, the damping tied with its look-alike over 90 deg of roll
// (the body asymmetry), the angularity with a roll reading error. With the
// catalog's own forms only: the calibration's other form, refused for its
// bound on the quiet yaw reading (0.054 deg at 0.47 deg), still takes a
// contender's place and changes the joint sets' pools; the record then
// ends `ambiguous` with the Magnus moment tied with the body asymmetry
// (the three true effects added or tied). Not mended.
TEST(Diagnose, TriesAJointSetBehindABetterContenderRefusedOtherwise) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  DiagnoseOptions own_forms;
  own_forms.other_forms = false;
  const Diagnosis d =
      Diagnose(ShortConfig({testing::SourcePath(
                   "tests/data/short_damping_magnus_angularity.csv")}),
               own_forms);
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  const std::set<std::string> added = EffectIds(d.steps);
  EXPECT_FALSE(added.count("asymmetric_body")) << text;
  EXPECT_TRUE(added.count("magnus")) << text;
  ExpectTruthAddedOrTied(d, {"tunnel_damping", "magnus", "flow_angularity"});
  // Two ties stay open (the damping with a body asymmetry, the angularity
  // with a roll reading error): each alternative of the first holds the
  // second's followed effect too, so each reaches the noise (without the
  // angularity neither did).
  ASSERT_EQ(d.alternatives.size(), 2u) << text;
  for (const AlternativeModel& a : d.alternatives) {
    EXPECT_TRUE(a.check.at_noise_level) << a.effect << "\n" << text;
  }
}

// A Table 6 run with a bearing moment near zero angle, a calibration
// nonlinearity and a roll torque: at constant spin a roll damping and the
// roll torque are twins (BIC 918.747 and 918.746), and without either the
// calibration error the bearing moment needs leaves its bounds (0.333 >
// 0.204 deg). The final model holds the followed one in the tie's place
// (not claimed), the bearing moment and the calibration error are added,
// and the final values cover the truth. Before, nothing was added: the
// final model was the nominal one.
TEST(Diagnose, KeepsATiedEffectTheOthersNeedAsTheTiesStandIn) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "800 samples; plain build";
  const Case c = LoadConfig(testing::SourcePath(
      "tests/data/table6_bearing_calibration_roll_torque.yaml"));
  const Diagnosis d = Diagnose(c, DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  std::vector<std::string> added, tied;
  for (const DiagnosisStep& s : d.steps) added.push_back(s.effect);
  for (const CandidateFit& k : d.ambiguous) tied.push_back(k.effect);
  EXPECT_EQ(
      added,
      std::vector<std::string>({"bearing_moment", "calibration_nonlinearity"}))
      << text;
  EXPECT_EQ(std::set<std::string>(tied.begin(), tied.end()),
            std::set<std::string>({"roll_damping", "roll_torque"}))
      << text;
  ASSERT_FALSE(tied.empty());
  EXPECT_EQ(d.stand_in, tied[0]) << text;
  EXPECT_TRUE(d.final.at_noise_level) << text;
  ExpectFinalCovers(d,
                    {{"Cm_alpha", -0.236},
                     {"Cm_q", -4.0},
                     {"Cm_bearing", -0.000917},
                     {"theta_cal3", 0.0612},
                     {"psi_cal3", -0.0612}},
                    text);
  const nlohmann::json json = nlohmann::json::parse(DiagnosisJson(d, c));
  EXPECT_EQ(json["tie_stand_in"], tied[0]);
}

// Two runs with a tunnel stiffness, a nonlinear damping and a body yaw
// asymmetry: a roll torque ties with the stiffness and is followed; the
// damping, the asymmetry and a roll damping are taken after it. Without
// the torque the roll damping drives the roll (out of its bounds), and
// with the stiffness in its place it is worth nothing: it goes with the
// torque (partial), and the damping and the asymmetry, needed whichever
// of the tied effects is in, were added, the tie left open. But the
// complete model with the stiffness is 10.2 lower in BIC than the one with
// the torque: searched without the torque (OutdoneTieBranch), the record
// is explained by the three true effects, the roll damping gone with the
// torque. Before the tie's partial steps, nothing was added. Since the
// 77th session a set is trimmed no further than a tie allows (Needed's
// ceiling): the roll damping, a Magnus moment and the roll torque together
// rise 9.3 in the stiffness's place, and the stiffness stands in a tie with
// them, the damping and the asymmetry added.
TEST(Diagnose, AStepThatGoesWithTheTiedEffectLeavesWithIt) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  const Diagnosis d = DiagnoseConfig("pair_stiffness_damping_asymmetry.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(EffectIds(d.steps),
            (std::set<std::string>{"nonlinear_damping", "asymmetric_body"}))
      << text;
  EXPECT_TRUE(TiedIds(d).count("tunnel_stiffness")) << text;
  ExpectFinalCovers(d,
                    {{"Cm_alpha", -0.23},
                     {"Cm_q", -5.5},
                     {"Cm_q_alpha2", 136.0},
                     {"tunnel_Cm_theta", 0.000689},
                     {"tunnel_Cn_psi", -0.000241}},
                    text);
  EXPECT_TRUE(EffectIds(d.rejected).count("roll_torque")) << text;
  EXPECT_TRUE(d.stand_in.empty()) << text;
}

// tools/diagnose_suite's `coning` tunnel damping + Magnus moment + flow
// angularity (draw 2), kept as tests/data/coning_damping_magnus_angularity.
// csv. On one coning mode Cm_q and a Magnus moment are hardly told apart:
// the tunnel damping, added first, and Cm_q absorbed the Magnus moment,
// 35 below the damping at the first round (outside rival_bic), and the
// final model reached the noise with Cm_q at -3.68 +- 0.014 (truth -5.5;
// 129 of its errors off). Every round's contenders are now tried beside
// the complete model: the Magnus moment is not excluded there, and the
// final error bars cover its values. The final model holds the tunnel
// damping: claimed, or (since a pool widened by the scores at its union,
// UnionPool) standing in for a Magnus moment with a roll damping, which
// the search without the damping found to explain the record as well.
TEST(Diagnose, AContenderBehindTheRivalsIsStillTriedBesideTheFinalModel) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d = DiagnoseRecord("coning_damping_magnus_angularity.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_TRUE(EffectIds(d.steps).count("tunnel_damping") +
              EffectIds(d.stood_in).count("tunnel_damping"))
      << text;
  EXPECT_TRUE(EffectIds(d.not_excluded).count("magnus")) << text;
  ExpectFinalCovers(d, kShortCoefficients, text);
}

// The same case on draw 38 (t2 0.061, t4 -0.083, Cm_p_alpha -43.6,
// theta_T -0.0086 deg, psi_T 0.0097 deg), kept as tests/data/coning_
// damping_magnus_angularity_draw38.csv. The flow angularity, taken alone
// last, brought the record to the noise and predicted its held-out part;
// a roll reading error refitted at that round predicted it worse than
// its four terms need, yet swapped in for the angularity within 10 of
// BIC, and the two tied. Judged on the odd runs held out alone, out of
// sample separates them there (SeparatedOutOfSample): the damping and the
// angularity are named. With the even runs held out too, the reading
// error, short of the bar on the odd runs, clears it on the even ones:
// over the record's 90 deg of roll the two fit alike, and they tie, the
// damping added.
TEST(Diagnose, ARivalThatFailedOutOfSampleBesideACompleteModelHoldsNoTie) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Case c = ShortConfig({testing::SourcePath(
      "tests/data/coning_damping_magnus_angularity_draw38.csv")});
  DiagnoseOptions odd_runs;
  odd_runs.held_out_both_halves = false;
  const Diagnosis d = Diagnose(c, odd_runs);
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kExplained) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("tunnel_damping")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("flow_angularity")) << text;
  EXPECT_FALSE(EffectIds(d.ambiguous).count("roll_interaction")) << text;
  ExpectFinalCovers(d, {{"theta_T", -0.008572}, {"psi_T", 0.009724}}, text);

  const Diagnosis both = Diagnose(c, DiagnoseOptions());
  const std::string both_text = FormatDiagnosis(both, {0.01, 0.01, 0.01});
  EXPECT_EQ(both.verdict, Verdict::kAmbiguous) << both_text;
  EXPECT_EQ(EffectIds(both.steps), std::set<std::string>({"tunnel_damping"}))
      << both_text;
  EXPECT_EQ(EffectIds(both.ambiguous),
            std::set<std::string>({"flow_angularity", "roll_interaction"}))
      << both_text;
  ExpectFinalCovers(both, kShortCoefficients, both_text);
}

// The same case on draw 5 (tests/data/coning_damping_magnus_angularity_
// seed5.csv): the angularity ties with a roll reading error, the tunnel
// damping is added, and the Magnus moment, not excluded beside it, leaves
// the fit's likelihood nearly as it was (Cm_p_alpha 18 +- 47, truth 67;
// BIC +4.8, AIC +1.9). At its BIC weight (0.08) the final Cm_q was -3.31
// +- 0.47, 4.6 of its errors off the truth (-5.5); at its Akaike weight
// (0.28), -3.31 +- 0.88, within 3.
TEST(Diagnose, AnEffectTheRecordCannotSeeWeighsByItsLikelihood) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("coning_damping_magnus_angularity_seed5.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_TRUE(EffectIds(d.steps).count("tunnel_damping")) << text;
  EXPECT_TRUE(EffectIds(d.not_excluded).count("magnus")) << text;
  ExpectFinalCovers(d, kShortCoefficients, text);
}

// tools/diagnose_suite's `coning` tunnel stiffness + nonlinear damping +
// body yaw asymmetry (draw 0), kept as tests/data/coning_stiffness_
// damping_asymmetry.csv. The asymmetry and the damping explain the record
// to the noise with Cm_alpha at -0.2299 +- 2e-5; beside them a tunnel
// stiffness lowers BIC by 6.7 on the Eq. 43 ridge (only t1 - t3 and
// Cm_alpha + t1 determined), with t1 = 0.138 +- 0.051, past its bound by
// half an error, and Cm_alpha -0.368. Judged at its point fit it was
// excluded, and the final Cm_alpha stood 6 of its errors off the truth;
// within two errors of its bounds it is not excluded, and the final error
// bars cover it. So widened, Cm_alpha's error bar is printed beside the
// final model's own.
TEST(Diagnose, AnEffectOnARidgeIsJudgedWithinItsErrors) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d = DiagnoseRecord("coning_stiffness_damping_asymmetry.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_TRUE(EffectIds(d.not_excluded).count("tunnel_stiffness")) << text;
  ExpectFinalCovers(d, kShortCoefficients, text);
  const size_t widened =
      text.find("error bars widened by the models the record cannot exclude: ");
  ASSERT_NE(widened, std::string::npos) << text;
  const std::string line = text.substr(widened, text.find('\n', widened));
  EXPECT_NE(line.find("Cm_alpha +- "), std::string::npos) << line;
  EXPECT_NE(line.find("model_standard_error"), std::string::npos) << line;
}

// tools/diagnose_suite's `coning` tunnel stiffness + nonlinear damping +
// body yaw asymmetry on draw 130 (another body and flow), kept as
// tests/data/coning_stiffness_damping_asymmetry_vary130.yaml. The damping
// came in a joint set with a tunnel damping (t2 0.065 +- 0.038, t4 -0.049
// +- 0.038, false), named `explained`, the true model 9.2 lower in BIC;
// the asymmetry, a near twin beside that model, took part in no set in
// the tunnel damping's place, and the set without it stood in for no step
// (+28.2). Now it joins the set there: with a roll torque (the
// stiffness's roll part) it stands in for the tunnel damping within 10 of
// BIC (+0.4), and the two tie.
TEST(Diagnose, ANearTwinStandsInForAStepInASet) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_stiffness_damping_asymmetry_vary130.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_NE(d.verdict, Verdict::kExplained) << text;
  EXPECT_FALSE(EffectIds(d.steps).count("tunnel_damping")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("nonlinear_damping")) << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("asymmetric_body")) << text;
  ExpectFinalCovers(
      d,
      {{"Cm_alpha", -0.1429}, {"Cm_q", -5.985}, {"Cm_q_delta2", -34.42}},
      text);
}

// tools/diagnose_suite's `short` tunnel damping + Magnus moment + flow
// angularity on another noise draw (--seed 1), kept as tests/data/short_
// damping_magnus_angularity_seed1.csv. A body's own yaw damping lowers BIC
// by 16 more than the tunnel damping at the first round (over a quarter
// turn of roll a body-fixed damping looks tunnel-fixed) and earns its
// place; the damping and the Magnus moment, each alone swapped for it
// worse, are both not excluded beside it. Together, in its place, they
// lower BIC by 16 more: the search without the body asymmetry is the
// answer, and it adds them. Before, the body asymmetry was added.
TEST(Diagnose, AStepTheEffectsNotExcludedBeatTogetherIsReplaced) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  const Diagnosis d =
      DiagnoseRecord("short_damping_magnus_angularity_seed1.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_FALSE(EffectIds(d.steps).count("asymmetric_body")) << text;
  EXPECT_TRUE(EffectIds(d.rejected).count("asymmetric_body")) << text;
  ExpectTruthAddedOrTied(d, {"tunnel_damping", "magnus", "flow_angularity"});
}

// tools/diagnose_suite's `pair` tunnel damping + Magnus moment + flow
// angularity (draw 143, sigma: auto; tests/data/pair_damping_magnus_
// angularity_vary143.yaml). A body yaw asymmetry, the first step, stayed
// beside the three true effects (`explained`, four added) with its own
// terms at the symmetric body's (Cn_beta at -Cm_alpha, Cn_r 0.14 from
// Cm_q): without it BIC fell by 3.0, but the tunnel damping then came to
// t4 3.53 +- 0.29 beside Cm_q -4.47 +- 0.33, past |t4| <= 2 |Cm_q + t4| at
// the point fit. The backward check judges a ridge's effects within two
// of their errors, as the effects not excluded are: the asymmetry is
// pruned.
TEST(Diagnose, AStepThatOnlyHeldARidgeEffectInsideItsBoundsIsPruned) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_damping_magnus_angularity_vary143.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_FALSE(EffectIds(d.steps).count("asymmetric_body")) << text;
  EXPECT_TRUE(EffectIds(d.pruned).count("asymmetric_body")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("tunnel_damping")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("magnus")) << text;
  std::set<std::string> named = EffectIds(d.steps);
  for (const CandidateFit& k : d.ambiguous) named.insert(k.effect);
  EXPECT_TRUE(named.count("flow_angularity")) << text;
  ExpectFinalCovers(d,
                    {{"Cm_alpha", -0.2591},
                     {"Cm_q", -5.027},
                     {"tunnel_Cm_thetadot", -2.789},
                     {"tunnel_Cn_psidot", 3.016}},
                    text);
}

// tools/diagnose_suite's `pair` tunnel stiffness + roll reading error +
// flow angularity (draw 142, sigma: auto), kept as tests/data/pair_
// stiffness_roll_reading_angularity_vary142.yaml. The search added the
// reading error and the stiffness; a trim moment and the angularity in the
// reading error's place beat it by 12.9, and the search without it named
// them with the stiffness, 7.0 lower in BIC: `explained` with a false trim
// moment. At 25.7 and 51.4 deg/s, far below the pitch frequency, the two
// roll-locked effects leave the same motion: within ambiguity_bic they
// stand in a tie.
TEST(Diagnose, ARollLockedStepSwappedForItsTwinStandsInATie) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  const Diagnosis d =
      DiagnoseConfig("pair_stiffness_roll_reading_angularity_vary142.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.steps), std::set<std::string>{"tunnel_stiffness"})
      << text;
  EXPECT_EQ(EffectIds(d.ambiguous),
            (std::set<std::string>{
                "roll_interaction", "trim_moment", "flow_angularity"}))
      << text;
  EXPECT_NE(d.verdict_text.find("spinning near the pitch frequency"),
            std::string::npos)
      << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.1955}, {"Cm_q", -6.121}}, text);
}

// The same case on draw 73 (t2 -1.65, t4 2.24, Cm_p_alpha -2.8, theta_T
// -0.0097 and psi_T 0.011 deg: 1.85 times the noise), kept as
// tests/data/short_damping_magnus_angularity_draw73.csv. At the first
// round the angularity came sixth by score and was never refitted; a trim
// moment taken in a joint set with the damping and the Magnus moment then
// tied with a roll reading error and a drift in time, but not with the
// angularity: over 25 deg of roll the three are one offset. Where roll
// does not separate them, a round refits the whole offset family when one
// of it is refitted (Refitted): the angularity ties with the trim moment
// and the roll reading error.
TEST(Diagnose, TheOffsetFamilyIsRefittedTogether) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("short_damping_magnus_angularity_draw73.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectTruthAddedOrTied(d, {"tunnel_damping", "magnus", "flow_angularity"});
  std::vector<std::vector<CandidateFit>> ties = d.later_ties;
  ties.push_back(d.ambiguous);
  const auto angularity = std::find_if(ties.begin(), ties.end(), [](auto& t) {
    return EffectIds(t).count("flow_angularity") > 0;
  });
  ASSERT_NE(angularity, ties.end()) << text;
  EXPECT_TRUE(EffectIds(*angularity).count("trim_moment")) << text;
}

// The same case on draw 8 (tests/data/short_damping_magnus_angularity_
// seed8.csv), its tunnel damping's yaw term 1.36 times its pitch term. A
// body yaw asymmetry leads the tunnel damping by 14.6 at the first round
// (no tie, but within near_tie_bic) and is added; the search that follows
// it adds no Magnus moment, and the true model's BIC is about 20 lower
// than its complete model's. The search without the asymmetry is the
// answer (NearTieBranch).
TEST(Diagnose, ANearTieAtAStepIsSearchedWithoutItsLead) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("short_damping_magnus_angularity_seed8.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_FALSE(EffectIds(d.steps).count("asymmetric_body")) << text;
  EXPECT_TRUE(EffectIds(d.rejected).count("asymmetric_body")) << text;
  ExpectTruthAddedOrTied(d, {"tunnel_damping", "magnus", "flow_angularity"});
}

// The same case on draw 16 (tests/data/short_damping_magnus_angularity_
// vary16.csv). The body yaw asymmetry leads the tunnel damping by 17.4 at
// the first round and ends in a tie with it; the complete model with the
// tunnel damping is 17 lower than the one with the asymmetry. A reading
// lag (a probe) weighed against the asymmetry's side alone seemed to
// explain the record 19 better than the catalog, and the verdict was
// `not_explained` with Cm_q 57 of its errors off. Now the tie's better
// side counts (CompleteBic), and the search without the followed effect
// of a tie so outdone is the answer (OutdoneTieBranch): the three effects
// are named, or the angularity tied with a roll reading error (TieGap).
TEST(Diagnose, ATieOutdoneOnItsOtherSideIsSearchedWithoutItsLead) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("short_damping_magnus_angularity_vary16.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectDampingMagnusWithAngularityOrItsTwin(d,
                                             {{"Cm_alpha", -0.23},
                                              {"Cm_q", -5.5},
                                              {"Cm_p_alpha", 4.8258},
                                              {"tunnel_Cm_thetadot", -2.3173},
                                              {"tunnel_Cn_psidot", 3.1459}},
                                             text);
  EXPECT_TRUE(EffectIds(d.rejected).count("asymmetric_body")) << text;
}

// tools/diagnose_suite --vary's `coning` Magnus moment (Cm_p_alpha 103) +
// nonlinear damping (Cm_q_delta2 252) + calibration error (draw 16), kept
// as tests/data/coning_magnus_nonlinear_damping_calibration_vary16.csv.
// The search follows a tunnel damping that ties with the Magnus moment,
// though swapped in for it the Magnus moment lowers BIC by 46; and a dry
// friction with the Magnus moment and the calibration error fits the
// record as well as the truth does (the same sum of squares to 1e-4,
// Cm_q +5.8 there). Weighed against the tie's followed side alone the
// friction had seemed 46 better: the verdict was `not_explained`,
// nothing added, Cm_q 80 of its errors off. The tie's other side counts
// (CompleteBic), and the search without the followed effect of a tie so
// outdone is the answer (OutdoneTieBranch): the three effects are named,
// and the final values cover the truth. The friction is named alike where
// the searches' paths weigh it (with the calibration's other form tried,
// they no longer do).
TEST(Diagnose, ATieFollowedWhereItsOtherSideIsBetterIsSearchedWithout) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("coning_magnus_nonlinear_damping_calibration_vary16.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(
      d,
      {"magnus", "nonlinear_damping", "calibration_nonlinearity"},
      {{"Cm_alpha", -0.23},
       {"Cm_q", -5.5},
       {"Cm_p_alpha", 103.157},
       {"Cm_q_delta2", 251.94},
       {"theta_cal3", -0.03664},
       {"psi_cal3", 0.03495}},
      text);
  // The tunnel damping is rejected where the search without it is the
  // answer; where the search past the noise is (a tunnel stiffness, lower
  // in BIC beside the tie's model, sends it there: Unrefitted), it is not
  // excluded beside the final model.
  EXPECT_TRUE(EffectIds(d.rejected).count("tunnel_damping") ||
              EffectIds(d.not_excluded).count("tunnel_damping"))
      << text;
  if (!d.outside_catalog_alike.empty()) {
    EXPECT_EQ(d.outside_catalog_alike[0], "bearing_friction") << text;
  }
}

// tools/diagnose_suite --vary's `pair` tunnel stiffness + roll reading
// error + flow angularity (draw 120: two 3-s runs at 30 and 60 deg/s),
// kept as tests/data/pair_stiffness_roll_angularity_draw120.yaml. The
// search follows a tunnel damping (t2 10 +- 1.3) into a tie with the
// stiffness, whose side is 78.7 lower in BIC; searched without the
// damping (OutdoneTieBranch), the three are named. The outdone tie is
// thought of before the near one (SecondThoughts): the answer is then
// explained, and the near tie's search without the first step, 2.1 s of
// the 4.9 the diagnosis had taken alone, is not run (tools/bench times
// this record).
TEST(Diagnose, APairsTieOutdoneOnItsOtherSideNamesTheThree) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_stiffness_roll_angularity_draw120.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(
      d,
      {"tunnel_stiffness", "roll_interaction", "flow_angularity"},
      {{"Cm_alpha", -0.23},
       {"Cm_q", -5.5},
       {"tunnel_Cm_theta", 0.0013859},
       {"tunnel_Cn_psi", -0.00048505},
       {"theta_cos_phi", 0.024143},
       {"theta_sin_phi", 0.014486},
       {"psi_cos_phi", 0.019315},
       {"psi_sin_phi", 0.0096573},
       {"theta_T", 0.019045},
       {"psi_T", 0.021604}},
      text);
  EXPECT_TRUE(ListedWith(d.rejected, "tunnel_damping", "tied with an effect"))
      << text;
}

// `d` is ambiguous with `effect` pruned from its steps within the tie
// (PruneWithinTie): neither its final model nor any complete model of the
// tie holds the effect's terms.
void ExpectPrunedWithinTie(const Diagnosis& d, const std::string& effect) {
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_FALSE(EffectIds(d.steps).count(effect)) << text;
  EXPECT_TRUE(EffectIds(d.pruned).count(effect)) << text;
  ASSERT_GE(d.alternatives.size(), 2u) << text;
  std::vector<const std::vector<ParameterEstimate>*> models = {
      &d.FinalFit().parameters};
  for (const AlternativeModel& a : d.alternatives) {
    models.push_back(&a.parameters);
  }
  const Effect* e = FindEffect(effect);
  std::vector<std::string> terms = e->symmetric;
  terms.insert(terms.end(), e->asymmetric.begin(), e->asymmetric.end());
  for (const auto* parameters : models) {
    for (const std::string& term : terms) {
      const ParameterEstimate* p = SharedEstimate(*parameters, term);
      EXPECT_TRUE(p == nullptr || (!p->free && p->value == 0.0)) << term << "\n"
                                                                 << text;
    }
  }
}

// The same coning record as above: the body yaw asymmetry (true), added
// first, and a tunnel stiffness (true) with a tunnel damping (false) in its
// place explain the record alike (BIC +3.0 with both needed there): over a
// quarter turn of roll a body-fixed asymmetry looks tunnel-fixed. The
// verdict is a tie of the one against the two; the final model keeps the
// asymmetry's terms without claiming it, its error bars covering the other
// model.
TEST(Diagnose, AStepTwoEffectsReplaceAlikeIsATieNotAClaim) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d = DiagnoseRecord("coning_stiffness_damping_asymmetry.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  ASSERT_EQ(d.stood_in.size(), 1u) << text;
  EXPECT_EQ(d.stood_in[0].effect, "asymmetric_body") << text;
  EXPECT_EQ(d.stood_in_for[0].size(), 2u) << text;
  EXPECT_FALSE(EffectIds(d.steps).count("asymmetric_body")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("nonlinear_damping")) << text;
  EXPECT_NE(SharedEstimate(d.FinalFit(), "Cn_r"), nullptr) << text;
  ExpectFinalCovers(d, kShortCoefficients, text);
}

// Draw 3 of the suite's short record with a tunnel stiffness, a nonlinear
// damping and a body yaw asymmetry (t1 = 5.3e-4, t3 = -1.8e-4: over a
// quarter turn of roll the stiffness shows mostly through the roll that
// Eq. 39's t3 psi drives). A roll torque was added first; swapped in for
// it once the other two were in, the tunnel stiffness lowered BIC by 1.1
// more with t1 = 0.138, past its bound (0.115) on the Eq. 43 ridge, and
// the roll torque was claimed, a false effect. The swap now judges the
// rival within two of its errors of its bounds: the two tie.
TEST(Diagnose, ASwapOnTheRidgeIsJudgedWithinItsErrors) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("short_stiffness_damping_asymmetry_seed3.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_FALSE(EffectIds(d.steps).count("roll_torque")) << text;
  ExpectTruthAddedOrTied(
      d, {"tunnel_stiffness", "nonlinear_damping", "asymmetric_body"});
}

// The same case on draw 23 (t1 9.0e-4, t3 -3.2e-4, Cm_q_delta2 926, body
// yaw +0.26%), kept as tests/data/short_stiffness_damping_asymmetry_vary23
// .csv. A roll torque takes the stiffness's roll signature first and the
// search explains the record with it; the stiffness, not excluded beside
// that model (BIC -2.1), ran along Eq. 43's ridge out of its bounds in the
// torque's place (t1 0.15, bound 0.115). With each of its terms held at
// zero in turn (FindSingleReplacement) it explains the record 5 lower
// (one more parameter counted): the roll torque is not claimed, the two
// tie.
TEST(Diagnose, AnEffectNotExcludedHeldOnItsRidgeTiesWithAStep) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("short_stiffness_damping_asymmetry_vary23.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_FALSE(EffectIds(d.steps).count("roll_torque")) << text;
  const std::set<std::string> tied = EffectIds(d.ambiguous);
  EXPECT_TRUE(tied.count("roll_torque") && tied.count("tunnel_stiffness"))
      << text;
  ExpectTruthAddedOrTied(
      d, {"tunnel_stiffness", "nonlinear_damping", "asymmetric_body"});
}

// A 3-s run with a dry friction on both axes (outside the catalog; suite
// draw 68, kept as tests/data/short_friction_draw68.csv). The axis
// friction probe lowers BIC by 288.0, a tunnel damping by 248.4, and a
// calibration error in signed-square form by 296.2 but 3.8 times past its
// bound: refused so, it had kept the probe from counting, and the tunnel
// damping was named `explained`. Weighed against the contenders within
// their bounds, the probe outdoes the catalog: `not_explained`, nothing
// added, the probe named.
TEST(Diagnose, AContenderFarPastItsBoundLeavesAProbeToCount) {
  const Diagnosis d = DiagnoseRecord("short_friction_draw68.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(VerdictToString(d.verdict), std::string("not_explained")) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_EQ(d.outside_catalog.effect, "axis_friction") << text;
  EXPECT_TRUE(d.outside_at_noise_level) << text;
}

// The same case on draw 24 (t1 1.02e-3, t3 -3.6e-4, Cm_q_delta2 930, body
// yaw -0.32%), kept as tests/data/short_stiffness_damping_asymmetry_vary24
// .csv. A Magnus moment led the first round by 1.7 over the asymmetry and
// was adopted, the stiffness's roll signature then tied with a roll torque
// and a tunnel damping, and the false Magnus moment, needed in none of the
// complete models (RedundantInEach), was pruned within the tie
// (PruneWithinTie; the draw-39 record below still goes that way). Since a
// probe is weighed against the contenders within their bounds (a
// calibration error refused far past its bound had kept a friction probe
// from counting, suite draw 68), a reading lag outdoes the first round's
// catalog effects; the catalog alone explains the record 232.6 lower in
// BIC, and its search names the three, the Magnus moment dropped again as
// redundant and the roll torque's tie resolved without it.
TEST(Diagnose, AFalseMagnusStepIsDroppedAndTheThreeNamed) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("short_stiffness_damping_asymmetry_vary24.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_FALSE(EffectIds(d.steps).count("magnus")) << text;
  ExpectTruthAddedOrTied(
      d, {"tunnel_stiffness", "nonlinear_damping", "asymmetric_body"});
}

// The same case on draw 39 (t1 1.02e-3, t3 -3.6e-4, Cm_q_delta2 788, body
// yaw -0.30%), kept as tests/data/short_stiffness_damping_asymmetry_draw39
// .csv. A Magnus moment is taken first, a roll torque ties with a tunnel
// damping after the damping and the asymmetry, and every complete model
// is 4.8 lower in BIC without the Magnus moment (1.6 +- 3.4 in the final
// model). Searched without it, the tunnel stiffness ran along Eq. 43's
// ridge out of its bounds with every companion and the record stayed
// unexplained, so the search without a step (the older rule) kept the
// false Magnus moment; pruned within the tie, it is gone, and the
// stiffness (t1 1e-3) stays not excluded beside the answer.
TEST(Diagnose, AStepPrunedWithinATieNeedsNoSearchWithoutIt) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("short_stiffness_damping_asymmetry_draw39.csv");
  ExpectPrunedWithinTie(d, "magnus");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(EffectIds(d.steps),
            (std::set<std::string>{"asymmetric_body", "nonlinear_damping"}))
      << text;
  ExpectFinalCovers(d, kShortCoefficients, text);
}

// The same case on draw 70 (t1 -9.5e-4, t3 3.3e-4, Cm_q_delta2 558, body
// yaw +0.30%), kept as tests/data/short_stiffness_damping_asymmetry_draw70
// .csv. After the asymmetry a tunnel damping, dragging Cm_q alone, came in
// a joint set with the stiffness, which then tied with a roll torque and a
// roll damping: the answer added the asymmetry and a false tunnel damping
// (t2 5.7 +- 5.7), the nonlinear damping only "not excluded" though 46
// lower in BIC beside it. The damping stood on a partner not adopted
// (WithoutTiedPartner): without it the asymmetry and the nonlinear damping
// are named, 13.9 lower, the stiffness tied with a roll effect.
TEST(Diagnose, AStepWhoseJointPartnerTiedIsSearchedWithout) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("short_stiffness_damping_asymmetry_draw70.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_FALSE(EffectIds(d.steps).count("tunnel_damping")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("nonlinear_damping")) << text;
  ExpectTruthAddedOrTied(
      d, {"tunnel_stiffness", "nonlinear_damping", "asymmetric_body"});
}

// The same rule where the partner went into a later tie: draw 74's 3-s
// tunnel damping + Magnus moment (Cm_p_alpha 2.4) + flow angularity,
// kept as tests/data/short_damping_magnus_angularity_draw74.csv. The
// tunnel damping's yaw term is not its pitch term (t2 -1.65, t4 2.24),
// which a body yaw asymmetry's own yaw damping takes up: the asymmetry
// was adopted in a joint set with the Magnus moment, which then tied with
// the tunnel damping after the angularity's tie with a roll reading
// error. Without the asymmetry the damping and the Magnus moment are
// named, 9.6 lower in BIC (the true model's own fit is 16 below every
// model of the first answer).
TEST(Diagnose, AStepWhosePartnerWentIntoALaterTieIsSearchedWithout) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("short_damping_magnus_angularity_draw74.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_FALSE(EffectIds(d.steps).count("asymmetric_body")) << text;
  ExpectTruthAddedOrTied(d, {"tunnel_damping", "magnus", "flow_angularity"});
}

// The same case on draw 124 (t2 1.65, t4 -2.24, Cm_p_alpha -2.50; sigma:
// auto), kept as tests/data/short_damping_magnus_angularity_draw124.yaml.
// The first answer names the damping and the Magnus moment (a joint set
// with the angularity, which ties with a trim moment and a roll reading
// error); the search without the damping named a body asymmetry and a
// false nonlinear damping whose complete model came 1.6 lower in BIC, and
// had been taken. By less than partner_search_bic (2) the record holds no
// evidence either way: the first answer stands.
TEST(Diagnose, ASearchWithoutAPartnerNeedsEvidenceToReplaceTheAnswer) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_damping_magnus_angularity_draw124.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_FALSE(EffectIds(d.steps).count("nonlinear_damping")) << text;
  EXPECT_FALSE(EffectIds(d.steps).count("asymmetric_body")) << text;
  ExpectTruthAddedOrTied(d, {"tunnel_damping", "magnus", "flow_angularity"});
}

// The effects of the suite's 3-s stiffness + nonlinear damping + body
// asymmetry records.
const std::set<std::string> kStiffnessDampingAsymmetry = {
    "asymmetric_body", "nonlinear_damping", "tunnel_stiffness"};

// Whether the tie model `m` holds exactly `effects`.
bool Holds(const Diagnosis::TieModel& m, const std::set<std::string>& effects) {
  return std::set<std::string>(m.effects.begin(), m.effects.end()) == effects;
}

// The entries of diagnosis.json's tie_models (of `d`, diagnosed from `c`)
// that hold exactly `effects`.
std::vector<nlohmann::json> ReportedTieModels(
    const Diagnosis& d, const Case& c, const std::set<std::string>& effects) {
  const nlohmann::json j = nlohmann::json::parse(DiagnosisJson(d, c));
  std::vector<nlohmann::json> reported;
  for (const nlohmann::json& m : j["tie_models"]) {
    if (m["effects"].get<std::set<std::string>>() == effects) {
      reported.push_back(m);
    }
  }
  return reported;
}

// The same case on draw 72 (t1 -9.6e-4, t3 3.4e-4, Cm_q_delta2 -582, body
// yaw +0.27%), kept as tests/data/short_stiffness_damping_asymmetry_draw72
// .csv. Two ties stay open: the asymmetry with a Magnus moment, and after
// the nonlinear damping a roll torque with a roll damping, a tunnel
// damping and the stiffness. The alternatives hold the roll torque the
// search followed: the asymmetry's, without the stiffness, had Cn_beta
// 0.23174 +- 3.7e-5 against a true 0.23061 (30 of its errors). The models
// that kept the second tie open (tie_models) hold each of its rivals in
// the torque's place: the one with the stiffness, 10.7 lower in BIC, is
// the true model, and its values cover the truth (on Eq. 43's ridge).
TEST(Diagnose, ATieModelHoldsTheTrueEffectOfASecondTie) {
  const std::string file = "short_stiffness_damping_asymmetry_draw72.csv";
  const Diagnosis d = DiagnoseRecord(file);
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  ASSERT_FALSE(d.later_ties.empty()) << text;
  const auto true_model =
      std::find_if(d.tie_models.begin(), d.tie_models.end(), [](const auto& m) {
        return Holds(m, kStiffnessDampingAsymmetry);
      });
  ASSERT_NE(true_model, d.tie_models.end()) << text;
  EXPECT_EQ(true_model->in_place_of, "roll_torque") << text;
  EXPECT_TRUE(true_model->check.at_noise_level) << text;
  ExpectCovers(true_model->parameters,
               {{"Cm_alpha", -0.23},
                {"Cn_beta", 0.23 * (1.0 + 0.0026659)},
                {"tunnel_Cm_theta", -9.618e-4},
                {"tunnel_Cn_psi", 3.366e-4},
                {"Cm_q_alpha2", -582.15}},
               text);
  // diagnosis.json reports it with its effects.
  const std::vector<nlohmann::json> reported = ReportedTieModels(
      d,
      ShortConfig({testing::SourcePath("tests/data/" + file)}),
      kStiffnessDampingAsymmetry);
  ASSERT_EQ(reported.size(), 1u) << text;
  EXPECT_EQ(reported[0]["in_place_of"], "roll_torque");
  EXPECT_TRUE(reported[0]["check"]["at_noise_level"].get<bool>());
  EXPECT_TRUE(reported[0]["parameters"].contains("tunnel_Cn_psi"));
}

// The same case on draw 128 (t1 7.28e-4, t3 -2.55e-4, Cm_q_delta2 -504.6,
// body yaw -0.22%), kept as tests/data/short_stiffness_damping_asymmetry_
// vary128.yaml. The asymmetry ties with a Magnus moment (followed), and
// after the damping a roll torque (followed) with the stiffness and a
// tunnel damping: the alternatives hold the torque, the tie models one
// rival each, so no model held the true three, and the asymmetry's
// alternative had Cn_beta 26 of its errors off. The cross model with both
// rivals in (cross_tie_models) is the true model, 6.5 lower in BIC than
// the one with the followed effects, and covers the truth on Eq. 43's
// ridge. That is the search with the odd runs held out alone; with the
// even runs held out too (held_out_both_halves) the asymmetry clears the
// bar and is followed, and the stiffness in the roll torque's place is
// the true model, a single swap.
TEST(Diagnose, ACrossModelHoldsTheTrueEffectsOfTwoTies) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const std::string file = "short_stiffness_damping_asymmetry_vary128.yaml";
  const Case c = LoadConfig(testing::SourcePath("tests/data/" + file));
  const auto holds_truth = [](const Diagnosis::TieModel& m) {
    return Holds(m, kStiffnessDampingAsymmetry);
  };
  const std::map<std::string, double> truth = {
      {"Cm_alpha", -0.23},
      {"Cn_beta", 0.23 * (1.0 - 0.0021670)},
      {"tunnel_Cm_theta", 7.284e-4},
      {"tunnel_Cn_psi", -2.549e-4},
      {"Cm_q_alpha2", -504.56}};
  const Diagnosis both = Diagnose(c, DiagnoseOptions());
  const std::string both_text = FormatDiagnosis(both, {0.01, 0.01, 0.01});
  EXPECT_EQ(both.verdict, Verdict::kAmbiguous) << both_text;
  const auto single =
      std::find_if(both.tie_models.begin(), both.tie_models.end(), holds_truth);
  ASSERT_NE(single, both.tie_models.end()) << both_text;
  EXPECT_EQ(single->in_place_of, "roll_torque") << both_text;
  ExpectCovers(single->parameters, truth, both_text);

  DiagnoseOptions odd_runs;
  odd_runs.held_out_both_halves = false;
  const Diagnosis d = Diagnose(c, odd_runs);
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  ASSERT_FALSE(d.later_ties.empty()) << text;
  EXPECT_TRUE(
      std::none_of(d.tie_models.begin(), d.tie_models.end(), holds_truth))
      << text;
  const auto cross = std::find_if(
      d.cross_tie_models.begin(), d.cross_tie_models.end(), holds_truth);
  ASSERT_NE(cross, d.cross_tie_models.end()) << text;
  EXPECT_EQ(cross->also_in_place_of, "magnus") << text;
  EXPECT_EQ(cross->also_effect, "asymmetric_body") << text;
  EXPECT_EQ(cross->in_place_of, "roll_torque") << text;
  EXPECT_EQ(cross->effect, "tunnel_stiffness") << text;
  EXPECT_LT(cross->rise, 0.0) << text;
  EXPECT_TRUE(cross->check.at_noise_level) << text;
  ExpectCovers(cross->parameters, truth, text);
  // diagnosis.json reports it among the tie models, with both swaps.
  const std::vector<nlohmann::json> reported =
      ReportedTieModels(d, c, kStiffnessDampingAsymmetry);
  ASSERT_EQ(reported.size(), 1u) << text;
  EXPECT_EQ(reported[0]["also_in_place_of"], "magnus");
  EXPECT_EQ(reported[0]["in_place_of"], "roll_torque");
}

// The same case on draw 27 (t1 8.1e-4, t3 -2.8e-4, Cm_q_delta2 670, body
// yaw -0.20%), kept as tests/data/short_stiffness_damping_asymmetry_vary27
// .csv. A Magnus moment comes in with the damping, and the roll torque
// that follows ties with a tunnel damping; the stiffness, swapped in for
// the torque, ran along Eq. 43's ridge to t1 = 0.5 (bound 0.11) and lost,
// and the final Cm_alpha, -0.22899 +- 2e-5, was 47 of its errors off the
// truth (-0.23: the stiffness's part). A tunnel term out of its bounds in
// a swap is now held at zero in turn (Unresolved): 7 above the torque
// with the held term counted, the stiffness joins the tie and the final
// error bars cover its model. The Magnus moment (-2.5 +- 0.56) was named
// too: the asymmetry, scored seventh at the first round on two terms, was
// never refitted (refitting seven changed six other kept records'
// answers), and beside the answer it is a near twin not excluded (BIC
// -3.1). Fitted in the Magnus moment's place it explains the record 5
// lower (FindSingleReplacement, open to ambiguous answers and near twins
// since session 25): the two tie, and neither is claimed.
TEST(Diagnose, ASwapRunningAlongTheRidgeIsHeldAtZeroInTurn) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("short_stiffness_damping_asymmetry_vary27.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  const std::set<std::string> tied = EffectIds(d.ambiguous);
  EXPECT_TRUE(tied.count("roll_torque") && tied.count("tunnel_stiffness"))
      << text;
  EXPECT_FALSE(EffectIds(d.steps).count("magnus")) << text;
  std::set<std::string> later;
  for (const auto& tie : d.later_ties) {
    for (const CandidateFit& k : tie) later.insert(k.effect);
  }
  EXPECT_TRUE(later.count("magnus") && later.count("asymmetric_body")) << text;
  ExpectFinalCovers(d, kShortCoefficients, text);
}

// The alternative model of `d` with the tunnel stiffness in the tie holds
// the true t1 and t3 within 3 of their errors.
void ExpectStiffnessAlternativeCovers(const Diagnosis& d,
                                      double t1,
                                      double t3,
                                      const std::string& text) {
  const auto stiffness = std::find_if(
      d.alternatives.begin(),
      d.alternatives.end(),
      [](const AlternativeModel& a) { return a.effect == "tunnel_stiffness"; });
  ASSERT_NE(stiffness, d.alternatives.end()) << text;
  ExpectCovers(stiffness->parameters,
               {{"tunnel_Cm_theta", t1}, {"tunnel_Cn_psi", t3}},
               text);
}

// `d` (`text` its report), ambiguous, names the body asymmetry and the
// nonlinear damping and ties the tunnel stiffness, the final model
// covering the truth: Cm_alpha and Cm_q, and the damping (the asymmetric
// program's Cm_q_alpha2).
void ExpectAsymmetryAndDampingNamed(const Diagnosis& d,
                                    double damping,
                                    const std::string& text) {
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.steps),
            (std::set<std::string>{"asymmetric_body", "nonlinear_damping"}))
      << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("tunnel_stiffness")) << text;
  ExpectFinalCovers(d, kShortCoefficients, text);
  ExpectCovers(d.final_parameters, {{"Cm_q_alpha2", damping}}, text);
}

// As ExpectAsymmetryAndDampingNamed, and the stiffness's complete model
// covers t1 and t3.
void ExpectAsymmetryAndDampingBesideAStiffnessTie(const Diagnosis& d,
                                                  double damping,
                                                  double t1,
                                                  double t3) {
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectAsymmetryAndDampingNamed(d, damping, text);
  ExpectStiffnessAlternativeCovers(d, t1, t3, text);
}

// The same case on draw 40 (t1 1.02e-3, t3 -3.6e-4, Cm_q_delta2 806, body
// yaw -0.30%), kept as tests/data/short_stiffness_damping_asymmetry_draw40
// .csv. A Magnus moment led the first round by 0.9 over the stiffness and
// took the asymmetry's signal: beside it the asymmetry is excluded, so no
// search nor replacement from the effects not excluded tried it, and the
// search without the Magnus moment ended `not_explained` (a lag of the
// readings outdid the stiffness, which then ran along Eq. 43's ridge).
// The Magnus moment was named, -3.7 +- 1.3 (2.8 of its own errors from
// zero). Since ambiguous answers are searched past the noise too
// (PastNoise), the search past the noise names the asymmetry and the
// damping, drops the Magnus moment, and ties the tunnel stiffness with a
// roll torque and a tunnel damping. (A stage that scored a barely held
// step's place afresh at the end had tied the asymmetry with the Magnus
// moment here; it was removed when no record needed it.)
TEST(Diagnose, AMagnusMomentThatTookTheAsymmetrysSignalIsNotClaimed) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("short_stiffness_damping_asymmetry_draw40.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_FALSE(EffectIds(d.steps).count("magnus")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("nonlinear_damping")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("asymmetric_body")) << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("tunnel_stiffness")) << text;
  ExpectFinalCovers(d, kShortCoefficients, text);
  ExpectStiffnessAlternativeCovers(d, 1.02e-3, -3.57e-4, text);
}

// Draw 29's record below, whose tie has a side in each program (the body
// asymmetry's complete models fit the asymmetric one): refitting one side
// from another (AlignedSides, FromOtherSide) had written the asymmetric
// solution's values by position into a symmetric case, past its table, a
// heap overflow that aborted diagnose_test now and then. Run in the
// sanitized build too, where AddressSanitizer watches that path.
TEST(Diagnose, ATieSideStartedFromTheOtherProgramStaysInItsTable) {
  const Diagnosis d =
      DiagnoseRecord("short_stiffness_damping_asymmetry_vary29.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("tunnel_stiffness")) << text;
}

// The same case on draw 29 (t1 8.1e-4, t3 -2.8e-4, Cm_q_delta2 983, body
// yaw +0.25%), kept as tests/data/short_stiffness_damping_asymmetry_vary29
// .csv. A roll torque (Eq. 39's roll part of the stiffness) is taken
// first; the asymmetry and the damping, together, bring the record to the
// noise. In the final model the stiffness in the torque's place (t1 held
// at zero) is 10.3 lower in BIC: the search without the torque took a
// Magnus moment first and left the record unexplained, and the torque
// had been named. A step one effect beats in its place stands in a tie
// with it when the search without it explains nothing.
TEST(Diagnose, AStepOutdoneByOneEffectTiesWithItWhenTheSearchWithoutItFails) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("short_stiffness_damping_asymmetry_vary29.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.ambiguous),
            (std::set<std::string>{"roll_torque", "tunnel_stiffness"}))
      << text;
  EXPECT_EQ(EffectIds(d.steps),
            (std::set<std::string>{"asymmetric_body", "nonlinear_damping"}))
      << text;
  ExpectFinalCovers(d, kShortCoefficients, text);
}

// The same case on draw 53 (t1 6.2e-4, t3 -2.2e-4, Cm_q_delta2 519, body
// yaw -0.19%; tests/data/short_stiffness_damping_asymmetry_draw53.yaml).
// After the asymmetry a tunnel damping (false) was named, 108.8 lower in
// BIC. The effects not excluded in its place lowered BIC by 29.5, but the
// stiffness among them ran along Eq. 43's ridge to t1 = 0.186 (bound
// 0.114), and the set was refused; with t1 held at zero they lowered it by
// 29.2 within their bounds. Of the five, taken out together, the four
// each unneeded beside the others left the damping alone, short of the
// noise; taken out one at a time the stiffness stays with it. The search
// without the tunnel damping names the asymmetry and the damping and ties
// the stiffness with a roll torque. A set's tunnel term out of its bounds
// is held at zero in turn, as a swap's is, and a set's members are
// dropped one at a time.
TEST(Diagnose, ASetsTunnelTermOnTheRidgeIsHeldAtZeroInTurn) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_stiffness_damping_asymmetry_draw53.yaml");
  ExpectAsymmetryAndDampingBesideAStiffnessTie(d, 518.6, 6.22e-4, -2.18e-4);
}

// The same case on draw 56's pair of runs (t1 1.02e-3, t3 -3.57e-4,
// Cm_q_delta2 236, body yaw +0.34%; tests/data/pair_stiffness_damping_
// asymmetry_draw56.yaml). A roll torque, taken first, tied with the
// stiffness; after it the damping and the asymmetry (together) and a
// Magnus moment were adopted as "needed with each of the tied effects" --
// the three together were, but beside the stiffness the record is at the
// noise without the Magnus moment, BIC 5.6 lower (beside the torque, 18.8
// higher). A step that only the followed tied effect needs goes with it
// (CompanionsWithinTie); then the torque explains the record worse than
// the effects found without it, and the three true effects are named.
TEST(Diagnose, AStepOnlyTheFollowedTiedEffectNeedsGoesWithIt) {
  if (testing::PlainBuildOnly())
    GTEST_SKIP() << "two runs, three effects; plain";
  const Diagnosis d =
      DiagnoseConfig("pair_stiffness_damping_asymmetry_draw56.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_FALSE(EffectIds(d.steps).count("magnus")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("nonlinear_damping")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("asymmetric_body")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("tunnel_stiffness") ||
              EffectIds(d.ambiguous).count("tunnel_stiffness"))
      << text;
  ExpectFinalCovers(d, kShortCoefficients, text);
}

// A roll moment's step has Eq. 39's tunnel terms among its rivals whatever
// the round's gap (RollPartRivals): their pitch and yaw moments projected
// on the body's roll axis are a roll torque. On draw 159's 3-s run of
// another body with a tunnel stiffness, a nonlinear damping and a body yaw
// asymmetry (tests/data/short_stiffness_damping_asymmetry_draw159.yaml,
// sigma: auto) a roll torque tied with a roll damping and a tunnel damping
// came 48.6 ahead of the stiffness at the first round (the stiffness's
// pitch and yaw parts want the asymmetry beside them), and a Magnus
// moment was added after the damping and the asymmetry. With those in,
// the stiffness in the torque's place is 3.0 above it: it joins the tie,
// and the Magnus moment, needed beside the torque and not beside the
// stiffness (+6.9 without it), goes with the torque.
TEST(Diagnose, ARollMomentsStepTiesWithTheTunnelTermsWhoseRollPartItIs) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_stiffness_damping_asymmetry_draw159.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.steps),
            (std::set<std::string>{"nonlinear_damping", "asymmetric_body"}))
      << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("tunnel_stiffness")) << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("roll_torque")) << text;
}

// The same case on draw 56 (t1 6.56e-4, t3 -2.30e-4, Cm_q_delta2 661,
// body yaw -0.22%; tests/data/short_stiffness_damping_asymmetry_draw56
// .yaml). A lag of the readings outdid every catalog effect at the first
// round; the catalog alone took the damping with a Magnus moment (a joint
// set) and tied a roll torque with the stiffness, 19.9 above the lag with
// the damping, the asymmetry and that tie beside it: `not_explained`,
// Cm_alpha 10.6 of its errors off. The Magnus moment is what the probe's
// answer does without; searched without it, the catalog names the
// asymmetry and the damping with the same tie, 24 lower in BIC, and the
// lag's model comes 4.3 above (alike).
TEST(Diagnose, TheCatalogIsSearchedWithoutWhatTheProbesAnswerDoesWithout) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  const Diagnosis d =
      DiagnoseConfig("short_stiffness_damping_asymmetry_draw56.yaml");
  ExpectAsymmetryAndDampingBesideAStiffnessTie(d, 660.8, 6.56e-4, -2.30e-4);
}

// tools/diagnose_suite's `short` tunnel damping (t2 1.65, t4 -2.24) +
// Magnus moment (Cm_p_alpha 3.37) + flow angularity (0.011, 0.013 deg),
// draw 31, kept as tests/data/short_damping_magnus_angularity_vary31.csv.
// A body yaw asymmetry led the first round by 29 in BIC and was named
// beside the angularity's tie with a roll reading error; searched without
// it, the damping and the Magnus moment explain the record, their final
// fit 15 lower in BIC, the complete models of the two 2.4 apart. A near
// tie's first step that the search without it matches within
// ambiguity_bic stands in a tie with what that search found. Since the
// first round also refits the candidates scored at its cut
// (ACandidateScoredAtTheCutIsRefittedToo) the damping and the Magnus
// moment beat the asymmetry in its place together, and the search
// without it (ReplacedStep) names them, 6.8 lower in BIC, with the
// angularity tied with a roll reading error: the asymmetry is named as
// what stood in for them, rejected.
TEST(Diagnose, ANearTiesFirstStepMatchedWithoutItTiesWithWhatWasFound) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("short_damping_magnus_angularity_vary31.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_FALSE(EffectIds(d.steps).count("asymmetric_body")) << text;
  EXPECT_EQ(EffectIds(d.steps),
            (std::set<std::string>{"magnus", "tunnel_damping"}))
      << text;
  EXPECT_TRUE(ListedWith(d.rejected, "asymmetric_body", "stood in")) << text;
  ExpectFinalCovers(d, kShortCoefficients, text);
  ExpectFinalCovers(d,
                    {{"Cm_p_alpha", 3.37},
                     {"tunnel_Cm_thetadot", 1.65},
                     {"tunnel_Cn_psidot", -2.24}},
                    text);
}

// tools/diagnose_suite's `short` tunnel damping + Magnus moment + flow
// angularity (draw 29: t2 -1.83, t4 2.48, Cm_p_alpha 3.89, theta_T 0.0123,
// psi_T -0.0140 deg), kept as tests/data/short_damping_magnus_angularity_
// draw29.csv. A body yaw asymmetry led the first round by 20 and was
// taken; after the angularity a lag of the readings outdid the damping and
// the Magnus moment and reached the noise: `not_explained`, Cm_q 36 of its
// errors off. Without the asymmetry the three explain the record, their
// complete model below the lag's (the angularity named, or tied with a roll
// reading error: TieGap).
TEST(Diagnose, AProbeAfterANearTiesFirstStepLosesToTheSearchWithoutIt) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  const Diagnosis d =
      DiagnoseRecord("short_damping_magnus_angularity_draw29.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectDampingMagnusWithAngularityOrItsTwin(d,
                                             {{"Cm_alpha", -0.23},
                                              {"Cm_q", -5.5},
                                              {"tunnel_Cm_thetadot", -1.83},
                                              {"tunnel_Cn_psidot", 2.48},
                                              {"Cm_p_alpha", 3.89},
                                              {"theta_T", 0.0123},
                                              {"psi_T", -0.0140}},
                                             text);
  EXPECT_TRUE(EffectIds(d.rejected).count("asymmetric_body")) << text;
  EXPECT_TRUE(EffectIds(d.rejected).count("reading_lag")) << text;
}

// tools/diagnose_suite's `coning` tunnel stiffness + roll reading error +
// flow angularity (draw 33), kept as tests/data/coning_stiffness_roll_
// error_angularity_draw33.yaml: over 68 deg of roll the angularity is a sum
// of the reading error's terms. It led the first round by 0.8 and tied;
// the reading error's side was 29 lower, and the search without the
// angularity is the answer (the reading error tied with a drift in time).
// Left out of that search, the angularity was never tried beside its
// model, where the record cannot exclude it: it is listed there now, and
// the final error bars cover it.
TEST(Diagnose, AnEffectASecondSearchLeftOutIsTriedBesideItsModel) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_stiffness_roll_error_angularity_draw33.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_TRUE(EffectIds(d.rejected).count("flow_angularity")) << text;
  EXPECT_TRUE(EffectIds(d.not_excluded).count("flow_angularity")) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}}, text);
}

// tools/diagnose_suite's `short` tunnel stiffness + roll reading error +
// flow angularity (draw 27), kept as tests/data/short_stiffness_roll_error_
// angularity_vary27.csv: the stiffness is added, the reading error ties
// with a trim moment (and a drift in time) and the final model holds it in
// the tie's place; the flow angularity is not excluded beside it. Each
// alternative's error bars cover the effects not excluded beside it; the
// one the final model is had kept its own (theta_cos_phi 0.0257 +- 0.0023
// deg, truth 0.0394: 6 of those errors).
TEST(Diagnose, TheFinalModelsAlternativeCoversWhatIsNotExcludedBesideIt) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("short_stiffness_roll_error_angularity_vary27.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  const auto roll = std::find_if(
      d.alternatives.begin(),
      d.alternatives.end(),
      [](const AlternativeModel& a) { return a.effect == "roll_interaction"; });
  ASSERT_NE(roll, d.alternatives.end()) << text;
  ASSERT_EQ(roll->fit, static_cast<int>(d.final_fit)) << text;
  ExpectCovers(roll->parameters,
               {{"theta_cos_phi", 0.0394},
                {"theta_sin_phi", -0.0236},
                {"psi_cos_phi", 0.0315},
                {"psi_sin_phi", -0.0158}},
               text);
}

// tools/diagnose_suite's `short` roll reading error + nonlinear damping at
// 0.003-deg noise (draw 0), kept as tests/data/short_roll_error_nonlinear_
// damping_noise3.csv. The damping drags Cm_q alone; its joint set with a
// flow angularity and a trim moment explains the record, and the trim
// moment ties with the reading error. Taken in the set's order, the flow
// angularity came before the tie and stayed in the final model, though
// beside the reading error it is not needed: over a quarter turn of roll
// a trim moment and a flow angularity together are what a roll reading
// error is. The tied member goes first (TakeJointSteps) and the
// angularity, which goes with the trim moment (TieCompanions), is not
// added.
TEST(Diagnose, AJointSetsMemberNeededOnlyBesideATiedOneIsNotAdded) {
  Case c = ShortConfig({testing::SourcePath(
      "tests/data/short_roll_error_nonlinear_damping_noise3.csv")});
  c.sigma = {0.003, 0.003, 0.003};
  const Diagnosis d = Diagnose(c, DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.003, 0.003, 0.003});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.steps), std::set<std::string>({"nonlinear_damping"}))
      << text;
  const std::set<std::string> tied = EffectIds(d.ambiguous);
  EXPECT_TRUE(tied.count("trim_moment") && tied.count("roll_interaction"))
      << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.23}}, text);
}

// tools/diagnose_suite's `short` roll reading error + nonlinear damping
// (draw 7), kept as tests/data/short_roll_error_nonlinear_damping_seed7.csv:
// the damping sized to 1.3 times the noise is Cm_q_delta2 = 1125, which
// changes Cm_q by 4.0 times its size at 8 deg, at the catalog's bound. The
// fit put it at 967 +- 83 with Cm_q at -4.73 (the two 99.96% correlated:
// only Cm_q + 0.0049 Cm_q_delta2 is determined), 4.02 times: refused,
// and the verdict was `not_explained` with the nominal fit's Cm_q 253 of
// its errors off. The nonlinear damping's bound is judged within two of
// its errors in the second search, as a tunnel term's on Eq. 43's ridge.
TEST(Diagnose, ANonlinearDampingAtItsBoundIsJudgedWithinItsErrors) {
  const Diagnosis d =
      DiagnoseRecord("short_roll_error_nonlinear_damping_seed7.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_TRUE(d.verdict == Verdict::kExplained ||
              d.verdict == Verdict::kAmbiguous)
      << text;
  std::set<std::string> found = EffectIds(d.steps);
  for (const auto* fits : {&d.ambiguous, &d.not_excluded}) {
    for (const std::string& id : EffectIds(*fits)) found.insert(id);
  }
  EXPECT_TRUE(found.count("nonlinear_damping")) << text;
  for (const std::string& id : EffectIds(d.steps)) {
    EXPECT_TRUE(id == "nonlinear_damping" || id == "roll_interaction") << text;
  }
  ExpectFinalCovers(d, kShortCoefficients, text);
}

// Judged within its errors, a nonlinear damping moves along its ridge with
// Cm_q (RidgeMoves): on a 3-s run with a damping of 3.6 times |Cm_q| at 6
// deg (tests/data/short_nonlinear_damping_varied104.yaml), fitted at 4.9
// times, Cm_q_delta2 and Cm_q of one sign, shrunk alone it stayed past
// the bound of 4 and the record was left `not_explained`, Cm_q 22 of its
// errors off; followed by Cm_q it is within it, and named. (Cm_q is not
// checked: the true model's own fit has it 3.0 of its errors off, the
// noise's draw.)
TEST(Diagnose, ANonlinearDampingIsJudgedAlongItsRidge) {
  const Diagnosis d = DiagnoseConfig("short_nonlinear_damping_varied104.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kExplained) << text;
  EXPECT_EQ(EffectIds(d.steps), std::set<std::string>({"nonlinear_damping"}))
      << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.2207}, {"Cm_q_delta2", -1078.0}}, text);
}

// The same coning record on draw 9 (tests/data/coning_roll_error_
// nonlinear_damping_seed9.csv). The damping, which alone dragged Cm_q, is
// adopted in a joint set with a flow angularity and a trim moment; the
// trim moment ties with the reading error. Beside the trim moment the
// angularity was pruned, yet the final model (the one before the tie)
// kept it: a false effect. It now goes with the tie (partial, not
// excluded), and only the damping is added.
TEST(Diagnose, AStepPrunedBesideTheTieIsNotAddedBeforeIt) {
  const Diagnosis d =
      DiagnoseRecord("coning_roll_error_nonlinear_damping_seed9.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_FALSE(EffectIds(d.steps).count("flow_angularity")) << text;
  ExpectTruthAddedOrTied(d, {"roll_interaction", "nonlinear_damping"});
}

// tools/diagnose_suite's `coning` tunnel stiffness + roll reading error +
// flow angularity (draw 3), kept as tests/data/coning_stiffness_roll_error_
// angularity_seed3.csv. The true model's own residual has a periodogram
// peak 5.3 times the mean but 28 times its neighbours, which the fit had
// emptied: the local line test called it structure, no model reached the
// noise, and the verdict was `not_explained`. The neighbourhood's mean is
// now at least half the periodogram's (CheckResiduals).
TEST(Diagnose, TheFitsEmptiedBinsRaiseNoLineOnATrueModel) {
  const Diagnosis d =
      DiagnoseRecord("coning_stiffness_roll_error_angularity_seed3.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_TRUE(d.verdict == Verdict::kExplained ||
              d.verdict == Verdict::kAmbiguous)
      << text;
  const std::set<std::string> tied = EffectIds(d.ambiguous);
  EXPECT_TRUE(tied.count("roll_interaction")) << text;
}

// The same case on draw 4 (tests/data/coning_stiffness_roll_error_
// angularity_seed4.csv): beside a trim moment (tied with the reading error
// and the angularity) the tunnel stiffness lowers BIC by 78 on Eq. 43's
// ridge at t1 = t3 = -0.134 +- 0.048 (truth 1.8e-4, -6.2e-5; the true
// model's own fit lands there too), past its bound (0.115) at the point
// fit: refused, and the verdict was `not_explained`. The second search
// judges a tunnel term's bounds, on Eq. 43's ridge, within two of its
// errors (FromBounds, bounds_within_errors): the record is explained, the
// tunnel stiffness beside the tie, and the final error bars cover Cm_alpha.
TEST(Diagnose, AnEffectOnItsRidgeIsJudgedWithinItsErrorsWhenNothingExplains) {
  const Diagnosis d =
      DiagnoseRecord("coning_stiffness_roll_error_angularity_seed4.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  const std::set<std::string> tied = EffectIds(d.ambiguous);
  EXPECT_TRUE(tied.count("roll_interaction") && tied.count("flow_angularity"))
      << text;
  std::set<std::string> beside = EffectIds(d.steps);
  for (const auto& ids : {EffectIds(d.partial), EffectIds(d.not_excluded)}) {
    beside.insert(ids.begin(), ids.end());
  }
  EXPECT_TRUE(beside.count("tunnel_stiffness")) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}}, text);
}

// tools/diagnose_suite's `pair` bearing moment + calibration error + roll
// torque (draw 2), kept as tests/data/pair_bearing_calibration_roll_
// torque.yaml. Alone, the calibration error reached 0.263 deg at 8.2 deg
// (bound 0.246) and the bearing moment's angle ran to 8.3 deg, each
// taking up the other; the search ended `not_explained` with Cm_alpha 6.1
// of its errors off. A second search lets an effect out of its bounds
// lead a joint set (FromBounds): the bearing moment and the calibration
// error are added. The roll torque's place may go to a roll damping: with
// the others in, the swap raises BIC by 9.7-10.1 (as the search's fits
// stop a little sooner or later) against ambiguity_bic's 10, so `explained`
// with the roll torque and `ambiguous` between the two are both right.
// Along the bearing moment's ridge (angle 2.2 +- 1.6 deg, truth 1)
// Cm_bearing's error bar is its profile's (CheckRidges) and covers the
// truth.
TEST(Diagnose, AnEffectOutOfItsBoundsLeadsAJointSetWhenNothingElseExplains) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "two runs; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_bearing_calibration_roll_torque.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  const std::set<std::string> both = {"bearing_moment",
                                      "calibration_nonlinearity"};
  if (d.verdict == Verdict::kAmbiguous) {
    EXPECT_EQ(EffectIds(d.steps), both) << text;
    EXPECT_EQ(EffectIds(d.ambiguous),
              std::set<std::string>({"roll_damping", "roll_torque"}))
        << text;
  } else {
    ASSERT_EQ(d.verdict, Verdict::kExplained) << text;
    std::set<std::string> three = both;
    three.insert("roll_torque");
    EXPECT_EQ(EffectIds(d.steps), three) << text;
  }
  // The search's fit of the final model stopped by its BIC rule (10
  // iterations); the model reported is taken on to the user's (42).
  EXPECT_EQ(d.FinalFit().termination.find("BIC"), std::string::npos)
      << d.FinalFit().termination;
  ExpectFinalCovers(d,
                    {{"Cm_alpha", -0.23},
                     {"Cm_q", -5.5},
                     {"Cm_bearing", -0.00327},
                     {"theta_cal3", 0.0461}},
                    text);
}

// The same case on draw 28 (Cm_bearing -0.0055 at 1 deg, theta_cal3
// 0.0496 deg, 0.218 deg at the record's 8.19 deg), kept as tests/data/pair_
// bearing_calibration_roll_torque_draw28.yaml. With the roll torque and the
// bearing moment in, the calibration error lowers BIC by 240 but its fit
// reaches 0.254 +- 0.013 deg there, past the bound of 0.246 at the point
// fit; the second search judges only the effects on a ridge within their
// errors, and both ended `not_explained`, the final (nominal) Cm_alpha 6.9
// of its errors off. A third judges every effect so: the record is
// explained or tied, and the final error bars cover the truth.
TEST(Diagnose, AThirdSearchJudgesEveryBoundWithinItsErrors) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "two runs; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_bearing_calibration_roll_torque_draw28.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_NE(d.verdict, Verdict::kNotExplained) << text;
  EXPECT_NE(d.verdict_text.find("every effect's bounds judged within two "
                                "of its errors"),
            std::string::npos)
      << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}}, text);
}

// tools/diagnose_suite's `coning` bearing moment + calibration error + roll
// torque (draw 29), kept as tests/data/coning_bearing_calibration_roll_
// torque_draw29.yaml: the bearing moment, 72 lower in BIC, is refused for
// moving Cm_alpha by 148 of its errors, and leads a joint set. Its pool by
// BIC (the calibration, a roll damping and a roll torque, the two last
// lowering BIC by 8.1 alone, lesser refits that join no triple) reaches the
// noise but no set of it earns its place; its pool by score takes the
// roll damping into a triple that does. At one spin rate a roll damping
// and a roll torque are one constant roll acceleration (8.07993 and
// 8.07981 lower in BIC alone): the set's roll damping ties with the roll
// torque among the lesser refits, and neither is named. Before the pool
// by score the record ended `not_explained`, the nominal Cm_alpha 97 of
// its errors off.
TEST(Diagnose, ALesserRefitInAJointSetTiesWithItsTwins) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_bearing_calibration_roll_torque_draw29.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  const std::set<std::string> tied = EffectIds(d.ambiguous);
  EXPECT_TRUE(tied.count("roll_torque") && tied.count("roll_damping")) << text;
  EXPECT_EQ(
      EffectIds(d.steps),
      (std::set<std::string>{"bearing_moment", "calibration_nonlinearity"}))
      << text;
  ExpectFinalCovers(
      d, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}, {"theta_cal3", 0.02}}, text);
}

// tools/diagnose_suite's `short` bearing moment + cubic calibration error +
// roll torque on another body (draw 155, sigma: auto; tests/data/short_
// bearing_calibration_roll_torque_draw155.yaml). The calibration came
// first as the signed square, then the bearing moment; beside the roll
// torque the search took the calibration back to the cube, and the roll
// torque tied with a tunnel damping. The final model, the one before the
// tie, still held the signed square: the true cube held at zero in the
// answer while both complete models held it. The final model holds each
// effect in its own form where the complete model does
// (OwnFormsBeforeTie).
TEST(Diagnose, AFinalModelWithoutATiedEffectHoldsTheCompleteModelsForm) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  const Diagnosis d =
      DiagnoseConfig("short_bearing_calibration_roll_torque_draw155.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("roll_torque")) << text;
  EXPECT_EQ(
      EffectIds(d.steps),
      (std::set<std::string>{"bearing_moment", "calibration_nonlinearity"}))
      << text;
  const ParameterEstimate* cube =
      SharedEstimate(d.FinalFit().parameters, "theta_cal3");
  const ParameterEstimate* square =
      SharedEstimate(d.FinalFit().parameters, "theta_cal2");
  ASSERT_TRUE(cube != nullptr && square != nullptr) << text;
  EXPECT_TRUE(cube->free) << text;
  EXPECT_FALSE(square->free) << text;
  ExpectFinalCovers(
      d,
      {{"Cm_alpha", -0.2462}, {"Cm_q", -3.751}, {"theta_cal3", -0.02814}},
      text);
}

// `d` (a Table 6 record) adds the bearing moment and the calibration error
// beside a tie of a roll damping and a roll torque (twins at constant
// spin), its final model covering Cm_alpha, Cm_q and the calibration's
// `terms`.
void ExpectBearingAndCalibrationBesideTheRollTie(
    const Diagnosis& d, const std::map<std::string, double>& terms) {
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.ambiguous),
            (std::set<std::string>{"roll_damping", "roll_torque"}))
      << text;
  EXPECT_EQ(
      EffectIds(d.steps),
      (std::set<std::string>{"bearing_moment", "calibration_nonlinearity"}))
      << text;
  std::map<std::string, double> truths = {{"Cm_alpha", -0.236}, {"Cm_q", -4.0}};
  truths.insert(terms.begin(), terms.end());
  ExpectFinalCovers(d, truths, text);
}

// tools/diagnose_suite's Table 6 bearing moment + calibration error + roll
// torque (draw 30; tests/data/table6_bearing_calibration_roll_torque_
// draw30.yaml). A roll damping and a roll torque score alike (795.922:
// at the nominal fit's constant spin, one direction) and came fifth and
// sixth; with five refitted a round, the roll damping alone was weighed
// and named (BIC 962 lower) and the roll torque never was. Score twins
// are refitted together: the two lower BIC alike, and they tie.
TEST(Diagnose, ScoreTwinsAreRefittedTogether) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "48-s record; plain build";
  const Diagnosis d =
      DiagnoseConfig("table6_bearing_calibration_roll_torque_draw30.yaml");
  ExpectBearingAndCalibrationBesideTheRollTie(
      d, {{"theta_cal3", -0.0810}, {"psi_cal3", 0.0746}});
}

// tools/diagnose_suite's `coning` Magnus moment + nonlinear damping +
// calibration nonlinearity (draw 29), kept as tests/data/coning_magnus_
// damping_calibration_draw29.yaml. The damping, 115 lower in BIC alone, is
// refused for moving Cm_q 21.9 of its errors and leads a joint set; its
// pool by BIC (Magnus 9.0, a body yaw asymmetry 4.8, a tunnel damping 3.3)
// reaches a probable error of 1.44 at best (limit 1.18) and the record
// ended `not_explained`, Cm_q 65 of its nominal errors off. The
// calibration, 1.5 higher in BIC alone but fourth by score, is in the pool
// by score, whose union reaches 0.98: the three are named.
TEST(Diagnose, AJointPoolDrawsOnTheScoresWhenItsBicPoolCannotReachTheNoise) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_magnus_damping_calibration_draw29.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(
      d,
      {"magnus", "nonlinear_damping", "calibration_nonlinearity"},
      {{"Cm_alpha", -0.23},
       {"Cm_q", -5.5},
       {"Cm_p_alpha", -92.0},
       {"Cm_q_delta2", -157.0},
       {"theta_cal3", 0.0389}},
      text);
}

// The same three on draw 34 (tests/data/coning_magnus_damping_calibration_
// draw34.yaml): the calibration scored too little at the round to be
// refitted (the Magnus moment second at 10.8, the calibration below the
// five), and both pools stopped at a probable error of 1.42 (limit 1.18):
// `not_explained`, the nominal Cm_q -10.0. At the damping's own fit the
// Magnus moment (14.3) and the calibration (13.7) score highest: the
// lead's pool (LeadPool) names the three. On draw 35's record (_draw35)
// the calibration came third there, after a tunnel damping: three drawn.
TEST(Diagnose, AJointSetsLeadDrawsAPoolFromTheScoresAtItsOwnFit) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const struct {
    const char* config;
    double magnus, damping, calibration;
  } records[] = {
      {"coning_magnus_damping_calibration_draw34.yaml", -96.0, -131.2, 0.0404},
      {"coning_magnus_damping_calibration_draw35.yaml", -87.5, -120.7, 0.0319},
  };
  for (const auto& r : records) {
    const Diagnosis d = DiagnoseConfig(r.config);
    const std::string text =
        r.config + ("\n" + FormatDiagnosis(d, {0.01, 0.01, 0.01}));
    ExpectNamedExactly(
        d,
        {"magnus", "nonlinear_damping", "calibration_nonlinearity"},
        {{"Cm_alpha", -0.23},
         {"Cm_q", -5.5},
         {"Cm_p_alpha", r.magnus},
         {"Cm_q_delta2", r.damping},
         {"theta_cal3", r.calibration},
         {"psi_cal3", -r.calibration}},
        text);
  }
}

// The same three on draw 52 (tests/data/coning_magnus_damping_calibration_
// draw52.yaml): at the damping's own fit the calibration scored fourth
// (8.0, after the Magnus moment 17.1, a tunnel stiffness 12.9 and a tunnel
// damping 12.5), every pool's union stopped at a probable error of 1.22
// (limit 1.18), and the record ended `not_explained`, Cm_q 3.0 of its
// errors off. At the union's own fit the calibration scores highest: the
// pool widened by it (UnionPool) reaches 0.94 and names the three.
TEST(Diagnose, AJointSetsLeadWidensItsPoolByTheScoresAtItsUnion) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_magnus_damping_calibration_draw52.yaml");
  ExpectNamedExactly(
      d,
      {"magnus", "nonlinear_damping", "calibration_nonlinearity"},
      {{"Cm_alpha", -0.23},
       {"Cm_q", -5.5},
       {"Cm_p_alpha", -80.0},
       {"Cm_q_delta2", -115.1},
       {"theta_cal3", 0.0303},
       {"psi_cal3", -0.0303}},
      FormatDiagnosis(d, {0.01, 0.01, 0.01}));
}

// The same three on draw 56 (Cm_p_alpha 65.4, Cm_q_delta2 -87.5,
// calibration 0.0174 deg; tests/data/coning_magnus_damping_calibration_
// draw56.yaml). The damping dragged Cm_q and led; its pool by BIC (the
// Magnus moment, a tunnel damping, the calibration) held only lesser
// refits, which JointSets leaves out of triples, so its pairs alone were
// fitted (1.31, limit 1.18); the same three drawn by the damping's own
// scores counted as tried, and the record ended `not_explained` with the
// truth's model 157 lower in BIC. A pool whose triples were not all tried
// is drawn again from the lead's scores: the damping and the calibration
// are named, the Magnus moment tied with a tunnel damping (on a circular
// cone their signatures are alike).
TEST(Diagnose, ALeadPoolWhoseTriplesWereNotTriedIsDrawnAgain) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_magnus_damping_calibration_draw56.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_NE(d.verdict, Verdict::kNotExplained) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("nonlinear_damping")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("calibration_nonlinearity")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("magnus") ||
              EffectIds(d.ambiguous).count("magnus"))
      << text;
  ExpectFinalCovers(d, kShortCoefficients, text);
  ExpectCovers(
      d.final_parameters,
      {{"Cm_q_delta2", -87.5}, {"theta_cal3", -0.0174}, {"psi_cal3", 0.0174}},
      text);
}

// The pool a lead draws from its own scores has no round's BIC behind its
// members: each must show in the set's fit (MembersShow). On draw 28's
// pair of runs with a signed-square calibration error (tests/data/pair_
// calibration_signed_square_draw28.yaml; a form outside the catalog), the
// cube dragged Cm_alpha and led; with a bearing moment from its scores it
// reached the noise, Cm_bearing -0.0017 +- 0.0094 and bearing_angle 0.96
// +- 6.3 deg, and both were named. The record stays `not_explained` (with
// the catalog's own forms only: the effect's other form names it).
TEST(Diagnose, ALeadPoolsMemberThatDoesNotShowIsNotAdopted) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "two runs; plain build";
  const Diagnosis d =
      DiagnoseConfigOwnForms("pair_calibration_signed_square_draw28.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kNotExplained) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}}, text);
}

// The same case on draw 58 (Cm_bearing -0.00145 at 1 deg, theta_cal3
// 0.0711, psi_cal3 -0.0847; tests/data/table6_bearing_calibration_roll_
// torque_draw58.yaml). After the roll torque (tied with the roll
// damping) a joint set of three, led by a nonlinear stiffness, reached the
// noise with the bearing moment and the calibration error; in the explained
// model the stiffness was redundant (pruned), and it ended the steps adopted
// after the tie: nothing was added, the three left partial. A redundant step
// no longer ends them (the stiffness then needed in no complete model is
// pruned within the tie). The torque's complete model had stopped 23 in BIC
// above the damping's, its bearing angle stuck where the stiffness had left
// it (0.28 +- 437 deg); fitted from the damping's side it reaches it.
TEST(Diagnose, ARedundantStepDoesNotEndWhatIsAdoptedAfterATie) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "48-s record; plain build";
  const Diagnosis d =
      DiagnoseConfig("table6_bearing_calibration_roll_torque_draw58.yaml");
  ExpectBearingAndCalibrationBesideTheRollTie(
      d, {{"theta_cal3", 0.0711}, {"psi_cal3", -0.0847}});
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_TRUE(d.final.at_noise_level) << text;
  // The sides of the tie alike, and each with the bearing moment's terms
  // determined and covering the truth.
  ASSERT_EQ(d.alternatives.size(), 2u) << text;
  EXPECT_NEAR(d.alternatives[0].check.probable_error,
              d.alternatives[1].check.probable_error,
              1e-3)
      << text;
  for (const AlternativeModel& a : d.alternatives) {
    ExpectCovers(
        a.parameters, {{"Cm_bearing", -0.00145}, {"bearing_angle", 1.0}}, text);
    EXPECT_LT(SharedEstimate(a.parameters, "bearing_angle")->standard_error,
              0.5)
        << text;
  }
}

// The Table 6 record of the same three (draw 33; tests/data/table6_magnus_
// damping_calibration_draw33.yaml): the damping leads a joint set, and a
// roll torque and a roll damping, score twins (44.4466), filled its pool
// beside the Magnus moment by BIC and by score alike, the calibration
// (14.6, -0.9 in BIC alone) fourth: `not_explained`. The pool by score
// draws one of twins: the three are named.
TEST(Diagnose, AJointPoolByScoreDrawsOneOfScoreTwins) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "48-s record; plain build";
  const Diagnosis d =
      DiagnoseConfig("table6_magnus_damping_calibration_draw33.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(
      d,
      {"magnus", "nonlinear_damping", "calibration_nonlinearity"},
      {{"Cm_alpha", -0.236},
       {"Cm_q", -4.0},
       {"Cm_p_alpha", 0.100},
       {"Cm_q_delta2", -116.3},
       {"theta_cal3", 0.0705},
       {"psi_cal3", 0.0742}},
      text);
}

// tools/diagnose_suite's `pair` signed-square calibration error (draw 24;
// tests/data/pair_calibration_signed_square_draw24.yaml), a form outside
// the catalog: no effect earns its place, and the calibration nonlinearity
// (the cube) is refused for moving Cm_q toward the truth by many of its
// errors. The record ends `not_explained` with the nominal fit, whose Cm_q
// stands 10.5 of its own errors off; its error bars cover the dragged
// contender's model at its Akaike weight (refused_for_drag). With the
// catalog's own forms only: the effect's other form names the record.
TEST(Diagnose, AContenderRefusedForItsDragWidensAnUnexplainedRecordsErrorBars) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "two runs; plain build";
  const std::string config = "pair_calibration_signed_square_draw24.yaml";
  const Diagnosis d = DiagnoseConfigOwnForms(config);
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kNotExplained) << text;
  EXPECT_TRUE(std::count(d.refused_for_drag.begin(),
                         d.refused_for_drag.end(),
                         "calibration_nonlinearity"))
      << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}}, text);
  ASSERT_EQ(d.model_standard_errors.count("Cm_q"), 1u) << text;
  const ParameterEstimate* own =
      SharedEstimate(d.FinalFit().parameters, "Cm_q");
  ASSERT_NE(own, nullptr);
  EXPECT_GT(std::abs(own->value + 5.5),
            3.0 * d.model_standard_errors.at("Cm_q"))
      << "the nominal fit's own error bar covered the truth already\n"
      << text;
  const nlohmann::json j = nlohmann::json::parse(DiagnosisJson(
      d, LoadConfig(testing::SourcePath("tests/data/" + config))));
  EXPECT_EQ(j["refused_for_drag"], nlohmann::json(d.refused_for_drag));
}

// The same case on draw 32 (tests/data/pair_bearing_calibration_roll_
// torque_draw32.yaml), searched once, without joint sets: a roll torque
// and a false body yaw asymmetry leave the record structured, a reading
// lag (a probe) outdoes every catalog effect, and the bearing moment, 205
// lower in BIC at that round, is refused for moving Cm_alpha toward the
// truth (-0.2306 -> -0.2294). The final model is the nominal fit, Cm_alpha
// 6.8 of its errors off; the contenders refused for their drag widen its
// error bars where a probe outdoes the catalog too.
TEST(Diagnose, AContenderRefusedForItsDragWidensTheErrorBarsBesideAProbe) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "two runs; plain build";
  DiagnoseOptions once;
  once.joint_sets = false;
  const Diagnosis d = Diagnose(
      LoadConfig(testing::SourcePath(
          "tests/data/pair_bearing_calibration_roll_torque_draw32.yaml")),
      once);
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kNotExplained) << text;
  EXPECT_FALSE(d.outside_catalog.effect.empty()) << text;
  EXPECT_TRUE(std::count(
      d.refused_for_drag.begin(), d.refused_for_drag.end(), "bearing_moment"))
      << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}}, text);
}

// The same case on draw 126 (tests/data/pair_bearing_calibration_roll_
// torque_vary126.yaml). At the first round the calibration and a tunnel
// stiffness leave their bounds alone, each taking up the bearing moment's
// part, and the bearing moment drags Cm_alpha. In the search with effects
// out of their bounds leading joint sets (FromBounds) the stiffness led
// first, and its set with the calibration and the bearing moment earned
// its place: `explained` with a false tunnel stiffness, the roll torque
// left out, the true model 63.8 lower in BIC. The set's other members
// lead their own sets too (OtherMembersLead), the lowest in BIC kept: led
// by the calibration, the set holds the roll torque, and the record ends
// named, or tied where the roll torque's look-alike (Eq. 39's roll part
// of a tunnel damping) ties with it.
TEST(Diagnose, AJointSetsOtherMembersLeadInTurnWhereBoundsLead) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "two runs; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_bearing_calibration_roll_torque_vary126.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_NE(d.verdict, Verdict::kNotExplained) << text;
  const std::set<std::string> steps = EffectIds(d.steps);
  EXPECT_EQ(steps.count("tunnel_stiffness"), 0u) << text;
  EXPECT_EQ(steps.count("bearing_moment"), 1u) << text;
  EXPECT_EQ(steps.count("calibration_nonlinearity"), 1u) << text;
  // Named, or tied with its look-alike, the roll torque held in the
  // final model (a stand-in for the tie) or not.
  EXPECT_TRUE(steps.count("roll_torque") ||
              EffectIds(d.ambiguous).count("roll_torque"))
      << text;
  std::map<std::string, double> truths = {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}};
  const ParameterEstimate* torque =
      SharedEstimate(d.FinalFit().parameters, "Cl_0");
  if (torque != nullptr && torque->free) truths["Cl_0"] = 2.611376e-7;
  ExpectFinalCovers(d, truths, text);
}

// The same record searched in full: the third search (every bound judged
// within two errors) admits the calibration error alone at 0.349 deg at
// 8.2 deg (bound 0.246) and then judged it at its point fit once others
// joined it, refusing the bearing moment beside it (0.249) and the three
// fitted as one (0.250 +- 0.012, truth 0.215, where the true model's own
// fit lands): `not_explained`. An effect admitted within its errors is
// now judged so beside others (ImplausibleAmongAsJudged): the three are
// named.
TEST(Diagnose, AnEffectAdmittedWithinItsErrorsIsJudgedSoBesideOthers) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "two runs; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_bearing_calibration_roll_torque_draw32.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(
      d,
      {"bearing_moment", "calibration_nonlinearity", "roll_torque"},
      {{"Cm_alpha", -0.23},
       {"Cm_q", -5.5},
       {"Cm_bearing", -0.00451},
       {"theta_cal3", 0.0486},
       {"Cl_0", -2.99e-7}},
      text);
}

// tools/diagnose_suite's `coning` Magnus moment + nonlinear damping +
// calibration nonlinearity (draw 42, --vary; tests/data/coning_magnus_
// damping_calibration_draw42.yaml). On the steady cone the Magnus moment
// keeps 0.014% of its information apart from the free parameters: no fit
// sees it, the calibration alone is named, and Cm_q carries the moment
// (-0.24 +- 0.009 own against a truth of -5.5). The answer lists it among
// the effects not seen apart from the coefficients, in the text too.
TEST(Diagnose, AnEffectTheCoefficientsAbsorbIsListedAsUnseen) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_magnus_damping_calibration_draw42.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  const auto magnus = std::find_if(
      d.coefficient_twins.begin(),
      d.coefficient_twins.end(),
      [](const CoefficientTwin& t) { return t.score.effect == "magnus"; });
  ASSERT_NE(magnus, d.coefficient_twins.end()) << text;
  EXPECT_LT(magnus->score.novelty, 0.01) << text;
  EXPECT_NE(text.find("not seen apart from the fitted coefficients: magnus"),
            std::string::npos)
      << text;
  // It says what the fitted Cm_q stands for, and that holds: refitted with
  // the Magnus moment held at m, Cm_q moves by -per_unit m.
  ASSERT_TRUE(magnus->in_final_model) << text;
  ASSERT_EQ(magnus->shifts.size(), 1u) << text;
  const TwinShift& shift = magnus->shifts[0];
  EXPECT_EQ(shift.term, "Cm_p_alpha");
  EXPECT_EQ(shift.parameter, "Cm_q");
  EXPECT_NE(text.find("the fitted Cm_q stands for Cm_q "), std::string::npos)
      << text;
  Case held = CaseAtSolution(d.final_case, d.FinalFit());
  constexpr double kHeld = -20.0;
  held.parameters[FindParameter(held.model, "Cm_p_alpha")] =
      ParameterSetting{kHeld, false};
  std::vector<TimeHistory> data;
  for (const SegmentFit& segment : d.FinalFit().segments) {
    data.push_back(segment.data);
  }
  const FitResult refit = FitSamples(held, data);
  const double moved = SharedEstimate(refit.parameters, "Cm_q")->value -
                       SharedEstimate(d.FinalFit().parameters, "Cm_q")->value;
  EXPECT_NEAR(moved, -shift.per_unit * kHeld, 0.02 * std::abs(moved)) << text;
  // Eq. 43's tunnel terms, twins on every record, are not listed.
  for (const CoefficientTwin& t : d.coefficient_twins) {
    EXPECT_NE(t.score.effect, "tunnel_stiffness") << text;
    EXPECT_NE(t.score.effect, "tunnel_damping") << text;
  }
}

// `d`'s final model lists `effect` as a twin of Cm_q alone, its fitted
// Cm_q is 10 or more of its errors from `true_cmq`, and within 3 of what
// it stands for (Cm_q + per_unit times `true_term`), which the answer
// says.
void ExpectCmqCarries(const Diagnosis& d,
                      const std::string& effect,
                      double true_cmq,
                      double true_term,
                      const std::string& text) {
  const auto twin = std::find_if(
      d.coefficient_twins.begin(),
      d.coefficient_twins.end(),
      [&](const CoefficientTwin& t) { return t.score.effect == effect; });
  ASSERT_NE(twin, d.coefficient_twins.end()) << text;
  EXPECT_TRUE(twin->in_final_model) << text;
  ASSERT_EQ(twin->shifts.size(), 1u) << text;
  EXPECT_EQ(twin->shifts[0].parameter, "Cm_q");
  const ParameterEstimate* cm_q =
      SharedEstimate(d.FinalFit().parameters, "Cm_q");
  ASSERT_NE(cm_q, nullptr);
  EXPECT_GT(std::abs(cm_q->value - true_cmq), 10.0 * cm_q->standard_error)
      << text;
  const double carried = true_cmq + twin->shifts[0].per_unit * true_term;
  EXPECT_LT(std::abs(cm_q->value - carried), 3.0 * cm_q->standard_error)
      << text;
  EXPECT_NE(text.find("the fitted Cm_q stands for Cm_q + "), std::string::npos)
      << text;
}

// A record at the noise with nothing added lists its nominal fit's near
// twins too: the `short` run of another body (tests/data/short_weak_
// nonlinear_damping_varied78.yaml, Cm_q -1.967) with a nonlinear damping
// of 114.36 that leaves the fit without it at 1.04 times the noise. The
// fitted Cm_q is 55 of its errors from the true one; what it stands for
// (Cm_q + per_unit Cm_q_delta2) is within 3.
TEST(Diagnose, ANoiseLevelAnswerSaysWhatItsCoefficientsCarry) {
  const Diagnosis d =
      DiagnoseConfig("short_weak_nonlinear_damping_varied78.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kNoiseLevel) << text;
  ExpectCmqCarries(d, "nonlinear_damping", -1.967, 114.36, text);
}

// tools/diagnose_suite's `short` tunnel stiffness + nonlinear damping +
// body yaw asymmetry (draw 35, --vary; tests/data/short_stiffness_damping_
// asymmetry_draw35.yaml), its nominal fit 3.7 times the noise off. Its
// refits had taken the growing windows from there (kNearSolution was 3),
// which stopped the stiffness short of its minimum along Eq. 43's ridge
// (BIC 83.1 lower than the nominal fit); the first answer was then a tie
// of a roll torque and a tunnel damping, nothing added, and past the
// noise the three were named. Refitted from the solution (kNearSolution
// 10) the stiffness reaches its minimum (94.1 lower, t1 2.1 +- 0.96,
// Cm_alpha with it along the ridge, out of its bounds) and the first
// search names the asymmetry and the damping and ties the stiffness with
// a roll torque and a tunnel damping: the answer of this class on every
// suite draw whose nominal fit starts below 3 times the noise.
TEST(Diagnose, AStiffnessAtItsRidgesMinimumTiesWithRollEffects) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_stiffness_damping_asymmetry_draw35.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.steps),
            std::set<std::string>({"asymmetric_body", "nonlinear_damping"}))
      << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("tunnel_stiffness")) << text;
  ExpectFinalCovers(
      d, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}, {"Cm_q_alpha2", 937.5}}, text);
  const auto stiffness = std::find_if(d.tie_models.begin(),
                                      d.tie_models.end(),
                                      [](const Diagnosis::TieModel& m) {
                                        return m.effect == "tunnel_stiffness";
                                      });
  ASSERT_NE(stiffness, d.tie_models.end()) << text;
  ExpectCovers(stiffness->parameters,
               {{"tunnel_Cm_theta", 1.04e-3}, {"tunnel_Cn_psi", -3.64e-4}},
               text);
}

// The same case on draw 60 (t1 1.03e-3, t3 -3.61e-4, Cm_q_delta2 386.8,
// body yaw -0.37%; tests/data/short_stiffness_damping_asymmetry_draw60
// .yaml). The first search named the asymmetry and a tunnel damping (t2
// 4.4 +- 2.6, false), the nonlinear damping lowering BIC by 22.7 beside
// them; past the noise the damping earned its place and the tunnel damping
// tied with the tunnel stiffness, but only an explained second answer could
// replace an explained first. Now a tie can, by the ambiguous answer's
// rule (its complete model lower, counting what lowers BIC beside each).
TEST(Diagnose, AnExplainedAnswerGivesWayToATiePastTheNoise) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_stiffness_damping_asymmetry_draw60.yaml");
  ExpectAsymmetryAndDampingBesideAStiffnessTie(d, 386.8, 1.03e-3, -3.61e-4);
}

// The same case on draw 62 (t1 8.69e-4, t3 -3.04e-4, Cm_q_delta2 895.7,
// body yaw -0.25%; tests/data/short_stiffness_damping_asymmetry_draw62
// .yaml). The asymmetry, refused at the first step for moving Cm_alpha,
// lost to a Magnus moment; swapped in for it at the end the asymmetry
// lowered BIC by 37, a tie left open and not adopted. Past the noise a
// false bearing moment made the Magnus moment look better, and it was
// named beside a five-way tie. A tie whose rival outdid the followed
// effect so is searched without it (OutdoneSwapBranch). That had named
// the asymmetry and the damping, the stiffness tied with its Eq. 39 twins,
// but only because a tunnel term in a joint set was looked up by its alias
// and never showed (EffectCatalog.TermsGoByTheNamesFitsReport). Now the
// asymmetry, the damping and a tunnel damping earn their place together
// (BIC 50.0; the true stiffness in its place 39.7, t1 0.39 on Eq. 43's
// ridge, out of its bounds); the tunnel damping, outdone in a swap by
// 10.3, is searched without, and that answer, 0.9 lower, names a roll
// torque and the damping, the asymmetry tied with a Magnus moment, short
// of the noise. Not the truth, but not a confident answer either: the
// asymmetry stays in the tie and the final error bars cover the body's
// coefficients. The search is that close to its turns: since the 70th
// session's sines and cosines (angles.h, within two units in the last
// place of the library's) the asymmetry, the damping and a roll torque
// earn their place together, and the torque ties with the true stiffness
// (its model 3.4 lower) and a tunnel damping: the asymmetry named, the
// stiffness in the tie (OutdoneSwapBranch is no longer reached here; it
// runs on other kept records, ATieOutdoneOnItsOtherSideIsSearchedWith-
// outItsLead's among them). Since the 80th session's search step (its
// fits at 8 ms where the config says 2, each within a tenth of its errors
// of the fit at 2 ms) the asymmetry ties with a Magnus moment again, as it
// had before the 70th session: named or tied, never left out.
TEST(Diagnose, AnEffectOutdoneInASwapIsSearchedWithout) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_stiffness_damping_asymmetry_draw62.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("nonlinear_damping")) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("asymmetric_body") ||
              TiedIds(d).count("asymmetric_body"))
      << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("tunnel_stiffness")) << text;
  ExpectCovers(d.final_parameters, kShortCoefficients, text);
}

// The same case on draw 64 (t1 -9.69e-4, t3 3.39e-4, Cm_q_delta2 -640.6,
// body yaw -0.30%; tests/data/short_stiffness_damping_asymmetry_draw64
// .yaml). A roll damping tied four ways (a roll torque, a tunnel damping,
// the tunnel stiffness); after it the asymmetry and the damping reached
// the noise, but were not adopted: with the tunnel damping in the roll
// damping's place Cm_q slid along Eq. 43's ridge to -0.33, and the
// nonlinear damping's bound, 4 times |Cm_q|, refused it there. The bound
// weighs against Cm_q plus the tunnel term when that is larger.
TEST(Diagnose, ANonlinearTermsBoundFollowsTheTunnelRidge) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_stiffness_damping_asymmetry_draw64.yaml");
  ExpectAsymmetryAndDampingBesideAStiffnessTie(d, -640.6, -9.69e-4, 3.39e-4);
}

// tools/diagnose_suite's `coning` tunnel stiffness + nonlinear damping +
// body yaw asymmetry (draw 43, --vary; tests/data/coning_stiffness_damping_
// asymmetry_draw43.yaml). After the asymmetry a tunnel damping led the
// tunnel stiffness by 10.4 (a near tie), and after it a bearing friction
// outdid the catalog: `not_explained`, the nominal Cm_q -0.45 +- 0.04
// against a truth of -5.5. Searched without the damping the three are
// found, 5.7 below the friction's model: not enough to set the probe
// aside, so the verdict stands, but it names them and the final error
// bars cover their model.
TEST(Diagnose, ACatalogAnswerAlikeWithAProbeWidensTheUnexplainedAnswer) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  const Diagnosis d =
      DiagnoseConfig("coning_stiffness_damping_asymmetry_draw43.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kNotExplained) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  const std::set<std::string> alike(d.catalog_alike.begin(),
                                    d.catalog_alike.end());
  EXPECT_EQ(alike,
            std::set<std::string>(
                {"asymmetric_body", "tunnel_stiffness", "nonlinear_damping"}))
      << text;
  EXPECT_LT(std::abs(d.catalog_alike_bic), DiagnoseOptions().ambiguity_bic)
      << text;
  EXPECT_NE(text.find("explain the record alike"), std::string::npos) << text;
  ExpectCovers(d.final_parameters, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}}, text);
}

// tools/diagnose_suite's `pair` tunnel stiffness + roll reading error +
// flow angularity (draw 41, --vary; tests/data/pair_stiffness_roll_error_
// angularity_draw41.yaml). The roll error and a trim moment tied at their
// step (BIC 107.1 and 99.5), and at 30 and 60 deg/s, far below the pitch
// frequency, the two are roll-locked twins whose swap was held a tie
// unfitted. But the trim moment's two terms cannot follow this reading
// error's four: with the stiffness and the angularity in its place the
// probable error stayed at 1.20 (0.999 with the roll error), and since
// that complete model left the noise the drag rule was applied at the
// tie, refusing the stiffness (Cm_alpha moved along Eq. 43's ridge by
// 1640 of the nominal fit's errors): `ambiguous`, nothing added. A twin
// whose swap is far worse (structured residuals, BIC 10 or more above)
// no longer holds the tie (FarWorse): the three are named.
TEST(Diagnose, ATwinWhoseSwapIsFarWorseHoldsNoTie) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "two runs; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_stiffness_roll_error_angularity_draw41.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(
      d,
      {"tunnel_stiffness", "roll_interaction", "flow_angularity"},
      {{"Cm_alpha", -0.23},
       {"Cm_q", -5.5},
       {"tunnel_Cm_theta", 1.25e-3},
       {"theta_cos_phi", -0.0248},
       {"psi_T", -0.0196}},
      text);
}

// tools/diagnose_suite's `pair` tunnel damping + Magnus moment + flow
// angularity (draw 15, --vary; tests/data/pair_damping_magnus_angularity_
// vary15.yaml). Alone, the Magnus moment and the angularity predicted the
// held-out part worse, a body yaw asymmetry dragged Cm_alpha and the
// tunnel damping Cm_q: the asymmetry, first of the two dragged, led every
// joint set, none earned its place, and the record ended `not_explained`
// with Cm_q 82 of its errors off. Each dragged contender now leads its sets
// in turn: led by the damping, the three are named.
TEST(Diagnose, EachDraggedContenderLeadsJointSetsInTurn) {
  const Diagnosis d =
      DiagnoseConfig("pair_damping_magnus_angularity_vary15.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(d,
                     {"flow_angularity", "magnus", "tunnel_damping"},
                     {{"Cm_alpha", -0.23},
                      {"Cm_q", -5.5},
                      {"tunnel_Cm_thetadot", 2.331},
                      {"tunnel_Cn_psidot", -3.165},
                      {"Cm_p_alpha", 4.337},
                      {"theta_T", -0.01574},
                      {"psi_T", -0.01785}},
                     text);
}

// The same case on draw 18 (tests/data/pair_damping_magnus_angularity_
// vary18.yaml). The Magnus moment is added first; at the next round the
// flow angularity leads and fails alone to predict the held-out part, and
// the tunnel damping, second, drags Cm_q by 72 of its errors. Its joint
// sets had drawn on the contenders after it first, three of them, and left
// the angularity out: the record ended `not_explained`, Cm_q 75 of its
// errors off. The pool is drawn in the order of BIC (JointPool): the three
// are named.
TEST(Diagnose, AJointSetDrawsOnItsPoolInTheOrderOfBic) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_damping_magnus_angularity_vary18.yaml");
  ExpectNamedExactly(d,
                     {"flow_angularity", "magnus", "tunnel_damping"},
                     {{"Cm_alpha", -0.23},
                      {"Cm_q", -5.5},
                      {"tunnel_Cm_thetadot", 2.578},
                      {"tunnel_Cn_psidot", -3.500},
                      {"Cm_p_alpha", 5.013},
                      {"theta_T", -0.01815},
                      {"psi_T", -0.02058}},
                     FormatDiagnosis(d, {0.01, 0.01, 0.01}));
}

// tools/diagnose_suite --vary's `coning` tunnel stiffness (t1 -3.1e-4, t3
// 1.1e-4) + nonlinear damping (Cm_q_delta2 259) + body yaw asymmetry
// (Cn_beta 0.2% above -Cm_alpha), draw 18, kept as tests/data/coning_
// stiffness_damping_asymmetry_vary18.csv. The asymmetry is added first;
// then the damping drags Cn_r by 188 of its errors and is the round's only
// contender, the stiffness lowering BIC by 3 alone: no joint set had a
// member to draw on, and nothing was adopted (Cm_q 62 of its errors off).
// A joint set draws on the round's lesser refits too: the three are named.
TEST(Diagnose, AJointSetDrawsOnTheRoundsLesserRefits) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("coning_stiffness_damping_asymmetry_vary18.csv");
  ExpectNamedExactly(
      d,
      {"asymmetric_body", "nonlinear_damping", "tunnel_stiffness"},
      {{"Cm_alpha", -0.23},
       {"Cm_q", -5.5},
       {"Cm_q_alpha2", 259.2},
       {"Cn_beta", 0.230515},
       {"tunnel_Cm_theta", -3.146e-4},
       {"tunnel_Cn_psi", 1.101e-4}},
      FormatDiagnosis(d, {0.01, 0.01, 0.01}));
}

// The same case on draw 25 (t1 -3.3e-4, t3 1.1e-4, Cm_q_delta2 247, body
// yaw +0.24%), kept as tests/data/coning_stiffness_damping_asymmetry_
// vary25.csv. The asymmetry and the damping reach the noise; the
// stiffness, 4 lower in BIC beside the asymmetry alone (a lesser refit),
// was never tried beside them, where it is 35 lower. The effects not
// excluded outdid the asymmetry, and the search without it named a
// tunnel damping and a Magnus moment (Cm_q 10.6 of its errors off), 16
// above the true model. The lesser refits are tried beside the complete
// model too: the false pair is not named.
TEST(Diagnose, ALesserRefitIsTriedBesideTheCompleteModel) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("coning_stiffness_damping_asymmetry_vary25.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  const std::set<std::string> named = EffectIds(d.steps);
  EXPECT_FALSE(named.count("tunnel_damping") || named.count("magnus")) << text;
  EXPECT_TRUE(named.count("asymmetric_body")) << text;
  EXPECT_TRUE(EffectIds(d.not_excluded).count("tunnel_stiffness") ||
              named.count("tunnel_stiffness"))
      << text;
  ExpectFinalCovers(d, kShortCoefficients, text);
}

// tools/diagnose_suite's `short` body yaw asymmetry (Cn_beta 0.19% off
// -Cm_alpha, draw 0), kept as tests/data/short_asymmetric_body_draw0.csv.
// With every lesser refit its score test calls for tried beside the
// model, a bearing moment whose angle the record leaves open (+- 29 deg)
// was not excluded, and with a Magnus moment it stood in for the
// asymmetry (BIC +5.0): a named answer became a tie. A lesser refit
// widens the error bars but never stands in for a step
// (Diagnosis::lesser_refits): the asymmetry is named.
TEST(Diagnose, ALesserRefitDoesNotStandInForAStep) {
  const Diagnosis d = DiagnoseRecord("short_asymmetric_body_draw0.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(d,
                     {"asymmetric_body"},
                     {{"Cm_alpha", -0.23},
                      {"Cm_q", -5.5},
                      {"Cn_beta", 0.23 * (1.0 + 0.0018779)}},
                     text);
}

// tools/diagnose_suite --vary's `short` tunnel damping (t2 -2.56, t4 3.30)
// + Magnus moment (Cm_p_alpha 5.08) + flow angularity, draw 18, kept as
// tests/data/short_damping_magnus_angularity_vary18.csv. A body yaw
// asymmetry leads the first round by 26 of BIC; once in, every other
// effect fails alone to predict the held-out part, none drags, and the
// asymmetry, leaving the residuals structured, is not adopted: the record
// was `not_explained`, nothing added, Cm_q 55 of its errors off. The
// search without that first step (DeadEndBranch) names the three (or the
// damping and the Magnus moment, the angularity tied with a roll reading
// error).
// The kept `short` tunnel damping + Magnus + angularity record `file`
// (tests/data) diagnosed: the three named with their true terms (t2, t4,
// Cm_p_alpha, theta_T, psi_T), or the angularity tied with its twin
// (ExpectDampingMagnusWithAngularityOrItsTwin), the body yaw asymmetry that led
// the first round among the rejected or dropped again (Diagnosis::pruned).
void ExpectDampingMagnusAngularityNamed(const std::string& file,
                                        double t2,
                                        double t4,
                                        double magnus,
                                        double theta_t,
                                        double psi_t) {
  const Diagnosis d = DiagnoseRecord(file);
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectDampingMagnusWithAngularityOrItsTwin(d,
                                             {{"Cm_alpha", -0.23},
                                              {"Cm_q", -5.5},
                                              {"tunnel_Cm_thetadot", t2},
                                              {"tunnel_Cn_psidot", t4},
                                              {"Cm_p_alpha", magnus},
                                              {"theta_T", theta_t},
                                              {"psi_T", psi_t}},
                                             text);
  // The false lead, refused or taken and dropped again, is on record.
  const bool dropped =
      std::any_of(d.pruned.begin(), d.pruned.end(), [](const auto& s) {
        return s.effect == "asymmetric_body";
      });
  EXPECT_TRUE(EffectIds(d.rejected).count("asymmetric_body") || dropped)
      << text;
}

TEST(Diagnose, AFirstStepThatLeadsNowhereIsSearchedWithout) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  ExpectDampingMagnusAngularityNamed(
      "short_damping_magnus_angularity_vary18.csv",
      -2.558,
      3.300,
      5.078,
      0.01952,
      0.02214);
}

// The same case on draw 23 (t2 -2.09, t4 2.84, Cm_p_alpha -5.0), kept as
// tests/data/short_damping_magnus_angularity_vary23.csv. The body yaw
// asymmetry leads the Magnus moment by 33.6 at the first round, past the
// near tie's 20 of BIC then; with it in, the tunnel damping and the Magnus
// moment tie and neither is added: `ambiguous`, the asymmetry added, the
// true model's BIC 39 lower. A near tie is now anything within 40
// (DiagnoseOptions::near_tie_bic): searched without the asymmetry, the
// three are named.
TEST(Diagnose, AFirstStepLeadingBy34IsSearchedWithout) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  ExpectDampingMagnusAngularityNamed(
      "short_damping_magnus_angularity_vary23.csv",
      -2.0901,
      2.8374,
      -5.0,
      0.017358,
      0.019690);
}

// The same case on draw 125 (t2 1.38, t4 -1.88, Cm_p_alpha -3.05, theta_T
// 0.0106, psi_T 0.0120 deg), kept as tests/data/short_damping_magnus_
// angularity_vary125.csv. The body yaw asymmetry led the first round by 20;
// at the next round the angularity and a roll reading error tied, and the
// search without the angularity (OtherBranch) took the asymmetry again:
// `not_explained`, nothing added, Cm_q 56 of its errors off. The first
// step is searched without even so (DeadEndBranch), a diagnosis of its own
// (the plain search there named a trim moment or a roll reading error, the
// angularity only not excluded).
TEST(Diagnose, AFirstStepLeadingNowhereBeforeALaterTieIsSearchedWithout) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  ExpectDampingMagnusAngularityNamed(
      "short_damping_magnus_angularity_vary125.csv",
      1.3815517,
      -1.8755611,
      -3.0530079,
      0.0106054,
      0.0120300);
}

// The same case on draw 37 (t2 2.01, t4 -2.72, Cm_p_alpha -5.0, theta_T
// -0.0155, psi_T 0.0176 deg), kept as tests/data/short_damping_magnus_
// angularity_draw37.csv. The body yaw asymmetry led the first round by 42,
// past any near tie, and was added; the angularity tied with a roll
// reading error and the Magnus moment with a bearing moment: `ambiguous`,
// the tunnel damping not excluded beside the answer (3.6 lower in BIC),
// the true model 33 lower than the answer's. A first step taken alone is
// searched without wherever an effect not excluded still lowers BIC
// beside an ambiguous answer: the three are named.
TEST(Diagnose, AFirstStepLeadingBy42IsSearchedWithoutBesideWhatItLeftOut) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  ExpectDampingMagnusAngularityNamed(
      "short_damping_magnus_angularity_draw37.csv",
      2.0061,
      -2.7235,
      -5.0,
      -0.015503,
      0.017586);
}

// The same case on draw 24 (t2 2.69, t4 -3.65, Cm_p_alpha 4.38), kept as
// tests/data/short_damping_magnus_angularity_vary24.csv. The body yaw
// asymmetry leads (BIC drop 80.7), drags Cm_q and leads a joint set with
// the tunnel damping and the angularity that reaches the noise: explained,
// Cm_alpha 8.3 of its errors off. The Magnus moment, sixth by score, was
// refitted at no round; scored beside the set's model (31.9 on its one
// parameter) it is tried there (Unrefitted, FindNotExcluded), searched
// past the noise (PastNoise), and the asymmetry is pruned: the three
// named, BIC 45 lower.
TEST(Diagnose, AnEffectNoRoundRefittedIsTriedBesideTheFinalModel) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  ExpectDampingMagnusAngularityNamed(
      "short_damping_magnus_angularity_vary24.csv",
      2.6863,
      -3.6469,
      4.3844,
      0.016541,
      0.018763);
}

// tools/diagnose_suite --vary's `pair` tunnel stiffness (t1 1.01e-3, t3
// -3.53e-4) + roll reading error + flow angularity, draw 20, kept as
// tests/data/pair_stiffness_roll_angularity_vary20.yaml. The search names
// the reading error and the stiffness and stops at the noise, the
// angularity 47.7 lower beside them; the effects not excluded then seemed
// to replace the stiffness (ReplacedStep), and the search without it took
// a tunnel damping and the angularity: `ambiguous`, Cm_alpha 18.4 of its
// errors off. The search goes one round past the noise for the
// angularity (PastNoise), which earns its place there: the three named.
TEST(Diagnose, AnEffectBesideAnExplainedModelIsSearchedPastTheNoise) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_stiffness_roll_angularity_vary20.yaml");
  ExpectNamedExactly(
      d,
      {"flow_angularity", "roll_interaction", "tunnel_stiffness"},
      {{"Cm_alpha", -0.23},
       {"Cm_q", -5.5},
       {"tunnel_Cm_theta", 1.009e-3},
       {"tunnel_Cn_psi", -3.530e-4},
       {"theta_cos_phi", 0.01682},
       {"theta_sin_phi", 0.01009},
       {"psi_cos_phi", 0.01346},
       {"psi_sin_phi", 0.006728},
       {"theta_T", -0.0134},
       {"psi_T", 0.0152}},
      FormatDiagnosis(d, {0.01, 0.01, 0.01}));
}

// tools/diagnose_suite --vary's `coning` tunnel stiffness (t1 -2.67e-4, t3
// 9.3e-5) + nonlinear damping (Cm_q_delta2 168) + body yaw asymmetry
// (Cn_beta 0.2% below -Cm_alpha), draw 20, kept as tests/data/coning_
// stiffness_damping_asymmetry_vary20.csv. The asymmetry and the damping
// reach the noise; the stiffness, 22.8 lower beside them, was only not
// excluded. Past the noise it earns its place: the three named.
TEST(Diagnose, AStiffnessBesideAnExplainedModelIsSearchedPastTheNoise) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("coning_stiffness_damping_asymmetry_vary20.csv");
  ExpectNamedExactly(
      d,
      {"asymmetric_body", "nonlinear_damping", "tunnel_stiffness"},
      {{"Cm_alpha", -0.23},
       {"Cm_q", -5.5},
       {"Cm_q_alpha2", 167.55},
       {"Cn_beta", 0.229550},
       {"tunnel_Cm_theta", -2.665e-4},
       {"tunnel_Cn_psi", 9.33e-5}},
      FormatDiagnosis(d, {0.01, 0.01, 0.01}));
}

// tools/diagnose_suite --vary's `coning` tunnel stiffness (t1 -3.7e-4, t3
// 1.3e-4) + nonlinear damping (Cm_q_delta2 -127) + body yaw asymmetry
// (Cn_beta 0.2% above -Cm_alpha), draw 22, kept as tests/data/coning_
// stiffness_damping_asymmetry_vary22.csv. The damping drags Cm_q alone and
// the asymmetry earns its place; the damping's joint sets were fitted
// pairs and triples at once, and the lowest-BIC one that earned, {damping,
// Magnus, tunnel damping}, was taken: `ambiguous` with a false tunnel
// damping added. A pair that earns comes first (JointlyLedBy): the
// damping and the asymmetry, the stiffness not excluded beside them.
TEST(Diagnose, AJointPairThatEarnsComesBeforeTheTriples) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseRecord("coning_stiffness_damping_asymmetry_vary22.csv");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(d,
                     {"asymmetric_body", "nonlinear_damping"},
                     {{"Cm_alpha", -0.23},
                      {"Cm_q", -5.5},
                      {"Cm_q_alpha2", -126.85},
                      {"Cn_beta", 0.230504}},
                     text);
  EXPECT_TRUE(EffectIds(d.not_excluded).count("tunnel_stiffness")) << text;
}

// sigma: auto, the noise unknown as on a real record. Each fit would set
// its own weights, so the diagnosis holds the noise the nominal fit and
// the data show (WithNoiseHeld) and goes on past it while an effect earns
// its place. tools/diagnose_suite's `short` Magnus moment (draw 0, 1.3
// times the noise; kept as tests/data/short_magnus_seed0.csv) had been
// called `noise_level` with sigma: auto: the residuals were white at their
// own level. Now the Magnus moment is named as with sigma given, and the
// rerun config keeps sigma: auto. A clean record stays at the noise level,
// and a drift of the pitch reading (outside the catalog) is not explained:
// its level is judged against the data's own noise, which a partial
// explanation does not reach.
TEST(Diagnose, SigmaAutoHoldsTheNoiseTheDataShow) {
  Case magnus_config =
      ShortConfig({testing::SourcePath("tests/data/short_magnus_seed0.csv")});
  magnus_config.sigma_auto = {{true, true, true}};
  const Diagnosis d = Diagnose(magnus_config, DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_TRUE(d.noise_held) << text;
  ASSERT_EQ(d.verdict, Verdict::kExplained) << text;
  EXPECT_EQ(EffectIds(d.steps), std::set<std::string>({"magnus"})) << text;
  ExpectFinalCovers(
      d, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}, {"Cm_p_alpha", 2.474}}, text);
  EXPECT_NE(d.verdict_text.find("sigma: auto, the noise held"),
            std::string::npos)
      << text;
  EXPECT_EQ(d.verdict_text.find("sigma is larger than the noise"),
            std::string::npos)
      << text;
  for (int ch = 0; ch < 3; ++ch) EXPECT_TRUE(d.final_case.sigma_auto[ch]);
  // The held noise is the data's, near the simulated 0.01 deg.
  const ChannelValues& held = d.FinalFit().segments[0].sigma_deg;
  for (double s : {held.theta, held.psi}) EXPECT_NEAR(s, 0.01, 0.004) << text;
  // The report quotes that level, not the config's placeholder.
  const ChannelValues quoted = DiagnosedNoise(d, magnus_config.sigma);
  EXPECT_EQ(quoted.theta, held.theta);
  const nlohmann::json j =
      nlohmann::json::parse(DiagnosisJson(d, magnus_config));
  EXPECT_EQ(j["noise_sigma_deg"]["psi"].get<double>(), held.psi);

  if (testing::PlainBuildOnly()) return;  // one record there
  const std::string dir = testing::ScratchDirectory("diagnose_sigma_auto");
  Case clean = ShortConfig(
      {SimulateShort(UntrimmedShortTruth(30.0), dir + "/clean.csv", 17)});
  clean.sigma_auto = {{true, true, true}};
  const Diagnosis e = Diagnose(clean, DiagnoseOptions());
  EXPECT_EQ(e.verdict, Verdict::kNoiseLevel) << e.verdict_text;

  Case drift =
      ShortConfig(ShortRunWith(dir + "/drift.csv", "theta_drift", 0.015, 3));
  drift.sigma_auto = {{true, true, true}};
  const Diagnosis f = Diagnose(drift, DiagnoseOptions());
  EXPECT_EQ(f.verdict, Verdict::kNotExplained) << f.verdict_text;
  EXPECT_TRUE(f.steps.empty()) << f.verdict_text;
}

// Contenders refused for predicting nothing held out lead joint sets
// when nothing else ends the round: on a 3-s run of another body at 39
// deg/s (tests/data/short_roll_error_magnus_varied79.yaml, sigma: auto)
// a roll reading error and a Magnus moment each failed the held-out part
// alone (log-likelihood gains -17.6 and -4.7), and the record was left
// `not_explained`. Together they explain it: the Magnus moment is named,
// the reading error tied with a drift in time (121 deg of roll).
TEST(Diagnose, EffectsThatPredictNothingAloneMayLeadASet) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  const Diagnosis d = DiagnoseConfig("short_roll_error_magnus_varied79.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.steps), std::set<std::string>({"magnus"})) << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("roll_interaction")) << text;
  ExpectFinalCovers(
      d,
      {{"Cm_alpha", -0.1506}, {"Cm_q", -7.019}, {"Cm_p_alpha", -3.0904}},
      text);
}

// sigma: auto holds the noise at the least of the nominal fit's RMS
// residual and the model-free levels of the data and of that residual: on
// a 3-s run at 9 points per cycle (tests/data/short_pitch_lag_varied79.yaml)
// the pitch data's level was 0.0122 deg against a true 0.01, and a lag of
// the pitch reading (outside the catalog) left 2.0 times the noise in
// pitch, under the held level's limit: a Magnus moment and a body
// asymmetry were named. The residual's level holds it `not_explained`.
TEST(Diagnose, SigmaAutoHoldsTheResidualsModelFreeLevel) {
  const Diagnosis d = DiagnoseConfig("short_pitch_lag_varied79.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kNotExplained) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_LT(DiagnosedNoise(d, {}).theta, 0.0115) << text;
}

// An effect earns its place on the record, not on one reading
// (RestsOnOneReading): on a 3-s run of another body with the pitch reading
// through a lag whose filter starts at rest
// (tests/data/short_pitch_lag_varied90.yaml), the first pitch reading lay
// 0.22 deg off the fitted motion, and a nonlinear damping that bent the
// motion there lowered BIC by 19.8 while every other reading fitted worse
// (without that one, by -60.7): it was added beside a Magnus moment tied
// with a reading lag. Refused, the record is `not_explained`, and its
// residuals' description names that reading.
TEST(Diagnose, AnEffectCarriedByOneReadingDoesNotEarnItsPlace) {
  const Diagnosis d = DiagnoseConfig("short_pitch_lag_varied90.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kNotExplained) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_TRUE(ListedWith(d.rejected,
                         "nonlinear_damping",
                         "rests on one reading, theta at t = 0 s"))
      << text;
  EXPECT_NE(d.residual_description.find("a reading far off the fitted motion"),
            std::string::npos)
      << d.residual_description;
}

// The nominal fit's wild points are said, with what the search did with
// them (the data's policy): on the lag record above, the first pitch
// reading, kept under `outliers: warn`, dropped under `reject`.
TEST(Diagnose, SaysWhatItDidWithTheWildPoints) {
  const Case c = LoadConfig(
      testing::SourcePath("tests/data/short_pitch_lag_varied90.yaml"));
  Diagnosis d = Diagnose(c, DiagnoseOptions());
  std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_NE(text.find("wild point: theta = 9.00289 deg at t = 0 s"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("kept in every fit of the search"), std::string::npos)
      << text;
  const nlohmann::json json = nlohmann::json::parse(DiagnosisJson(d, c));
  ASSERT_EQ(json["outliers"].size(), 1u) << json["outliers"];
  EXPECT_EQ(json["outliers"][0]["action"], "kept");
  EXPECT_EQ(json["outliers"][0]["channel"], "theta");
  Case rejecting = c;
  rejecting.segments[0].outliers = OutlierPolicy::kReject;
  d = Diagnose(rejecting, DiagnoseOptions());
  text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_NE(text.find("dropped, the search fits the rest"), std::string::npos)
      << text;
  EXPECT_EQ(d.fits[0].segments[0].data.size(), 57) << text;
}

// sigma: auto holds the noise again where a fit of the search leaves a
// channel well below the held level (HeldAgain): on a pair of 3-s runs at
// 8 points per cycle with a Magnus moment, a nonlinear damping and a
// calibration nonlinearity (tests/data/pair_magnus_damping_calibration_
// varied90.yaml) the cube's third harmonic of the pitch motion, near the
// Nyquist frequency, held pitch at 0.0140 deg (true 0.01); the three
// fitted together left 0.0097, and at 0.0140 a flow stiffer in yaw tied
// with the Magnus moment. Held again, the three are named.
TEST(Diagnose, SigmaAutoHoldsTheNoiseAgainAtAFitsLevel) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_magnus_damping_calibration_varied90.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kExplained) << text;
  EXPECT_EQ(EffectIds(d.steps),
            (std::set<std::string>{
                "magnus", "nonlinear_damping", "calibration_nonlinearity"}))
      << text;
  EXPECT_LT(DiagnosedNoise(d, {}).theta, 0.011) << text;
  ExpectFinalCovers(d,
                    {{"Cm_alpha", -0.2557},
                     {"Cm_q", -3.225},
                     {"Cm_p_alpha", 7.631},
                     {"Cm_q_delta2", 369.8}},
                    text);
}

// sigma: auto holds a channel again above its level where the search
// found the record at the noise level and every fit left that channel
// well above it, white (HeldAgain): on a 3-s run of 37 samples with a
// cubic error of the pitch reading (tests/data/short_calibration_in_pitch_
// varied101.yaml), yaw was held at 0.0053 deg (true 0.01), and the
// probable error it inflated hid the calibration: `noise_level`, Cm_alpha
// 10.8 of its errors off.
TEST(Diagnose, SigmaAutoHoldsTheNoiseAgainAboveALevelHeldLow) {
  const Diagnosis d =
      DiagnoseConfig("short_calibration_in_pitch_varied101.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kExplained) << text;
  EXPECT_EQ(EffectIds(d.steps),
            std::set<std::string>({"calibration_nonlinearity"}))
      << text;
  EXPECT_GT(DiagnosedNoise(d, {}).psi, 0.008) << text;
  ExpectFinalCovers(
      d,
      {{"Cm_alpha", -0.2059}, {"Cm_q", -3.038}, {"theta_cal3", 0.04287}},
      text);
}

// The same where the search named an effect at the noise level
// (HeldAgain): a level held low there weighs the channel's fall past what
// its errors warrant. On draw 162's 3-s run with no effect and reading
// errors that are not white (tests/data/short_correlated_errors_draw162.
// yaml: an AR(1) error of lag-1 autocorrelation 0.6 beside white noise,
// 0.014 deg in all) yaw was held at 0.0079 deg, the model-free level
// reading the errors' fast part, and every fit left it above 0.0118; a
// tunnel damping that lowered BIC by 21.7, in roll and yaw, was named.
TEST(Diagnose, SigmaAutoHoldsTheNoiseAgainAboveALevelHeldLowBesideAnEffect) {
  const Diagnosis d = DiagnoseConfig("short_correlated_errors_draw162.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_NE(d.verdict, Verdict::kExplained) << text;
  EXPECT_GT(DiagnosedNoise(d, {}).psi, 0.0115) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.3566}, {"Cm_q", -9.093}}, text);
}

// An effect whose BIC drop rests on reading errors that are not white is
// not added (RestsOnSlowResiduals): weighed as the AR(1) errors the model
// with it leaves, the record must still favor it by min_bic_drop. On draw
// 172's 3.6-s run with no effect and correlated reading errors
// (tests/data/short_correlated_errors_draw172.yaml: an AR(1) error of lag-1
// autocorrelation 0.6 beside white noise) the levels were held near the
// errors' 0.014 deg (0.0129-0.0152), and a tunnel damping lowered BIC by
// 14.1 (in roll and yaw), predicted the held-out runs better (9.9) and was
// named, its terms 0.93 +- 8.8 and 2.8 +- 8.8 on Eq. 43's ridge; it left
// a pooled lag-1 autocorrelation of 0.16, and weighed so its drop is 8.5.
TEST(Diagnose, AnEffectWhoseDropRestsOnCorrelatedErrorsIsNotAdded) {
  const Diagnosis d = DiagnoseConfig("short_correlated_errors_draw172.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_NE(d.verdict, Verdict::kExplained) << text;
  EXPECT_TRUE(ListedWith(d.rejected, "tunnel_damping", "not white")) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.365}, {"Cm_q", -7.79}}, text);
}

// A step before the last step's tie that the tie's rival does without goes
// with the tied effect the search followed (CompanionsBeforeLastTie): on
// draw 166's 3.9-s cone with a tunnel stiffness, a nonlinear damping and a
// body asymmetry (tests/data/coning_stiffness_damping_asymmetry_draw166.yaml)
// a Magnus moment came in a joint set with the damping and the asymmetry,
// and a tunnel damping tied with the stiffness after them. Beside the
// damping the Magnus moment is needed; with the stiffness in its place it
// stood at -4.7 +- 8.8 and BIC fell by 5.0 without it. It had been named
// (-29.9 +- 8.7 in the final model, a confident wrong answer); now it is
// reported with the tied damping, not added.
TEST(Diagnose, AStepTheTiesRivalDoesWithoutGoesWithTheTiedEffect) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_stiffness_damping_asymmetry_draw166.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  ASSERT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.ambiguous),
            (std::set<std::string>{"tunnel_damping", "tunnel_stiffness"}))
      << text;
  EXPECT_EQ(EffectIds(d.steps),
            (std::set<std::string>{"asymmetric_body", "nonlinear_damping"}))
      << text;
  const auto magnus =
      std::find_if(d.partial.begin(), d.partial.end(), [](const auto& s) {
        return s.effect == "magnus";
      });
  ASSERT_NE(magnus, d.partial.end()) << text;
  EXPECT_NE(magnus->note.find("goes with tunnel_damping"), std::string::npos)
      << magnus->note;
  // The verdict names it beside the tied damping (Beside), not the damping
  // beside it.
  EXPECT_NE(d.verdict_text.find(
                "with the first in the model, a Magnus moment explains"),
            std::string::npos)
      << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.2024}, {"Cm_q", -7.038}}, text);
}

// sigma: auto holds a channel whose readings lie on a grid at least at
// the rounding's own level, the step over sqrt(12) (RoundingLevelDeg): on
// draw 146's 4-s run with no effect and its roll read in 2-deg counts at
// 1.79 deg a sample (tests/data/short_quantized_roll_vary146.yaml) roll was
// held at 0.373 deg, and a product of inertia that took part of the
// rounding's sawtooth (its period near the pitch period) lowered BIC by
// 10.3 and was named.
TEST(Diagnose, SigmaAutoHoldsAQuantizedChannelAtLeastAtItsRounding) {
  const Diagnosis d = DiagnoseConfig("short_quantized_roll_vary146.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_NE(d.verdict, Verdict::kExplained) << text;
  EXPECT_NEAR(DiagnosedNoise(d, {}).phi, 2.0 / std::sqrt(12.0), 0.01) << text;
  // The residuals' description says what the roll residual is.
  EXPECT_NE(d.residual_description.find(
                "roll read in counts of 2 deg: their rounding alone leaves "
                "0.577 deg RMS"),
            std::string::npos)
      << d.residual_description;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.2197}, {"Cm_q", -6.305}}, text);
}

// Held at its rounding's level, a channel read in counts still has the
// rounding's sawtooth in its residual, and a fall in its sum of squares is
// no evidence of an effect (RestsOnRoundedReadings): on draw 157's 3-s run
// with no effect and roll read in 2-deg counts
// (tests/data/short_quantized_roll_draw157.yaml; 2.24 deg a sample) a
// product of inertia lowered BIC by 11.2, all of it in roll (pitch 6.0,
// yaw -2.0), with Izx -0.0023 +- 0.00046 slug ft^2, and was named.
TEST(Diagnose, AnEffectWhoseDropRestsOnReadingsInCountsIsNotAdded) {
  const Diagnosis d = DiagnoseConfig("short_quantized_roll_draw157.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_EQ(d.verdict, Verdict::kNoiseLevel) << text;
  EXPECT_NEAR(DiagnosedNoise(d, {}).phi, 2.0 / std::sqrt(12.0), 0.01) << text;
  const auto inertia = std::find_if(
      d.rejected.begin(), d.rejected.end(), [](const CandidateFit& r) {
        return r.effect == "product_of_inertia";
      });
  ASSERT_NE(inertia, d.rejected.end()) << text;
  EXPECT_NE(inertia->rejected.find("rests on readings in counts"),
            std::string::npos)
      << inertia->rejected;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.2925}, {"Cm_q", -3.121}}, text);
}

// A catalog effect whose fit whitens the record just past the noise
// level's limit shows the level held too low, as a fit at the noise
// level does (HeldLowByWhiteSteps): on draw 147's 3-s run with a roll
// torque (tests/data/short_roll_torque_vary147.yaml) pitch and yaw were
// held at 0.0053 and 0.0061 deg (true 0.01), the torque left 0.0101 and
// 0.0097, white, at a probable error of 1.60 against a limit of 1.56, and
// the answer was `not_explained` with nothing named. Held again, the
// torque ties with its twin at constant spin, the roll damping.
TEST(Diagnose, AStepThatWhitensTheRecordJustPastTheLimitHoldsTheNoiseAgain) {
  const Diagnosis d = DiagnoseConfig("short_roll_torque_vary147.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.ambiguous).count("roll_torque"), 1u) << text;
  EXPECT_EQ(EffectIds(d.ambiguous).count("roll_damping"), 1u) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_GT(DiagnosedNoise(d, {}).theta, 0.008) << text;
  EXPECT_GT(DiagnosedNoise(d, {}).psi, 0.008) << text;
}

// The record `file` (sigma: auto; an effect outside the catalog in its
// pitch reading, 0.01-deg noise) is diagnosed `not_explained` with nothing
// added, its pitch level not held again at the structure's.
void ExpectPitchStructureUnexplained(const std::string& file) {
  const Diagnosis d = DiagnoseConfig(file);
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kNotExplained) << file << "\n" << text;
  EXPECT_TRUE(d.steps.empty()) << file << "\n" << text;
  EXPECT_LT(DiagnosedNoise(d, {}).theta, 0.015) << file << "\n" << text;
}

// Far past the limit a white residual is a structure the whiteness test
// misses, not the noise's size: on draw 142's 2.7-s run whose pitch
// reading lags through a filter (outside the catalog;
// tests/data/short_pitch_lag_vary142.yaml) a Magnus moment left pitch
// at 0.033 deg, white, at a probable error of 2.22 against a limit of
// 1.52. Held there, the lag had passed for the Magnus moment's
// look-alike (`ambiguous`).
TEST(Diagnose, AStepThatWhitensTheRecordFarPastTheLimitHoldsNoNoiseAgain) {
  ExpectPitchStructureUnexplained("short_pitch_lag_vary142.yaml");
}

// No channel is held again above the middle of the three channels' white
// residuals: on draw 147's 3.7-s coning run whose pitch reading errs as
// the square of the angle (outside the catalog;
// tests/data/coning_even_calibration_vary147.yaml) a flow angularity left
// pitch at 0.022 deg, white, beside roll and yaw's 0.0105 and 0.0086, at a
// probable error of 1.61 against a limit of 1.49. Held there, the error
// passed for a catalog look-alike (`ambiguous`).
TEST(Diagnose, NoChannelIsHeldAgainFarAboveTheOtherTwo) {
  ExpectPitchStructureUnexplained("coning_even_calibration_vary147.yaml");
}

// A score read on BIC's scale (ScoreBicDrop): on draw 147's 3-s run whose
// pitch reading errs as a cube at 1.33 times the noise
// (tests/data/short_calibration_in_pitch_only_vary147.yaml), the
// calibration's score, 19.3, read as a drop of 9.8 where the refit's is
// 13.4; it was never refitted, and the answer was `noise_level` with Cm_q
// 5.1 of its errors off.
TEST(Diagnose, AScoreIsReadOnBicsScale) {
  const Diagnosis d =
      DiagnoseConfig("short_calibration_in_pitch_only_vary147.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  ExpectNamedExactly(
      d,
      {"calibration_nonlinearity"},
      {{"Cm_alpha", -0.2113}, {"Cm_q", -7.787}, {"theta_cal3", -0.0354}},
      text);
}

// A probe outside the catalog that outdoes a round no catalog effect won
// must predict the held-out part of the record as a newcomer must: on draw
// 127's 3-s run with a roll reading error (sigma: auto;
// tests/data/short_roll_interaction_auto127.yaml) the reading error took
// the probable error to 1.12 against a limit of 1.51, then past the held
// level a pressure-drift probe lowered BIC by 12.3 beside it, predicting
// the held-out part worse (gain -15.9), and the record ended
// `not_explained`. The reading error now ties with a drift in time (the
// record spans 89 deg of roll), the probe listed among the rejected.
TEST(Diagnose, AProbeThatPredictsNothingHeldOutOutdoesNothing) {
  const Diagnosis d = DiagnoseConfig("short_roll_interaction_auto127.yaml");
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << d.verdict_text;
  EXPECT_TRUE(d.outside_catalog.effect.empty()) << d.verdict_text;
  EXPECT_EQ(EffectIds(d.ambiguous),
            std::set<std::string>({"roll_interaction", "drift_in_time"}))
      << d.verdict_text;
  const auto probe = std::find_if(
      d.rejected.begin(), d.rejected.end(), [](const CandidateFit& k) {
        return k.effect == "pressure_drift";
      });
  ASSERT_NE(probe, d.rejected.end()) << d.verdict_text;
  EXPECT_LT(probe->prediction_gain, 0.0) << probe->rejected;
  EXPECT_NE(probe->rejected.find("does not predict the held-out part"),
            std::string::npos)
      << probe->rejected;
}

// A step not adopted for leaving the record past the noise level's limit
// says whether it leaves structure or white residuals, the noise's size:
// on a 3-s run with a body yaw asymmetry whose noise drew 1.2 times sigma
// (tests/data/short_body_asymmetry_varied115.yaml) the asymmetry left
// white residuals at 1.21 against a limit of 1.20, and the words had
// called them structured. With sigma: auto, as they advise, the record
// is `ambiguous` between the asymmetry and a Magnus moment.
TEST(Diagnose, SaysWhenAStepNotAdoptedLeavesWhiteResiduals) {
  const Diagnosis d = DiagnoseConfig("short_body_asymmetry_varied115.yaml");
  EXPECT_EQ(d.verdict, Verdict::kNotExplained) << d.verdict_text;
  ASSERT_EQ(EffectIds(d.partial), std::set<std::string>({"asymmetric_body"}))
      << d.verdict_text;
  EXPECT_TRUE(d.partial.back().after.white) << d.verdict_text;
  EXPECT_FALSE(d.partial.back().after.at_noise_level) << d.verdict_text;
  EXPECT_NE(d.verdict_text.find("leaves white residuals, past the noise "
                                "level's limit"),
            std::string::npos)
      << d.verdict_text;
  EXPECT_NE(d.verdict_text.find("sigma: auto"), std::string::npos)
      << d.verdict_text;
  EXPECT_EQ(d.verdict_text.find("leaves the residuals structured"),
            std::string::npos)
      << d.verdict_text;

  if (testing::PlainBuildOnly()) return;  // a second diagnosis; plain build
  Case c = LoadConfig(
      testing::SourcePath("tests/data/short_body_asymmetry_varied115.yaml"));
  c.sigma_auto = {true, true, true};
  const Diagnosis a = Diagnose(c, DiagnoseOptions());
  EXPECT_EQ(a.verdict, Verdict::kAmbiguous) << a.verdict_text;
  EXPECT_EQ(EffectIds(a.ambiguous),
            std::set<std::string>({"asymmetric_body", "magnus"}))
      << a.verdict_text;
}

// sigma: auto holds a channel again higher where a probe outside the
// catalog reaches the noise level and leaves that channel white well
// above its level (HeldAgainByTheProbe): on draw 116's 3-s coning run
// with a bearing moment at 2 deg (tests/data/coning_bearing_two_degrees_
// vary116.yaml) pitch was held at 0.0058 deg (true 0.01), a pressure
// drift came 12.1 in BIC below the bearing moment, and the answer was
// `not_explained` with nothing named. Held at the drift's 0.0081, the
// bearing moment and the drift explain the record alike. Since the
// bearing moment is charged only for the saturated moment the record
// determines (DeterminedBic: its angle 1.04 +- 3.7 deg) the two tie at
// the first level already; with the bearing moment known absent the
// drift outdoes the catalog there, and the level is held again.
TEST(Diagnose, SigmaAutoHoldsAgainALevelAProbesModelShowsTooLow) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  const Case c = LoadConfig(testing::SourcePath(
      "tests/data/coning_bearing_two_degrees_vary116.yaml"));
  const Diagnosis d = Diagnose(c, DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.ambiguous),
            std::set<std::string>({"bearing_moment", "pressure_drift"}))
      << text;

  DiagnoseOptions options;
  options.absent = {"bearing_moment"};
  const Diagnosis a = Diagnose(c, options);
  const std::string held = FormatDiagnosis(a, DiagnosedNoise(a, {}));
  EXPECT_GT(DiagnosedNoise(a, {}).theta, 0.0075) << held;
  EXPECT_EQ(a.verdict, Verdict::kNotExplained) << held;
  EXPECT_EQ(a.outside_catalog.effect, "pressure_drift") << held;
}

// A probe's level is read no higher than the middle channel's
// (HeldAgainByTheProbe): on draw 156's 2.9-s run with a tunnel stiffness,
// a nonlinear damping and a body asymmetry
// (tests/data/short_stiffness_damping_asymmetry_draw156.yaml) a lag of the
// pitch reading, outside the catalog, left pitch at 0.0159 deg beside
// 0.0124 in roll and yaw (the true model's own fit 0.0089 in pitch). Held
// there, a tunnel damping passed for the nonlinear damping and was named
// beside the asymmetry: `explained`, Cm_q 3.2 of its errors off.
TEST(Diagnose, SigmaAutoReadsAProbesLevelNoHigherThanTheMiddleChannel) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_stiffness_damping_asymmetry_draw156.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_LT(DiagnosedNoise(d, {}).theta, 0.012) << text;
  EXPECT_EQ(EffectIds(d.steps).count("tunnel_damping"), 0u) << text;
  EXPECT_NE(d.verdict, Verdict::kExplained) << text;
}

// A line of one channel between two bins is structure
// (MeanBesideLine, spectral_lines.cc): on draw 165's 3.4-s cone with a
// tunnel buzz at 2.3 times the pitch frequency, outside the catalog
// (tests/data/coning_tunnel_buzz_draw165.yaml), pitch was held at
// 0.0171 deg; the nominal fit left 0.034 there, and the check, its line
// measured against a mean that was mostly its own, called it white. Held
// again at 0.0357 the buzz passed for noise: `noise_level`. The
// description measures its lines so too (LocalSpectralLine): it had said
// "no line ... stands out" of the buzz at 3.05 Hz (3.15 Hz on the record's
// 0.29-Hz bins).
TEST(Diagnose, ABuzzOfOneChannelIsNotTheNoiseLevel) {
  const Diagnosis d = DiagnoseConfig("coning_tunnel_buzz_draw165.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kNotExplained) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_LT(DiagnosedNoise(d, {}).theta, 0.02) << text;
  EXPECT_NE(d.residual_description.find("pitch: a line at 3.15 Hz"),
            std::string::npos)
      << text;
}

// sigma: auto holds a channel again lower where the effects a search
// left unexplained, fitted together, show it held too high (HeldAgain,
// FittedTogether): on a 3-s run with a bearing moment, a cubic calibration
// error and a roll torque (tests/data/short_bearing_calibration_torque_
// varied105.yaml) pitch was held at 0.0225 deg (true 0.01), each effect
// alone left 0.022 there, a drift of the dynamic pressure explained the
// record at that level, and the answer was `not_explained`, Cm_alpha 24.9
// of its errors off. Held again at what the effects together leave, the
// calibration and the bearing moment are named, the torque tied.
TEST(Diagnose, SigmaAutoHoldsAgainALevelTheEffectsTogetherShowTooHigh) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_bearing_calibration_torque_varied105.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_LT(DiagnosedNoise(d, {}).theta, 0.015) << text;
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(
      EffectIds(d.steps),
      std::set<std::string>({"bearing_moment", "calibration_nonlinearity"}))
      << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("roll_torque")) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.2426}, {"Cm_q", -5.933}}, text);
}

// A tunnel term not excluded is tried in every step's place, whatever it
// does beside the complete model, and with each of its terms held at zero
// where it runs along Eq. 43's ridge: on a 3-s run with a tunnel
// stiffness, a nonlinear damping and a body asymmetry
// (tests/data/short_stiffness_damping_asymmetry_varied103.yaml) a roll
// torque came first and was named, the stiffness 0.8 above the model
// beside it (out of its bounds on the ridge). With t1 held at zero in the
// torque's place it is 4 lower: the two tie.
TEST(Diagnose, ATunnelTermIsTriedInEveryStepsPlace) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_stiffness_damping_asymmetry_varied103.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.ambiguous),
            std::set<std::string>({"roll_torque", "tunnel_stiffness"}))
      << text;
  EXPECT_EQ(EffectIds(d.steps),
            std::set<std::string>({"nonlinear_damping", "asymmetric_body"}))
      << text;
}

// A step before a tie that has no rivals and that the pruning of the
// complete model takes away is taken out of the final model too
// (TieDissolves, WithoutPrunedBeforeTie): on a coning run with a bearing
// moment, a calibration error and a roll torque tied with a roll damping
// (tests/data/coning_bearing_calibration_torque_varied105.yaml) a tunnel
// damping taken first stayed, t2 = 0.058 +- 0.062 and t4 = 0.033 +- 0.068,
// each complete model 9 lower in BIC without it.
TEST(Diagnose, AStepTheCompleteModelPrunesLeavesTheFinalModel) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_bearing_calibration_torque_varied105.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("roll_torque")) << text;
  EXPECT_EQ(
      EffectIds(d.steps),
      std::set<std::string>({"bearing_moment", "calibration_nonlinearity"}))
      << text;
}

// The pruning of an explained model keeps every effect left within its
// bounds (Prune): on a 3-s run with a bearing moment, a calibration error
// and a roll torque (tests/data/short_bearing_calibration_torque_
// varied107.yaml), a tunnel stiffness refused alone (t1 4.15 on Eq. 43's
// ridge, bound 0.146) came in with a roll damping and the bearing moment,
// t1 0.93 +- 1.63; pruned of both it was back at 4.15 +- 0.40, and named
// alone, Cm_alpha -4.4 +- 0.4 against -0.28.
TEST(Diagnose, APruningLeavesNoEffectOutOfItsBounds) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_bearing_calibration_torque_varied107.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_FALSE(EffectIds(d.steps).count("tunnel_stiffness")) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.2814}, {"Cm_q", -8.766}}, text);
}

// The final model's error bars cover the stiffness its bearing moment
// trades with on its ridge (StiffnessOnTheRidge): on a 3-s run with the
// moment fading at 2 deg (tests/data/short_bearing_two_degrees_vary111_
// diagnose.yaml; diagnose starts the angle at 1), the moment was named at
// 0.73 +- 1.2 deg and Cm_alpha, -0.20131 +- 0.00032, was 3.5 errors off
// the truth: frozen there, the sum of squares rises by 2.3 E^2. Its error
// bar is now its profile's, and the model's own error says so.
TEST(Diagnose, TheFinalErrorBarsCoverTheStiffnessOnTheBearingRidge) {
  const Diagnosis d =
      DiagnoseConfig("short_bearing_two_degrees_vary111_diagnose.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kExplained) << text;
  EXPECT_EQ(EffectIds(d.steps), std::set<std::string>({"bearing_moment"}))
      << text;
  // As diagnosis.json reports them.
  ExpectCovers(
      d.final_parameters, {{"Cm_alpha", -0.2002}, {"Cm_q", -7.411}}, text);
  EXPECT_TRUE(testing::InPipeline(d.FinalFit(),
                                  "Cm_alpha's error bar from its profile"))
      << ::testing::PrintToString(d.FinalFit().pipeline);
}

// A joint set with a tunnel term among its members shows it by its name
// (EffectCatalog's terms are the names fits report): on a 3-s run with a
// tunnel damping, a Magnus moment and a flow angularity, sigma: auto
// (tests/data/short_tunnel_damping_magnus_angularity_vary110.yaml), each
// alone failed to predict the held-out part, and every set with the
// damping in was refused as "a member its fit does not show" (t2 and t4
// matched no estimate): `not_explained`, Cm_q -4.62 +- 0.04 against
// -6.815. Now the damping and the Magnus moment are added, and the offset
// ties with a roll reading error, which less than a revolution of roll
// cannot tell apart.
TEST(Diagnose, AJointSetShowsItsTunnelDamping) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a tie among joint sets; plain build";
  }
  const Diagnosis d =
      DiagnoseConfig("short_tunnel_damping_magnus_angularity_vary110.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.steps),
            std::set<std::string>({"tunnel_damping", "magnus"}))
      << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("flow_angularity")) << text;
  ExpectCovers(d.final_parameters,
               {{"Cm_alpha", -0.1637},
                {"Cm_q", -6.815},
                {"tunnel_Cm_thetadot", 2.219},
                {"tunnel_Cn_psidot", -3.013},
                {"Cm_p_alpha", -5.324}},
               text);
}

// A probe outside the catalog weighed with the catalog's effects beside it
// (SearchedBeside) does not search that record again without a step: on
// a pair of 3-s runs with a tunnel damping, a Magnus moment and a flow
// angularity, sigma: auto (tests/data/pair_damping_magnus_angularity_
// vary110.yaml), a reading lag outdid every catalog effect at the first
// step; the catalog's three explain the record, the lag with them beside
// it 68 higher in BIC. Its search again without a first step and without
// a step a swap outdid took half the diagnosis's 6.6 s (tools/bench), and
// changed no answer over draws 99-110.
TEST(Diagnose, AProbeWeighedBesideTheCatalogLeavesTheThreeNamed) {
  if (testing::PlainBuildOnly()) {
    GTEST_SKIP() << "a probe searched beside the catalog; plain build";
  }
  const Diagnosis d =
      DiagnoseConfig("pair_damping_magnus_angularity_vary110.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kExplained) << text;
  EXPECT_EQ(
      EffectIds(d.steps),
      std::set<std::string>({"flow_angularity", "magnus", "tunnel_damping"}))
      << text;
  EXPECT_TRUE(d.outside_catalog_beside.empty()) << text;
  EXPECT_TRUE(std::any_of(
      d.rejected.begin(),
      d.rejected.end(),
      [](const CandidateFit& k) { return k.effect == "reading_lag"; }))
      << text;
  ExpectCovers(d.final_parameters,
               {{"Cm_alpha", -0.2789},
                {"Cm_q", -2.396},
                {"tunnel_Cm_thetadot", 1.4376},
                {"tunnel_Cn_psidot", -2.4681},
                {"Cm_p_alpha", -6.6622},
                {"theta_T", -0.017216},
                {"psi_T", 0.019528}},
               text);
}

// A probe outside the catalog that outdid every catalog effect earning its
// place makes the record `not_explained` even where the final model is
// within the noise level's limit: on a pair of 3-s runs with a reading
// error at the second harmonic of roll, sigma: auto
// (tests/data/pair_second_roll_harmonic_varied92.yaml), the nominal fit
// passed at 1.37 times the held level while a trim moment lowered BIC by 71
// and that probe by 97; the answer had been `noise_level`.
TEST(Diagnose, AProbeThatOutdidTheCatalogLeavesTheRecordUnexplained) {
  const Diagnosis d = DiagnoseConfig("pair_second_roll_harmonic_varied92.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kNotExplained) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_EQ(d.outside_catalog.effect, "second_roll_harmonic") << text;
  EXPECT_TRUE(d.final.at_noise_level) << text;
  EXPECT_NE(d.verdict_text.find("yet effects earn their place"),
            std::string::npos)
      << text;
}

// The final error bars of a record a probe left `not_explained` cover the
// probe's own model (KeepOutdoneByProbe): on draw 128's 3-s cone with a
// bearing moment (tests/data/coning_bearing_moment_vary128.yaml) a
// pressure drift outdid it, and the nominal Cm_alpha had been quoted
// -0.23252 +- 7.9e-5 while the drift's model, 96 lower in BIC, holds
// -0.23196.
TEST(Diagnose, TheFinalErrorBarsCoverTheModelOfAProbeThatOutdidTheCatalog) {
  const Case c = LoadConfig(
      testing::SourcePath("tests/data/coning_bearing_moment_vary128.yaml"));
  const Diagnosis d = Diagnose(c, DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ASSERT_EQ(d.verdict, Verdict::kNotExplained) << text;
  ASSERT_EQ(d.outside_catalog.effect, "pressure_drift") << text;
  Case drift = c;
  drift.parameters[FindParameter(drift.model, "q_drift")].free = true;
  const FitResult drift_fit = Fit(drift);
  const ParameterEstimate* probe = SharedEstimate(drift_fit, "Cm_alpha");
  const ParameterEstimate* final = SharedEstimate(d.FinalFit(), "Cm_alpha");
  ASSERT_NE(probe, nullptr);
  ASSERT_NE(final, nullptr);
  const double shift = std::abs(probe->value - final->value);
  EXPECT_GT(shift, 3.0 * d.model_standard_errors.at("Cm_alpha")) << text;
  EXPECT_LE(shift, final->standard_error) << text;
}

// An effect the final model holds in one form and the search's model with
// the effects not adopted in the other is said so, and its final values
// are the final model's form's: on a pair of 3-s runs with a bearing
// moment, a cubic calibration error and a roll torque, sigma: auto
// (tests/data/pair_bearing_calibration_torque_varied95.yaml), the bearing
// moment tied with a reading-gain error at the last step; the model
// before it, the final one, holds the calibration as the signed square,
// the search's model beside the bearing moment as the cube. The answer had
// read "theta_cal3 = 0 deg (held)".
TEST(Diagnose, SaysWhereAFormFollowsTheEffectsNotAdopted) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Case c = LoadConfig(testing::SourcePath(
      "tests/data/pair_bearing_calibration_torque_varied95.yaml"));
  const Diagnosis d = Diagnose(c, DiagnoseOptions());
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  const auto step =
      std::find_if(d.steps.begin(), d.steps.end(), [](const DiagnosisStep& s) {
        return s.effect == "calibration_nonlinearity";
      });
  ASSERT_NE(step, d.steps.end()) << text;
  ASSERT_FALSE(step->parameters.empty()) << text;
  EXPECT_EQ(step->parameters[0].name, "theta_cal2") << text;
  EXPECT_NE(text.find("form: calibration_nonlinearity as "
                      "calibration_signed_square in the final model, in its "
                      "own form beside bearing_moment"),
            std::string::npos)
      << text;
  const nlohmann::json json = nlohmann::json::parse(DiagnosisJson(d, c));
  ASSERT_EQ(json["forms_apart"].size(), 1u) << json["forms_apart"];
  EXPECT_EQ(json["forms_apart"][0]["final_form"], "calibration_signed_square");
}

// sigma: auto holds each channel's noise at its first flat difference
// order (DataNoiseDeg), not the least over the orders: on a pair of 3-s
// runs with a roll reading error and a Magnus moment
// (tests/data/pair_roll_error_magnus_varied92.yaml) the roll readings'
// levels fell from 0.0083 deg at the 2nd difference to 0.0051 at the 8th
// (true 0.01); held at 0.0051, the two effects, both found, left roll 1.8
// times that and the record `not_explained`.
TEST(Diagnose, SigmaAutoHoldsTheNoiseWhereTheMotionIsGone) {
  const Diagnosis d = DiagnoseConfig("pair_roll_error_magnus_varied92.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kExplained) << text;
  EXPECT_EQ(EffectIds(d.steps),
            std::set<std::string>({"magnus", "roll_interaction"}))
      << text;
  EXPECT_GT(d.FinalFit().segments[0].sigma_deg[0], 0.007) << text;
}

// A lesser refit (one that lowered BIC by less than 10 at its round)
// whose score beside the complete model says the record may not exclude
// it is tried there: on a pair of 3-s runs with a tunnel stiffness, a
// roll reading error and a flow angularity, sigma: auto
// (tests/data/pair_stiffness_roll_error_angularity_varied95.yaml), the
// reading error tied with a trim moment, the stiffness was added, and the
// angularity, refitted at BIC +8.5 in a round, was never tried beside the
// search's model (BIC +6.7 there): the answer did not say the record
// allows it, nor did the final error bars cover it.
TEST(Diagnose, ALesserRefitTheRecordCannotExcludeIsListed) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_stiffness_roll_error_angularity_varied95.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.steps), std::set<std::string>({"tunnel_stiffness"}))
      << text;
  EXPECT_TRUE(EffectIds(d.not_excluded).count("flow_angularity")) << text;
}

// An effect taken early that alone refused a later round's best
// contender, going out of its bounds beside it, is searched without
// (BlockerBranch): on a 3-s run with a tunnel damping, a Magnus moment and
// a flow angularity (tests/data/short_damping_magnus_angularity_varied94
// .yaml), a calibration error taken first went past its bound beside the
// Magnus moment (102 lower in BIC), and a body yaw asymmetry, standing in
// for the damping's yaw part, was named. Without the calibration error
// the damping and the Magnus moment are named, 31.7 lower.
TEST(Diagnose, AnEarlyStepThatRefusedABetterOneIsSearchedWithout) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  const Diagnosis d =
      DiagnoseConfig("short_damping_magnus_angularity_varied94.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(EffectIds(d.steps),
            (std::set<std::string>{"tunnel_damping", "magnus"}))
      << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("flow_angularity")) << text;
  EXPECT_TRUE(d.absent.empty()) << text;
  EXPECT_TRUE(ListedWith(d.rejected,
                         "calibration_nonlinearity",
                         "went out of its bounds beside a later"))
      << text;
  ExpectFinalCovers(d,
                    {{"Cm_alpha", -0.3311},
                     {"Cm_q", -3.699},
                     {"Cm_p_alpha", -8.261},
                     {"tunnel_Cm_thetadot", 2.219},
                     {"tunnel_Cn_psidot", -4.004}},
                    text);
}

// The effects tied in an answer are candidates past the noise beside it
// (PastNoise): on a cone of another body
// (tests/data/coning_damping_magnus_angularity_varied80.yaml) a Magnus
// moment tied with the tunnel damping and a flow angularity were in; past
// the noise a roll torque took the damping's roll part (Eq. 39) and was
// added at 4.8 of its errors, the damping only not excluded. With the
// tied effects weighed there too, the damping is named, no roll torque.
TEST(Diagnose, TiedEffectsAreWeighedPastTheNoise) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_damping_magnus_angularity_varied80.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  const std::set<std::string> added = EffectIds(d.steps);
  EXPECT_TRUE(added.count("tunnel_damping")) << text;
  EXPECT_FALSE(added.count("roll_torque")) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.1473}, {"Cm_q", -8.716}}, text);
}

// The probes are refitted in the order of their scores, two at a time,
// until one has its physical sign: on a 3-s run of another body with the
// pitch reading's gain 16% low (tests/data/short_pitch_gain_varied82.yaml)
// the frictions about both axes and about the yaw axis scored first and
// drove the motion; the gain probe was never fitted, and a tunnel damping
// cancelling 85% of the yaw damping was named. Now the gain probe outdoes
// every catalog effect and the record is not explained by the catalog.
TEST(Diagnose, ProbesAreFittedPastThoseOfTheWrongSign) {
  const Diagnosis d = DiagnoseConfig("short_pitch_gain_varied82.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kNotExplained) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_EQ(d.outside_catalog.effect, "reading_gain") << text;
}

// A rival that tied with a step where the step was added and loses its
// swap by far is fitted again from its own terms first (Unresolved): on a
// 3-s run of another body with a gas-bearing moment, a calibration error
// and a roll torque, sigma: auto
// (tests/data/short_bearing_calibration_roll_torque_varied85.yaml), the
// roll damping and the roll torque lowered BIC alike at their step (twins
// at one spin rate), but the torque swapped in for the damping ran the
// bearing's angle along its ridge and stopped 30.8 worse: the roll damping
// was named. From its own terms first the swap is as good: a tie.
TEST(Diagnose, ASwapFarWorseIsRefittedFromTheRivalsOwnTerms) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_bearing_calibration_roll_torque_varied85.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.ambiguous),
            (std::set<std::string>{"roll_damping", "roll_torque"}))
      << text;
  EXPECT_FALSE(EffectIds(d.steps).count("roll_damping")) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.1534}, {"Cm_q", -7.049}}, text);
}

// A final model with no effect, a tie's short of the noise, lists its own
// near twins (FindNotExcluded): on a cone of another body with a tunnel
// damping, a Magnus moment and a flow angularity, sigma: auto
// (tests/data/coning_damping_magnus_angularity_varied81.yaml), a trim
// moment tied with a drift in time and nothing was added; the Magnus
// moment was Cm_q's twin beside the search's model only, and the final
// Cm_q, 22.6 of its errors off the truth, was said to carry nothing. Now
// the answer says what it carries, and holds that.
TEST(Diagnose, AFinalModelShortOfTheTieSaysWhatItsCoefficientsCarry) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_damping_magnus_angularity_varied81.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_TRUE(d.steps.empty()) << text;
  ExpectCmqCarries(d, "magnus", -3.829, -17.643, text);
}

// A tunnel term of Eq. 39 not excluded beside the complete model stands in
// for the other tunnel term (FindSingleReplacement) whatever it does beside
// it: on a pair of runs of another body with a tunnel stiffness, a
// nonlinear damping and a body yaw asymmetry
// (tests/data/pair_stiffness_damping_asymmetry_varied84.yaml) a tunnel
// damping came in a joint set and was named, the stiffness 1.8 above the
// model beside it and never tried in the damping's place. In its place it
// explains the record alike: the two tie, neither claimed.
TEST(Diagnose, ATunnelTermNotExcludedStandsInForTheOther) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_stiffness_damping_asymmetry_varied84.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.ambiguous),
            (std::set<std::string>{"tunnel_damping", "tunnel_stiffness"}))
      << text;
  EXPECT_EQ(EffectIds(d.steps),
            (std::set<std::string>{"asymmetric_body", "nonlinear_damping"}))
      << text;
}

// A roll torque or a roll damping named is tried with each tunnel term of
// Eq. 39 in its place even where no round refitted that term (its roll
// part is their signature): on draw 127's 3-s run with a tunnel
// stiffness, a nonlinear damping and a body yaw asymmetry (sigma: auto;
// tests/data/short_stiffness_damping_asymmetry_auto127.yaml) the stiffness
// was never among a round's five by score, and a roll torque taken in a
// joint set with the other two was named `explained`, Cm_alpha 29 of its
// errors off. In the torque's place the stiffness is 5.6 higher in BIC:
// the two tie, and the final error bars cover the truth.
TEST(Diagnose, ARollMomentStepIsTriedWithAnUntriedTunnelTermInItsPlace) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_stiffness_damping_asymmetry_auto127.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.ambiguous),
            (std::set<std::string>{"roll_torque", "tunnel_stiffness"}))
      << text;
  EXPECT_EQ(EffectIds(d.steps),
            (std::set<std::string>{"asymmetric_body", "nonlinear_damping"}))
      << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.23}, {"Cm_q", -5.5}}, text);
  // The stiffness, never tried beside the model, carries its terms as
  // fitted in the torque's place.
  const auto stiffness = std::find_if(
      d.ambiguous.begin(), d.ambiguous.end(), [](const CandidateFit& k) {
        return k.effect == "tunnel_stiffness";
      });
  ASSERT_NE(stiffness, d.ambiguous.end()) << text;
  EXPECT_EQ(stiffness->parameters.size(), 2u) << text;
  EXPECT_GT(stiffness->bic_drop, 0.0) << text;
}

// The mirror: a tunnel term named is tried with each roll moment not
// excluded in its place, whatever that does beside the model (beside the
// term it adds nothing, as the term holds its roll part). On draw 144's
// coning run with a bearing moment, a calibration error and a roll torque
// (sigma: auto; tests/data/coning_bearing_calibration_roll_torque_vary144.
// yaml) a tunnel damping came first, its yaw term at the steady coning rate
// a torque about the tunnel axis, and was named `explained` with the other
// two at 0.0046 and 0.033 +- 0.050. In its place a roll moment (the torque
// and the damping are twins at a constant spin) lowers BIC: the two tie.
TEST(Diagnose, ATunnelTermStepIsTriedWithARollMomentInItsPlace) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_bearing_calibration_roll_torque_vary144.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_FALSE(EffectIds(d.steps).count("tunnel_damping")) << text;
  EXPECT_EQ(
      EffectIds(d.steps),
      (std::set<std::string>{"bearing_moment", "calibration_nonlinearity"}))
      << text;
  const std::set<std::string> tied = EffectIds(d.ambiguous);
  EXPECT_TRUE(tied.count("roll_torque") || tied.count("roll_damping")) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.2544}, {"Cm_q", -9.919}}, text);
}

// Any effect not excluded is tried in a tunnel term step's place, not a
// roll moment alone: on draw 148's cone with a Magnus moment, a nonlinear
// damping and a calibration error (sigma: auto;
// tests/data/coning_magnus_damping_calibration_vary148.yaml) a tunnel
// damping with pitch and yaw terms of opposite signs came in a joint set
// with the Magnus moment, which was then dropped as redundant; the answer
// was `explained` with the false damping, and the Magnus moment, +2.7
// beside it, is 6.9 lower in its place. The two now tie.
TEST(Diagnose, ATunnelTermStepIsTriedWithAnyEffectNotExcludedInItsPlace) {
  // Runs sanitized too: it reaches diagnose code no other sanitized test
  // does (tools/sanitized_coverage).
  const Diagnosis d =
      DiagnoseConfig("coning_magnus_damping_calibration_vary148.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_FALSE(EffectIds(d.steps).count("tunnel_damping")) << text;
  EXPECT_EQ(
      EffectIds(d.steps),
      (std::set<std::string>{"calibration_nonlinearity", "nonlinear_damping"}))
      << text;
  EXPECT_EQ(EffectIds(d.ambiguous).count("magnus"), 1u) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.3285}, {"Cm_q", -3.298}}, text);
}

// Any effect not excluded is tried in any step's place, not a tunnel
// term's alone (LowerInAStepsPlace): on draw 159's cone with a tunnel
// stiffness, a nonlinear damping and a body yaw asymmetry (sigma: auto;
// tests/data/coning_stiffness_damping_asymmetry_draw159.yaml) a Magnus
// moment was named beside the damping, `explained`; the asymmetry, never
// refitted after the first round and +2.8 beside the answer, is 1.2 lower
// in BIC in the Magnus moment's place. The two tie; the damping is named.
TEST(Diagnose, AnEffectNotExcludedIsTriedInAnyStepsPlace) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_stiffness_damping_asymmetry_draw159.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.steps), std::set<std::string>{"nonlinear_damping"})
      << text;
  EXPECT_EQ(EffectIds(d.ambiguous),
            (std::set<std::string>{"magnus", "asymmetric_body"}))
      << text;
}

// A tunnel term no round refitted nor tried beside the model joins the
// set of effects not excluded fitted in a step's place, and the set is
// trimmed no further than a tie allows: on draw 150's cone with a tunnel
// stiffness, a nonlinear damping and a body asymmetry a Magnus moment came
// in a joint set with the damping and the answer was `explained`; the
// asymmetry and the stiffness together in the moment's place tie with it.
// The final Cm_alpha covers the truth: the stiffness's t1 + t3 is its twin
// (Eq. 43), and the tie's model leaves them free. With the pitch noise
// held again nearer the truth (0.0065 -> 0.0084 deg; HeldAgain beside the
// tie) the stiffness is a lesser refit beside the model, joins the set
// last all the same (LesserRidge), and with the asymmetry past its bound
// among the three, the asymmetry and the stiffness stand in (AllButOne).
TEST(Diagnose, AnUntriedTunnelTermJoinsTheSetInAStepsPlace) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_stiffness_damping_asymmetry_vary150.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.steps), (std::set<std::string>{"nonlinear_damping"}))
      << text;
  EXPECT_EQ(
      EffectIds(d.ambiguous),
      (std::set<std::string>{"magnus", "asymmetric_body", "tunnel_stiffness"}))
      << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.2469}, {"Cm_q", -1.559}}, text);
}

// The tunnel terms no round tried join the set in a step's place last,
// where the set of the effects not excluded stands in for none: on draw
// 147's 3-s run with a tunnel damping, a Magnus moment and a flow
// angularity that set stands in for a false body asymmetry (+4.2), and
// with an untried tunnel stiffness among it rose 12.0 and the asymmetry
// was added.
TEST(Diagnose, AnUntriedTunnelTermJoinsTheSetLast) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_damping_magnus_angularity_vary147.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_TRUE(d.steps.empty()) << text;
  const std::set<std::string> tied = TiedIds(d);
  for (const char* id : {"tunnel_damping", "magnus", "flow_angularity"}) {
    EXPECT_TRUE(tied.count(id)) << id << "\n" << text;
  }
  ExpectFinalCovers(d, {{"Cm_alpha", -0.2113}, {"Cm_q", -7.787}}, text);
}

// Where the answer or a tie holds a member of the offset family (a trim
// moment, a roll reading error, a flow angularity), every other member
// whose score does not exclude it is tried beside the complete model: on
// draw 151's pair with a tunnel stiffness, a roll reading error and a
// flow angularity a trim moment tied with the reading error, the
// stiffness added, and the angularity (a BIC drop of -7.4 as its score
// reads) was never tried; beside the answer it rises 5.8, and is listed.
TEST(Diagnose, AnOffsetBesideAnOffsetsTwinIsTriedBesideTheModel) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("pair_stiffness_roll_error_angularity_vary151.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_TRUE(TiedIds(d).count("roll_interaction")) << text;
  EXPECT_TRUE(EffectIds(d.not_excluded).count("flow_angularity")) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.1954}, {"Cm_q", -4.106}}, text);
}

// An effect not excluded that lowers BIC beside the complete model may
// stand in for a step alone though a lesser refit at its round, and a
// tunnel term in a step's place is judged within two of its errors, as
// beside the model: on draw 150's 3-s run with a tunnel damping, a Magnus
// moment and a flow angularity a body yaw asymmetry was added (its Cn_r
// apart from Cm_q holds the damping's yaw term); the damping, 2.8 lower
// beside the answer, is 6.5 lower in the asymmetry's place with t4 1.64,
// past its bound of 1.59 at the point fit by a fifth of its error.
TEST(Diagnose, ALesserRefitLowerBesideTheModelStandsInAlone) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_damping_magnus_angularity_vary150.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(EffectIds(d.steps), (std::set<std::string>{"magnus"})) << text;
  EXPECT_TRUE(TiedIds(d).count("tunnel_damping")) << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.2076}, {"Cm_q", -2.213}}, text);
}

// An effect no round refitted whose score beside the complete model says
// it lowers BIC there is tried beside it, though short of min_bic_drop
// (tunnel terms aside: their scores leave Eq. 43's ridge open): on draw
// 147's cone with a Magnus moment, a nonlinear damping and a calibration
// error the two moments tied at the noise, and the calibration error, 7.6
// by its score, was never tried; beside the model it lowers BIC by 7.5
// and is listed as not excluded.
TEST(Diagnose, AnEffectWhoseScoreLowersBicBesideTheModelIsTried) {
  const Diagnosis d =
      DiagnoseConfig("coning_magnus_damping_calibration_vary147.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_TRUE(TiedIds(d).count("nonlinear_damping")) << text;
  EXPECT_TRUE(EffectIds(d.not_excluded).count("calibration_nonlinearity") ||
              EffectIds(d.steps).count("calibration_nonlinearity"))
      << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.2017}, {"Cm_q", -3.539}}, text);
}

// A set led by a contender refused alone is weighed against the sets of
// the one that earned its place alone (EarnedLeads): on draw 152's 3-s
// coning run with a tunnel stiffness, a nonlinear damping and a body yaw
// asymmetry (tests/data/coning_stiffness_damping_asymmetry_vary152.yaml),
// a Magnus moment's set with the damping was taken ahead of the asymmetry,
// and the record ended `not_explained`, silent about the asymmetry.
TEST(Diagnose, TheSetsOfTheEffectThatEarnedItsPlaceAloneAreWeighed) {
  const Diagnosis d =
      DiagnoseConfig("coning_stiffness_damping_asymmetry_vary152.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_NE(d.verdict, Verdict::kNotExplained) << text;
  EXPECT_TRUE(EffectIds(d.steps).count("nonlinear_damping")) << text;
  EXPECT_TRUE(TiedIds(d).count("asymmetric_body") ||
              EffectIds(d.steps).count("asymmetric_body"))
      << text;
  ExpectFinalCovers(d, {{"Cm_alpha", -0.267}, {"Cm_q", -2.114}}, text);
}

// A model explains the record only where its residuals depend on no angle,
// roll or time (Explains): on draw 152's coning run with an even
// calibration error of the pitch reading (tests/data/coning_even_
// calibration_vary152.yaml; outside the catalog) a flow angularity and a
// roll reading error tied at the noise level's limit, and the record was
// called `ambiguous` between them.
TEST(Diagnose, ResidualsThatDependOnTheAngleExplainNothing) {
  const Diagnosis d = DiagnoseConfig("coning_even_calibration_vary152.yaml");
  const std::string text = FormatDiagnosis(d, DiagnosedNoise(d, {}));
  EXPECT_EQ(d.verdict, Verdict::kNotExplained) << text;
  EXPECT_TRUE(d.steps.empty()) << text;
  EXPECT_TRUE(d.ambiguous.empty()) << text;
  EXPECT_NE(d.verdict_text.find("a dependence on the pitch angle"),
            std::string::npos)
      << text;
}

// Twins that earn their place together (the same fitted motion) are led by
// the one within its bounds at the point fit: on draw 145's Table 6 record
// with a bearing moment, a calibration error and a roll torque (sigma:
// auto; tests/data/table6_bearing_calibration_roll_torque_vary145.yaml) a
// roll damping led the torque by 0.001 of BIC at Cl_p = +6.1e-6 +- 3.7e-6,
// a damping that drives the roll; beside each later effect that sign grew
// determined and refused it, and the record ended `not_explained` with
// nothing named.
TEST(Diagnose, TheTwinWithinItsBoundsAtThePointFitLeads) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("table6_bearing_calibration_roll_torque_vary145.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kExplained) << text;
  EXPECT_EQ(EffectIds(d.steps),
            (std::set<std::string>{
                "roll_torque", "bearing_moment", "calibration_nonlinearity"}))
      << text;
  ExpectFinalCovers(d,
                    {{"Cm_alpha", -0.236},
                     {"Cm_q", -4.0},
                     {"Cm_bearing", -0.00092},
                     {"theta_cal3", 0.0713},
                     {"psi_cal3", 0.0741}},
                    text);
}

// An effect named past the noise level is refitted there even where its
// score, at the model's solution, gives it no degree of freedom
// (WithScores): on draw 130's 3-s run with a tunnel stiffness, a
// nonlinear damping and a body yaw asymmetry (tests/data/short_stiffness_
// damping_asymmetry_vary130.yaml) a roll torque and the asymmetry reached
// the noise at a steady cone, Cm_q -0.57 (truth -4.42), where the
// damping's delta^2 is a constant and the damping an exact twin of Cm_q;
// beside that model its fit lowered BIC by 52.6. The answer had been
// `explained` with the torque and the asymmetry; the damping is now named,
// and the torque ties with the stiffness.
TEST(Diagnose, AnEffectNamedPastTheNoiseIsRefittedWhateverItsScore) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("short_stiffness_damping_asymmetry_vary130.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  EXPECT_EQ(d.verdict, Verdict::kAmbiguous) << text;
  EXPECT_EQ(EffectIds(d.steps),
            (std::set<std::string>{"asymmetric_body", "nonlinear_damping"}))
      << text;
  EXPECT_TRUE(EffectIds(d.ambiguous).count("tunnel_stiffness")) << text;
  ExpectFinalCovers(d, {{"Cm_q", -4.418}}, text);
}

// A calibration error alone at 0.9 of its bound, on a pair of 3-s runs
// whose yaw reading stays near zero, fitted at 0.214 deg against a bound
// of 0.21 (theta_cal3 0.075 +- 0.040): refused at its point fit, it led a
// joint set with a nonlinear damping, tied with a bearing moment and a
// tunnel stiffness, in the search that judges bounds on a ridge within
// their errors. The search that judges every bound so names the
// calibration alone, 4.1 lower in BIC, and that answer is taken
// (FromBounds).
TEST(Diagnose, BoundsWithinErrorsTakesTheAnswerOfLowerBic) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three searches; plain build";
  const Diagnosis d = DiagnoseConfig("pair_calibration_vary117.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(d,
                     {"calibration_nonlinearity"},
                     {{"Cm_alpha", -0.1541},
                      {"Cm_q", -9.612},
                      {"theta_cal3", -0.0715},
                      {"psi_cal3", -0.1194}},
                     text);
  EXPECT_NE(text.find("every effect's bounds judged within two of its "
                      "errors"),
            std::string::npos)
      << text;
}

// The same pair of runs with the cube in the pitch reading alone, fitted
// at 0.226 deg against a bound of 0.223: the second search ties a
// nonlinear damping, a bearing moment and a tunnel stiffness beside the
// calibration, though each raises BIC beside it (its final model the
// calibration alone, as the third search's). Of two answers alike in
// BIC the one that claims fewer effects is taken (ExplainsBetter).
TEST(Diagnose, BoundsWithinErrorsTakesTheAnswerOfFewerEffects) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three searches; plain build";
  const Diagnosis d = DiagnoseConfig("pair_calibration_in_pitch_vary117.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(d,
                     {"calibration_nonlinearity"},
                     {{"Cm_alpha", -0.1541},
                      {"Cm_q", -9.612},
                      {"theta_cal3", 0.0607},
                      {"psi_cal3", 0.0}},
                     text);
}

// On a 3.5-s coning run with a tunnel stiffness, a nonlinear damping and
// a body yaw asymmetry, the stiffness's t1 + t3 is Cm_alpha's exact twin
// (Eq. 43) but t1 - t3 is not: scored 31.9 beside the other two, it is
// tried there (Unrefitted skips near twins only) and lowers BIC by 27.7.
// Fitted to the first part of the record, Cm_alpha and t1 slid along
// their ridge and predicted the rest worse (gain -5.3); with the body's
// stiffness held there (RidgeHeld) the stiffness earns its place past the
// noise, and all three are named.
TEST(Diagnose, ATunnelStiffnessIsJudgedOutOfSampleOffItsRidge) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  const Diagnosis d =
      DiagnoseConfig("coning_stiffness_damping_asymmetry_vary117.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(
      d,
      {"tunnel_stiffness", "nonlinear_damping", "asymmetric_body"},
      {{"Cm_alpha", -0.355},
       {"Cm_q", -5.958},
       {"Cn_beta", 0.3555},
       {"tunnel_Cm_theta", -3.11e-4},
       {"tunnel_Cn_psi", 1.09e-4}},
      text);
}

// On a Table 6 record with a tunnel stiffness, a nonlinear damping and a
// body yaw asymmetry (sigma: auto), the stiffness and the damping drag
// the coefficients alone, a false calibration error earns its place first,
// and the asymmetry, refitted at the second round, lowers BIC the most
// (1113) but leaves its bounds (|Cn_r - Cm_q| 13.5 against |Cm_q| 11.1).
// Ranked ahead of the damping that leads the joint sets, it was left out
// of its pools (only a contender that failed out of sample joined from
// ahead), they stopped at 1.77 times the noise, and the three were named
// only by a later search: without the calibration (DeadEndBranch), or,
// without probes, with contenders out of their bounds leading joint sets
// (FromBounds), which the verdict says. Where the pools by BIC and by
// score fail, one with those out of their bounds ahead of the lead is
// tried (BoundedAheadPool): the first search names the three.
TEST(Diagnose, AContenderOutOfItsBoundsJoinsThePoolsOfThoseBelowIt) {
  if (testing::PlainBuildOnly()) GTEST_SKIP() << "three effects; plain build";
  DiagnoseOptions options;
  options.probes = false;  // no DeadEndBranch: the first search or FromBounds
  const Diagnosis d = Diagnose(
      LoadConfig(testing::SourcePath(
          "tests/data/table6_stiffness_damping_asymmetry_vary135.yaml")),
      options);
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(
      d,
      {"tunnel_stiffness", "nonlinear_damping", "asymmetric_body"},
      {{"Cm_alpha", -0.236},
       {"Cm_q", -4.0},
       {"Cm_q_alpha2", -132.7},
       {"Cn_beta", 0.2047},
       {"tunnel_Cm_theta", 1.394e-3},
       {"tunnel_Cn_psi", -4.88e-4}},
      text);
  EXPECT_EQ(d.verdict_text.find("found with"), std::string::npos) << text;
}

// A nonlinear damping on a 3.16-s coning run of another body (sigma:
// auto) lowers BIC by 92, but fitted to the even runs of samples it
// predicted the odd ones by a log-likelihood gain of 0.7 (needs 2): most
// of its drop lies in the even runs, the first among them at the largest
// angles. With one split the record ended `not_explained`, Cm_q 47 of its
// errors off; an effect with a positive gain short of the bar on one half
// is judged on the other too (OutOfSample::GainOfBothHalves), where the
// damping clears it and is named.
TEST(Diagnose, AnEffectOneHalfMissesIsJudgedOnBothHalves) {
  const Diagnosis d = DiagnoseConfig("coning_nonlinear_damping_vary134.yaml");
  const std::string text = FormatDiagnosis(d, {0.01, 0.01, 0.01});
  ExpectNamedExactly(
      d,
      {"nonlinear_damping"},
      {{"Cm_alpha", -0.3971}, {"Cm_q", -9.239}, {"Cm_q_delta2", 65.09}},
      text);
}

}  // namespace
}  // namespace fit3dof
