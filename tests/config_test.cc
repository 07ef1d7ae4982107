// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/config.h"

#include <string>

#include "fit3dof/input_error.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

const char kValid[] = R"(name: table6
model: symmetric
incidence: velocity_ratio
body:
  area: 0.390
  diameter: 0.7047
  Ix: 0.0372
  Iy: 0.244
flow:
  velocity: 4774.0
  dynamic_pressure: 150.4
parameters:
  Cm_alpha: {value: -0.2, free: true}
  Cm_q: {value: 0.0, free: true}
  Cl_p: -0.0081
  t1: 0.01
  theta0: {value: 5.18, free: true}
initial_conditions: from_data
data:
  file: run12.csv
  start: 2
  fraction: 0.5
  every: 3
sigma: {phi: 1.0, theta: 0.05, psi: 0.05}
noise:
  sigma: {theta: 0.01, psi: 0.01}
  seed: 7
solver: {max_iterations: 20, tolerance: 1.0e-5, step: 0.002}
simulate: {duration: 10.0, dt: 0.01}
)";

Case Parse(const std::string& text) {
  return ParseConfig(text, "test.yaml", "/data");
}

// The message of the InputError that parsing `text` throws.
std::string Error(const std::string& text) {
  try {
    Parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string Replace(std::string text,
                    const std::string& from,
                    const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(Config, ReadsEveryKey) {
  const Case c = Parse(kValid);
  EXPECT_EQ(c.name, "table6");
  EXPECT_EQ(c.model, ModelKind::kSymmetric);
  EXPECT_EQ(c.incidence, Incidence::kVelocityRatio);
  EXPECT_DOUBLE_EQ(c.body.Iz, 0.244);  // symmetric: I = Iy
  EXPECT_DOUBLE_EQ(c.flow.dynamic_pressure, 150.4);
  EXPECT_DOUBLE_EQ(c.parameters[0].value, -0.2);
  EXPECT_TRUE(c.parameters[0].free);
  EXPECT_DOUBLE_EQ(c.parameters[12].value, -0.0081);
  EXPECT_FALSE(c.parameters[12].free);
  EXPECT_DOUBLE_EQ(c.parameters[20].value, 0.01);  // t1 alias
  ASSERT_EQ(c.segments.size(), 1u);
  EXPECT_EQ(c.segments[0].data_file, "/data/run12.csv");
  EXPECT_EQ(c.segments[0].selection.start, 2);
  EXPECT_DOUBLE_EQ(c.segments[0].selection.fraction, 0.5);
  EXPECT_EQ(c.segments[0].selection.every, 3);
  EXPECT_DOUBLE_EQ(c.segments[0].initial[2].value, 5.18);  // theta0
  EXPECT_TRUE(c.segments[0].initial[2].free);
  EXPECT_DOUBLE_EQ(c.sigma.theta, 0.05);
  EXPECT_TRUE(c.noise.enabled);
  EXPECT_DOUBLE_EQ(c.noise.sigma.phi, 0.0);
  EXPECT_DOUBLE_EQ(c.noise.sigma.psi, 0.01);
  EXPECT_EQ(c.noise.seed, 7u);
  EXPECT_EQ(c.solver.max_iterations, 20);
  EXPECT_DOUBLE_EQ(c.solver.step, 0.002);
  EXPECT_EQ(c.simulate.NumSamples(), 1001);
}

TEST(Config, AutoStartingValuesAndSolverMethod) {
  std::string text = Replace(
      kValid, "Cm_alpha: {value: -0.2, free: true}", "Cm_alpha: {free: true}");
  text = Replace(text,
                 "Cm_q: {value: 0.0, free: true}",
                 "Cm_q: {value: auto, free: true}");
  text = Replace(text,
                 "step: 0.002}",
                 "step: 0.002, method: gauss_newton, max_probable_error: 5}");
  const Case c = Parse(text);
  EXPECT_TRUE(c.parameters[0].auto_start);
  EXPECT_TRUE(c.parameters[1].auto_start);
  EXPECT_FALSE(c.parameters[12].auto_start);
  EXPECT_EQ(c.solver.method, FitMethod::kGaussNewton);
  EXPECT_DOUBLE_EQ(c.solver.max_probable_error, 5.0);
  EXPECT_NE(Error(Replace(kValid, "Cl_p: -0.0081", "Cl_p: {value: auto}"))
                .find("a frozen parameter needs a value"),
            std::string::npos);
  EXPECT_NE(
      Error(Replace(kValid, "step: 0.002}", "step: 0.002, method: newton}"))
          .find("solver.method: expected levenberg_marquardt, gauss_newton "
                "or filter_error"),
      std::string::npos);
}

TEST(Config, ProcessNoiseForTheFilterErrorMethod) {
  const std::string filter =
      Replace(kValid, "step: 0.002}", "step: 0.002, method: filter_error}");
  const Case c =
      Parse(filter + "process_noise: {roll: auto, pitch: 2.5, yaw: auto}\n");
  EXPECT_EQ(c.solver.method, FitMethod::kFilterError);
  EXPECT_TRUE(c.process_noise.estimated[0]);
  EXPECT_FALSE(c.process_noise.estimated[1]);
  EXPECT_DOUBLE_EQ(c.process_noise.intensity[1], 2.5);
  EXPECT_TRUE(c.process_noise.estimated[2]);
  EXPECT_EQ(Parse(CaseToYaml(c)), c);
  // The method needs the block, the block the method; bad values named.
  EXPECT_NE(Error(filter).find("filter_error needs process_noise"),
            std::string::npos);
  EXPECT_NE(Error(std::string(kValid) + "process_noise: {pitch: auto}\n")
                .find("process_noise: used only by solver: {method: "
                      "filter_error}"),
            std::string::npos);
  EXPECT_NE(Error(filter + "process_noise: {pich: auto}\n").find("pich"),
            std::string::npos);
  EXPECT_NE(Error(filter + "process_noise: {pitch: -1}\n")
                .find("process_noise.pitch"),
            std::string::npos);
  EXPECT_NE(Error(filter + "process_noise: {pitch: lots}\n")
                .find("process_noise.pitch"),
            std::string::npos);
}

TEST(Config, DensityGivesTheDynamicPressure) {
  const Case c =
      Parse(Replace(kValid, "dynamic_pressure: 150.4", "density: 0.00002"));
  EXPECT_NEAR(c.flow.dynamic_pressure, 0.5 * 0.00002 * 4774.0 * 4774.0, 1e-9);
}

TEST(Config, ReadsSegments) {
  std::string text = Replace(
      kValid,
      "data:\n  file: run12.csv\n  start: 2\n  fraction: 0.5\n  every: 3\n",
      "segments:\n"
      "  - name: first\n"
      "    data: {file: a.csv}\n"
      "    parameters: {psi0: {value: 1.0, free: true}}\n"
      "  - data: {file: /abs/b.csv, t_start: 1.0, t_end: 5.0}\n"
      "    initial_conditions: given\n");
  const Case c = Parse(text);
  ASSERT_EQ(c.segments.size(), 2u);
  EXPECT_EQ(c.segments[0].name, "first");
  EXPECT_EQ(c.segments[0].data_file, "/data/a.csv");
  EXPECT_DOUBLE_EQ(c.segments[0].initial[4].value, 1.0);
  EXPECT_DOUBLE_EQ(c.segments[0].initial[2].value, 5.18);  // from defaults
  EXPECT_EQ(c.segments[1].name, "segment2");
  EXPECT_EQ(c.segments[1].data_file, "/abs/b.csv");
  EXPECT_EQ(c.segments[1].initial_conditions, InitialConditionMode::kGiven);
  EXPECT_DOUBLE_EQ(c.segments[1].selection.t_end, 5.0);
}

struct BadCase {
  const char* from;
  const char* to;
  const char* expected;  // must appear in the message
};

class ConfigErrors : public ::testing::TestWithParam<BadCase> {};

TEST_P(ConfigErrors, NamesFileLineKeyAndProblem) {
  const BadCase& bad = GetParam();
  const std::string message = Error(Replace(kValid, bad.from, bad.to));
  EXPECT_NE(message.find("test.yaml:"), std::string::npos) << message;
  EXPECT_NE(message.find(bad.expected), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    Config,
    ConfigErrors,
    ::testing::Values(
        BadCase{"Cl_p: -0.0081",
                "Cm_alfa: -0.0081",
                "test.yaml:15: parameters.Cm_alfa: unknown parameter of the "
                "symmetric model (did you mean Cm_alpha?)"},
        BadCase{"Cl_p: -0.0081",
                "Izx: 0.001",
                "it belongs to the asymmetric model"},
        BadCase{"  area: 0.390\n",
                "",
                "test.yaml:5: body.area: missing (required)"},
        BadCase{"Ix: 0.0372",
                "Ix: -0.0372",
                "test.yaml:7: body.Ix: must be positive"},
        BadCase{"Ix: 0.0372", "Ix: .nan", "body.Ix: expected a finite number"},
        BadCase{"Ix: 0.0372",
                "Ix: heavy",
                "body.Ix: expected a number, got 'heavy'"},
        BadCase{"Ix: 0.0372", "Ix: 0.6", "cannot be the moments of inertia"},
        BadCase{"  Iy: 0.244\n",
                "  Iy: 0.244\n  Iz: 0.25\n",
                "body.Iz: the symmetric model needs Iy = Iz"},
        BadCase{"  velocity: 4774.0\n",
                "  velocity: 4774.0\n  density: 0.001\n",
                "give exactly one of dynamic_pressure"},
        BadCase{"model: symmetric",
                "model: round",
                "model: expected 'symmetric' or 'asymmetric'"},
        BadCase{"incidence: velocity_ratio",
                "incidence: tobak",
                "incidence: expected 'velocity_ratio'"},
        BadCase{
            "name: table6", "name: table6\nsigmas: 1", "sigmas: unknown key"},
        BadCase{"sigma: {phi: 1.0, theta: 0.05, psi: 0.05}",
                "sigma: {phi: 1.0, theta: 0.0, psi: 0.05}",
                "sigma.theta: must be positive (deg) or auto"},
        BadCase{"sigma: {phi: 1.0, theta: 0.05, psi: 0.05}",
                "sigma: {phi: 1.0, theta: 0.05}",
                "sigma.psi: missing"},
        BadCase{"start: 2",
                "start: 0",
                "test.yaml:21: data.start: expected an integer from 1 to"},
        BadCase{"fraction: 0.5",
                "fraction: 1.5",
                "data.fraction: must be in (0, 1]"},
        BadCase{"step: 0.002", "step: 0", "solver.step: must be positive"},
        BadCase{"Cl_p: -0.0081",
                "Cl_p: {free: false}",
                "a frozen parameter needs a value"},
        BadCase{"Cl_p: -0.0081", "spare16: 1.0", "spare slot"},
        BadCase{"Cl_p: -0.0081",
                "cal_range: -8",
                "parameters.cal_range: must be >= 0 (deg; 0 takes no line), "
                "got -8"},
        BadCase{"initial_conditions: from_data",
                "initial_conditions: guess",
                "initial_conditions: expected 'from_data'"},
        BadCase{"{duration: 10.0, dt: 0.01}",
                "{duration: 10.0, samples: 5, dt: 0.01}",
                "give exactly one of duration"},
        BadCase{"Cl_p: -0.0081", "Cl_p: -0.0081\n  t1: 0.02", "given twice"},
        BadCase{
            "seed: 7", "seed: -1", "noise.seed: expected an integer from 0 to"},
        BadCase{"every: 3", "every: [3]", "data.every: expected a number"},
        // Issue 9: what yaml-cpp lets through.
        BadCase{"  start: 2\n",
                "  start: 2\n  start: 5\n",
                "test.yaml:22: start: given twice in one mapping (first at "
                "line 21)"},
        BadCase{"model: symmetric",
                "model: symmetric\nmodel: asymmetric",
                "test.yaml:3: model: given twice"},
        BadCase{"Cl_p: -0.0081",
                "Cl_p: {value: -0.0081, value: 1.0}",
                "value: given twice"},
        BadCase{"simulate: {duration: 10.0, dt: 0.01}",
                "simulate: {duration: 10.0, dt: 0.01}\n---\nname: other",
                "test.yaml:30: a second YAML document"},
        BadCase{"Cl_p: -0.0081", "? [a, b]\n  : 1", "complex keys"},
        BadCase{"max_iterations: 20",
                "max_iterations: 2147483648",
                "solver.max_iterations: expected an integer from 1 to 1000000"},
        BadCase{"max_iterations: 20",
                "max_iterations: 1e300",
                "solver.max_iterations: expected an integer"},
        BadCase{"name: table6",
                "name: tab\xE9le",
                "test.yaml:1: the text is not valid UTF-8"},
        BadCase{"file: run12.csv",
                "file: run\xff.csv",
                "test.yaml:20: the text is not valid UTF-8"},
        BadCase{"every: 3",
                "every: 3000000000",
                "data.every: expected an integer from 1 to 2147483647"},
        // Ties (case.h).
        BadCase{"Cl_p: -0.0081",
                "Cl_p: {tied: Cl_pp, factor: 2}",
                "parameters.Cl_p.tied: unknown parameter 'Cl_pp'"},
        BadCase{"Cl_p: -0.0081",
                "Cl_p: {tied: Cl_p}",
                "parameters.Cl_p.tied: expected another parameter"},
        BadCase{"Cl_p: -0.0081",
                "Cl_p: {tied: theta0}",
                "initial conditions belong to each segment"},
        BadCase{"Cl_p: -0.0081",
                "Cl_p: {tied: Cm_q, value: 1}",
                "parameters.Cl_p.value: unknown key"},
        BadCase{"Cl_p: -0.0081",
                "Cl_p: {tied: Cm_q, factor: x}",
                "parameters.Cl_p.factor: expected a number"},
        BadCase{"Cl_p: -0.0081",
                "Cl_p: {tied: t2}\n  t2: {tied: Cm_q}",
                "is itself tied; tie to the parameter it follows"}));

// A tied parameter holds its factor times its source's value, and follows
// it as a fit moves it (fit_test, segment_cost_function_test).
TEST(Config, TiedParameterFollowsItsSource) {
  const Case c = Parse(
      Replace(kValid, "Cl_p: -0.0081", "Cl_p: {tied: Cm_q, factor: 0.5}"));
  const int cl_p = FindParameter(ModelKind::kSymmetric, "Cl_p");
  const int cm_q = FindParameter(ModelKind::kSymmetric, "Cm_q");
  ASSERT_TRUE(c.parameters[cl_p].tied());
  EXPECT_EQ(c.parameters[cl_p].tied_to, cm_q);
  EXPECT_FALSE(c.parameters[cl_p].free);
  EXPECT_EQ(c.Values()[cl_p], 0.5 * c.Values()[cm_q]);
  EXPECT_EQ(c.parameters[cl_p].value, 0.5 * c.parameters[cm_q].value);
  EXPECT_EQ(c.VaryingFlags()[cl_p], c.parameters[cm_q].free);
  ASSERT_EQ(c.Ties().size(), 1u);
  EXPECT_EQ(c.Ties()[0].factor, 0.5);
}

TEST(Config, AsymmetricNeedsIzAndAValidProductOfInertia) {
  std::string text = Replace(kValid, "model: symmetric", "model: asymmetric");
  text = Replace(text, "Cm_q:", "Cn_r:");
  EXPECT_NE(Error(text).find("body.Iz: missing (required)"), std::string::npos);
  text = Replace(text, "  Iy: 0.244\n", "  Iy: 0.244\n  Iz: 0.25\n");
  EXPECT_EQ(Error(text), "(no error)");
  EXPECT_NE(Error(Replace(text, "Cl_p: -0.0081", "Izx: 0.2"))
                .find("|Izx| must be below"),
            std::string::npos);
  EXPECT_NE(Error(Replace(text, "Cl_p: -0.0081", "Cm_alpha_delta2: 1.0"))
                .find("unknown parameter of the asymmetric model"),
            std::string::npos);
}

TEST(Config, ReportsYamlSyntaxErrorsWithALine) {
  const std::string message = Error("model: symmetric\nbody: {area: 1\n");
  EXPECT_NE(message.find("test.yaml:"), std::string::npos) << message;
  EXPECT_NE(message.find("not valid YAML"), std::string::npos) << message;
}

TEST(Config, MissingFileIsAnInputError) {
  try {
    LoadConfig("/nonexistent/config.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/config.yaml"),
              std::string::npos);
  }
}

TEST(Config, ReportConfigsLoad) {
  for (const char* name : {"check_case_1.yaml",
                           "check_case_1_printed.yaml",
                           "check_case_2.yaml",
                           "table6_motion.yaml",
                           "section5_1_motion.yaml"}) {
    EXPECT_NO_THROW(
        LoadConfig(testing::SourcePath(std::string("configs/report/") + name)))
        << name;
  }
}

// sigma: auto for every channel or some: those weights are estimated.
TEST(Config, SigmaAutoForAllChannelsOrSome) {
  const std::string dir = testing::ScratchDirectory("config_sigma_auto");
  std::string text = testing::ReadText(
      testing::SourcePath("configs/report/table6_sigma0.01.yaml"));
  const size_t at = text.find("sigma: {");
  ASSERT_NE(at, std::string::npos);
  const std::string line = text.substr(at, text.find('\n', at) - at);
  auto with = [&](const std::string& sigma) {
    std::string t = text;
    t.replace(at, line.size(), sigma);
    return ParseConfig(t, "s.yaml", testing::SourcePath("configs/report"));
  };
  const Case all = with("sigma: auto");
  EXPECT_EQ(all.sigma_auto, (std::array<bool, 3>{{true, true, true}}));
  const Case some = with("sigma: {phi: auto, theta: 0.02, psi: 0.03}");
  EXPECT_EQ(some.sigma_auto, (std::array<bool, 3>{{true, false, false}}));
  EXPECT_DOUBLE_EQ(some.sigma.theta, 0.02);
  EXPECT_THROW(with("sigma: automatic"), InputError);
  EXPECT_THROW(with("sigma: {phi: auto, theta: 0.02}"), InputError);
}

}  // namespace
}  // namespace fit3dof
