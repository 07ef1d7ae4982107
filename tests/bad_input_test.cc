// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The catalog of malformed inputs (issue 9): configs, data files,
// manifests, decks and flags, each run through the built command. Every one
// must exit with status 2, name the file and the line or key (or the flag),
// and leave nothing in the output directory.

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

namespace fs = std::filesystem;

// A small valid fit config (the Table 6 record's first 3.6 s); cases edit
// one thing in it.
std::string ValidConfig() {
  return "name: catalog\n"
         "model: symmetric\n"
         "body: {area: 0.390, diameter: 0.7047, Ix: 0.0372, Iy: 0.244}\n"
         "flow: {velocity: 4774.0, dynamic_pressure: 150.4}\n"
         "parameters:\n"
         "  Cm_alpha: {value: -0.2, free: true}\n"
         "  Cm_q: {value: 0.0, free: true}\n"
         "initial_conditions: from_data\n"
         "data: {file: data.csv}\n"
         "sigma: {phi: 0.01, theta: 0.01, psi: 0.01}\n"
         "solver: {max_iterations: 50, step: 0.01}\n";
}

std::string ValidData() {
  return "t,phi,theta,psi\n0,0,5.18,-2.589\n0.06,38.47,3.36,-2.99\n"
         "0.12,76.96,1.18,-3.23\n0.18,115.45,-1.07,-3.23\n";
}

std::string Edit(std::string text,
                 const std::string& from,
                 const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

struct BadInput {
  std::string name;
  std::string config;    // written to DIR/config.yaml when not empty
  std::string data;      // written to DIR/data.csv when not empty
  std::string extra;     // written to DIR/extra (manifest or deck)
  std::string command;   // with DIR for the case's directory
  std::string expected;  // must appear in the message
};

std::vector<BadInput> Catalog() {
  const std::string c = ValidConfig();
  const std::string d = ValidData();
  const std::string fit = "fit DIR/config.yaml --out_dir=DIR/out";
  std::vector<BadInput> v;
  auto config = [&](const std::string& name,
                    const std::string& from,
                    const std::string& to,
                    const std::string& expected) {
    v.push_back({name, Edit(c, from, to), d, "", fit, expected});
  };
  auto data = [&](const std::string& name,
                  const std::string& text,
                  const std::string& expected) {
    v.push_back({name, c, text, "", fit, expected});
  };
  // Configs.
  config("unknown key", "sigma:", "sigmas:", "config.yaml:10: sigmas");
  config("misspelt parameter",
         "Cm_q:",
         "Cm_qq:",
         "config.yaml:7: parameters.Cm_qq");
  config("duplicate key",
         "name: catalog",
         "name: catalog\nname: again",
         "config.yaml:2: name: given twice");
  config("nested duplicate",
         "Ix: 0.0372,",
         "Ix: 0.0372, Ix: 0.04,",
         "config.yaml:3: Ix: given twice");
  config("second document",
         "solver:",
         "---\nsolver:",
         "config.yaml:11: a second YAML document");
  config("complex key",
         "initial_conditions",
         "? [a]\n: 1\ninitial_conditions",
         "complex keys");
  config("iterations out of range",
         "max_iterations: 50",
         "max_iterations: 2147483648",
         "config.yaml:11: solver.max_iterations");
  config("non-integer iterations",
         "max_iterations: 50",
         "max_iterations: 2.5",
         "solver.max_iterations");
  config("negative step",
         "step: 0.01",
         "step: -0.01",
         "solver.step: must be positive");
  config(
      "a step of a nanosecond",
      "step: 0.01",
      "step: 1.0e-9",
      "RK4 steps per evaluation (0.18 s of record at solver.step = 1e-09 s)");
  data("time column in microseconds",
       "t,phi,theta,psi\n0,0,5,0\n6000000,1,5,0\n12000000,2,5,0\n",
       "would take 1.2e+09 RK4 steps");
  config("simulate a year at 1 ms",
         "solver:",
         "simulate: {dt: 0.001, duration: 3.2e7}\nsolver:",
         "simulate.duration: duration / dt gives");
  config("text for a number",
         "area: 0.390",
         "area: big",
         "config.yaml:3: body.area: expected a number");
  config("infinite number",
         "area: 0.390",
         "area: .inf",
         "body.area: expected a finite number");
  config("missing body",
         "body: {area: 0.390, diameter: 0.7047, Ix: 0.0372, Iy: 0.244}\n",
         "",
         "body: missing");
  config(
      "bad model", "model: symmetric", "model: round", "config.yaml:2: model");
  config("bad incidence",
         "model: symmetric",
         "model: symmetric\nincidence: sideways",
         "incidence");
  config("both q and rho",
         "dynamic_pressure: 150.4",
         "dynamic_pressure: 150.4, density: 0.002",
         "flow: give exactly one");
  config("zero sigma",
         "phi: 0.01, theta: 0.01, psi: 0.01}",
         "phi: 0.0, theta: 0.01, psi: 0.01}",
         "sigma.phi: must be positive (deg) or auto");
  config("NUL byte in a comment (fuzzer finding: yaml-cpp never returned)",
         "name: catalog",
         std::string("name: catalog\n# a comment\0\0 with NUL", 36),
         "config.yaml:2: a control character (0x00)");
  config("a lone comma (fuzzer finding: yaml-cpp's LoadAll never returned)",
         "name: catalog",
         ",",
         "config.yaml");
  config("non-UTF-8 name",
         "name: catalog",
         "name: cat\xC3\x28log",
         "config.yaml:1: the text is not valid UTF-8");
  config("non-UTF-8 path",
         "file: data.csv",
         "file: d\xFF.csv",
         "config.yaml:9: the text is not valid UTF-8");
  config("no data", "data: {file: data.csv}\n", "", "data: missing");
  config("missing data file",
         "file: data.csv",
         "file: nothing.csv",
         "nothing.csv: cannot open");
  config("data and segments",
         "data: {file: data.csv}",
         "data: {file: data.csv}\nsegments: [{data: {file: data.csv}}]",
         "segments: give either data");
  config(
      "every parameter frozen",
      "Cm_alpha: {value: -0.2, free: true}\n  Cm_q: {value: 0.0, free: true}",
      "Cm_alpha: -0.2",
      "every parameter is frozen");
  config("spare slot", "Cm_q:", "spare16: 1.0\n  Cm_q:", "spare slot");
  config("fraction above one",
         "file: data.csv}",
         "file: data.csv, fraction: 2}",
         "data.fraction");
  config("unknown outlier policy",
         "file: data.csv}",
         "file: data.csv, outliers: drop}",
         "data.outliers");
  config("start beyond the record",
         "file: data.csv}",
         "file: data.csv, start: 40}",
         "leaves 0 samples");
  config("empty window",
         "file: data.csv}",
         "file: data.csv, t_start: 5, t_end: 1}",
         "t_end must be later");
  config("sequence for a mapping",
         "solver: {max_iterations: 50, step: 0.01}",
         "solver: [1, 2]",
         "solver: expected a mapping");
  config("bad method",
         "step: 0.01}",
         "step: 0.01, method: newton}",
         "solver.method");
  config(
      "YAML syntax", "model: symmetric", "model: [symmetric", "not valid YAML");
  config("noise seed negative",
         "solver:",
         "noise: {seed: -1}\nsolver:",
         "noise.seed");
  // Data files.
  data("empty field",
       "t,phi,theta,psi\n0,0,5,0\n0.06,,5,0\n0.12,1,5,0\n",
       "data.csv:3: column 'phi'");
  data("lone minus",
       "t,phi,theta,psi\n0,0,5,0\n0.06,-,5,0\n0.12,1,5,0\n",
       "data.csv:3: column 'phi': expected a finite decimal number, got '-'");
  data("lone dot",
       "t,phi,theta,psi\n0,0,5,0\n0.06,1,.,0\n0.12,1,5,0\n",
       "data.csv:3: column 'theta'");
  data(
      "dangling exponent",
      "t,phi,theta,psi\n0,0,5,0\n0.06,1,5,1.5e\n0.12,1,5,0\n",
      "data.csv:3: column 'psi': expected a finite decimal number, got '1.5e'");
  data("nan",
       "t,phi,theta,psi\n0,0,5,0\n0.06,nan,5,0\n0.12,1,5,0\n",
       "got 'nan'");
  data("infinity",
       "t,phi,theta,psi\n0,0,5,0\n0.06,1,inf,0\n0.12,1,5,0\n",
       "got 'inf'");
  data("overflow",
       "t,phi,theta,psi\n0,0,5,0\n0.06,1e999,5,0\n0.12,1,5,0\n",
       "got '1e999'");
  data("text token",
       "t,phi,theta,psi\n0,0,5,0\n0.06,abc,5,0\n0.12,1,5,0\n",
       "got 'abc'");
  data("missing column",
       "t,phi,theta\n0,0,5\n0.06,1,5\n",
       "data.csv: the header has no column 'psi'");
  data("duplicate column",
       "t,phi,theta,psi,phi\n0,0,5,0,0\n0.06,1,5,0,0\n",
       "names column 'phi' twice");
  data("short row",
       "t,phi,theta,psi\n0,0,5,0\n0.06,1,5\n",
       "data.csv:3: fewer fields");
  data("long row",
       "t,phi,theta,psi\n0,0,5,0\n0.06,1,5,0,9\n",
       "data.csv:3: more fields");
  data("unclosed quote",
       "t,phi,theta,psi\n0,0,5,0\n0.06,\"1,5,0\n",
       "data.csv:3: a quoted field is not closed");
  data("times repeat",
       "t,phi,theta,psi\n0,0,5,0\n0.06,1,5,0\n0.06,1,5,0\n",
       "data.csv:4: times must increase");
  data("times go back",
       "t,phi,theta,psi\n0,0,5,0\n0.06,1,5,0\n0.03,1,5,0\n",
       "data.csv:4: times must increase");
  data("one row", "t,phi,theta,psi\n0,0,5,0\n", "at least two rows");
  data("header only", "t,phi,theta,psi\n", "at least two rows");
  data("empty file", "\n", "data.csv");
  // Manifests (batch).
  auto manifest = [&](const std::string& name,
                      const std::string& text,
                      const std::string& expected) {
    v.push_back({name,
                 c,
                 d,
                 text,
                 "batch DIR/extra --out_dir=DIR/out --progress=false",
                 expected});
  };
  manifest("manifest unknown key",
           "runs:\n  - {name: a, config: config.yaml}\nrunz: 1\n",
           "extra:3: runz: unknown key of a manifest");
  manifest("manifest duplicate run",
           "runs:\n  - {name: a, config: config.yaml}\n  - {name: a, config: "
           "config.yaml}\n",
           "'a' is used twice");
  manifest("manifest duplicate key",
           "runs:\n  - {name: a}\nruns:\n  - {name: b}\n",
           "extra:3: runs: given twice");
  manifest("manifest reserved name",
           "runs:\n  - {name: summary.json, config: config.yaml}\n",
           "'summary.json' is the name of a file");
  manifest("manifest lock name",
           "runs:\n  - {name: .fit3dof.lock, config: config.yaml}\n",
           "is the name of a file");
  manifest("manifest start_from list",
           "runs:\n  - {name: a, config: config.yaml, start_from: [b]}\n",
           "extra:2: runs[0]: start_from: expected the name of a run");
  manifest("manifest unknown start_from",
           "runs:\n  - {name: a, config: config.yaml, start_from: b}\n",
           "no run named 'b'");
  manifest(
      "manifest cycle",
      "runs:\n  - {name: a, start_from: b}\n  - {name: b, start_from: a}\n",
      "cycle");
  manifest(
      "manifest empty runs", "runs: []\n", "runs: expected a non-empty list");
  manifest("manifest bad diagnose",
           "runs:\n  - {name: a, config: config.yaml, diagnose: maybe}\n",
           "diagnose: expected true or false");
  manifest("manifest together not a list",
           "runs:\n  - {name: a, config: config.yaml}\n  - {name: g, "
           "together: a}\n",
           "extra:3: runs[1]: together: expected a list of run names");
  manifest("manifest together with its own data",
           "runs:\n  - {name: a, config: config.yaml}\n  - {name: b, config: "
           "config.yaml}\n  - {name: g, together: [a, b], data: {file: "
           "x.csv}}\n",
           "data: a together run takes its records");
  manifest("manifest unsafe name",
           "runs:\n  - {name: ../x, config: config.yaml}\n",
           "run name '../x' must use only");
  manifest("manifest second document",
           "runs:\n  - {name: a}\n---\nruns: []\n",
           "extra:3: a second YAML document");
  // Decks.
  auto deck = [&](const std::string& name,
                  const std::string& text,
                  const std::string& expected) {
    v.push_back({name,
                 "",
                 d,
                 text,
                 "namelist DIR/extra --out=DIR/out/deck.yaml",
                 expected});
  };
  deck("deck repeat beyond the array",
       " &NAM AACON(5)=1000000000*0.0 &END\n",
       "extra:1: AACON: repeat count 1000000000");
  deck("deck unclosed group", " &NAM NITER=5,\n", "extra:");
  deck("deck unknown variable", " &NAM XYZZY=1 &END\n", "XYZZY");
  deck("deck NSWTCH beyond an integer (fuzzer finding: undefined cast)",
       " &NAM\n NSWTCH=7.77778E9 &END\n",
       "extra:2: NSWTCH: expected an integer");
  deck("deck fractional NITER",
       " &NAM NITER=2.5 &END\n",
       "extra:1: NITER: expected an integer");
  deck("deck no group", "just a title\n", "no NAMELIST group");
  // Flags.
  auto flag = [&](const std::string& name,
                  const std::string& command,
                  const std::string& expected) {
    v.push_back({name, c, d, "", command, expected});
  };
  flag("unknown command", "frobnicate DIR/config.yaml", "frobnicate");
  flag("flag of another command",
       "fit DIR/config.yaml --out_dir=DIR/out --resume",
       "--resume");
  flag("jobs for fit",
       "fit DIR/config.yaml --out_dir=DIR/out --jobs=2",
       "--jobs");
  flag("jobs below one",
       "batch DIR/config.yaml --out_dir=DIR/out --jobs=0",
       "--jobs");
  flag("jobs not a number",
       "batch DIR/config.yaml --out_dir=DIR/out --jobs=many",
       "--jobs");
  flag("basin starts zero", "basin DIR/config.yaml --starts=0", "--starts");
  flag("missing out_dir", "fit DIR/config.yaml", "--out_dir");
  flag("bad shard",
       "batch DIR/config.yaml --out_dir=DIR/out --shard=3/2",
       "--shard=3/2");
  flag("two configs",
       "fit DIR/config.yaml DIR/config.yaml --out_dir=DIR/out",
       "fit");
  v.push_back({"out is a directory",
               Edit(c, "solver:", "simulate: {dt: 0.06, samples: 10}\nsolver:"),
               d,
               "",
               "simulate DIR/config.yaml --out=DIR",
               "expected a file to write"});
  return v;
}

std::string Substitute(std::string text, const std::string& dir) {
  for (size_t at; (at = text.find("DIR")) != std::string::npos;) {
    text.replace(at, 3, dir);
  }
  return text;
}

TEST(BadInput, CatalogExitsTwoNamingTheProblemAndWritesNothing) {
  const std::vector<BadInput> catalog = Catalog();
  EXPECT_GE(catalog.size(), 60u);
  std::printf("%zu malformed inputs\n", catalog.size());
  int index = 0;
  for (const BadInput& bad : catalog) {
    const std::string dir =
        testing::ScratchDirectory("bad_input/" + std::to_string(index++));
    if (!bad.config.empty())
      testing::WriteText(dir + "/config.yaml", bad.config);
    if (!bad.data.empty()) testing::WriteText(dir + "/data.csv", bad.data);
    if (!bad.extra.empty()) testing::WriteText(dir + "/extra", bad.extra);
    const auto r = testing::RunFit3dof(Substitute(bad.command, dir));
    EXPECT_EQ(r.exit_status, 2) << bad.name << ": " << r.output;
    EXPECT_NE(r.output.find(bad.expected), std::string::npos)
        << bad.name << ": expected '" << bad.expected << "' in: " << r.output;
    EXPECT_EQ(r.output.rfind("fit3dof: ", 0), 0u)
        << bad.name << ": " << r.output;
    const bool empty = !fs::exists(dir + "/out") || fs::is_empty(dir + "/out");
    EXPECT_TRUE(empty) << bad.name << ": left files in " << dir << "/out";
  }
}

}  // namespace
}  // namespace fit3dof
