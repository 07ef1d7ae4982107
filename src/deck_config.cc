// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The NAMELIST /NAM/ variables of both listings (Tables 1 and 2, Table 4)
// and the config keys they become:
//
//   NSWTCH             0: fit; 1 or 2: generate motion (simulate:)
//   NITER, BOUND       solver.max_iterations, solver.tolerance
//   DTMIN              solver.step
//   AREA, DIA          body.area, body.diameter
//   IX, IY, IZ         body.Ix, Iy, Iz
//   IZX                parameter Izx (AACON(60))
//   RO, U              flow.density, flow.velocity
//   AACON(i), NCON(i)  parameters: value, free
//   NSESWH             noise (seed 1: the 1978 program seeded RANDU from
//                      the clock)
//   SPHI, STHTA, SPSI  noise.sigma
//   AMPHI, AMTHTA, AMPSI  noise.bias
//   SAMPLE, NDELTA, NSTART  data.fraction, every, start
//   IUPDAT             the next group starts from this one (start_from)
//   INLCON             initial_conditions
//   IANGLE             incidence
//   DTGEN, NTOT        simulate.dt, simulate.samples (NSWTCH != 0)
//   SIGPHI, SIGTHA, SIGPSI  sigma
//   IGPNO, IBLKNO, IRCGEN, IRCSTR, NC, NTOT (NSWTCH = 0): accepted, ignored

#include "deck_config.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "config_node.h"
#include "fit3dof/input_error.h"
#include "fit3dof/parameters.h"

namespace fit3dof {
namespace {

// The deck's variables after some groups: scalars and 1-based arrays.
struct DeckState {
  std::map<std::string, DeckValue> scalars;
  std::map<std::string, std::map<int, DeckValue>> arrays;
  std::map<std::string, int> line;  // where each was last set

  bool Has(const std::string& name) const { return scalars.count(name) > 0; }
  double Number(const std::string& name, double fallback) const {
    const auto it = scalars.find(name);
    if (it == scalars.end()) return fallback;
    if (it->second.kind == DeckValue::kLogical)
      return it->second.logical ? 1 : 0;
    return it->second.number;
  }
};

const std::set<std::string>& ScalarVariables() {
  static const std::set<std::string> names = {
      "NSWTCH", "NTOT",  "NC",     "NITER",  "DTMIN",  "BOUND",  "AREA",
      "DIA",    "IX",    "IY",     "IZ",     "IZX",    "RO",     "U",
      "NSESWH", "SPHI",  "STHTA",  "STHA",   "SPSI",   "AMPHI",  "AMTHTA",
      "AMTHA",  "AMPSI", "SAMPLE", "NDELTA", "IUPDAT", "INLCON", "IANGLE",
      "DTGEN",  "IGPNO", "IBLKNO", "IRCGEN", "SIGPHI", "SIGTHA", "SIGPSI",
      "NSTART", "IRCSTR"};
  return names;
}

const std::set<std::string>& IgnoredVariables() {
  static const std::set<std::string> names = {
      "IGPNO", "IBLKNO", "IRCGEN", "IRCSTR", "NC"};
  return names;
}

void Apply(const std::string& source,
           const DeckAssignment& a,
           DeckState* state) {
  const std::string where = source + ":" + std::to_string(a.line) + ": ";
  if (a.variable == "AACON" || a.variable == "NCON") {
    const int first = a.index > 0 ? a.index : 1;
    for (size_t i = 0; i < a.values.size(); ++i) {
      const DeckValue& v = a.values[i];
      if (v.kind == DeckValue::kNull) continue;
      if (v.kind != DeckValue::kNumber) {
        throw InputError(where + a.variable + ": expected numbers");
      }
      const int index = first + static_cast<int>(i);
      // The report's lists only: the extensions have no NAMELIST index.
      if (index > kReportParameters[1]) {
        throw InputError(
            where + a.variable + "(" + std::to_string(index) +
            "): beyond the 72 parameters of the asymmetric program");
      }
      state->arrays[a.variable][index] = v;
    }
    state->line[a.variable] = a.line;
    return;
  }
  if (ScalarVariables().count(a.variable) == 0) {
    throw InputError(
        where + a.variable +
        ": not a variable of the report's NAMELIST /NAM/ (Table 4)");
  }
  if (a.index > 1 || a.values.size() != 1) {
    throw InputError(where + a.variable + ": expected a single value");
  }
  if (a.values[0].kind == DeckValue::kString) {
    throw InputError(where + a.variable + ": expected a number");
  }
  // The listing's integer variables (Fortran's I-N rule; IX, IY, IZ, IZX
  // are declared real) hold whole numbers an INTEGER can: anything else is
  // refused here, where the line is known, before it is cast.
  static const std::set<std::string> kIntegers = {"NSWTCH",
                                                  "NTOT",
                                                  "NC",
                                                  "NITER",
                                                  "NSESWH",
                                                  "NDELTA",
                                                  "NSTART",
                                                  "IUPDAT",
                                                  "INLCON",
                                                  "IANGLE",
                                                  "IGPNO",
                                                  "IBLKNO",
                                                  "IRCGEN",
                                                  "IRCSTR"};
  const DeckValue& v = a.values[0];
  if (kIntegers.count(a.variable) > 0 && v.kind == DeckValue::kNumber &&
      !(v.number == std::floor(v.number) &&
        std::abs(v.number) <= 2147483647.0)) {
    throw InputError(where + a.variable +
                     ": expected an integer from -2147483647 to 2147483647");
  }
  state->scalars[a.variable] = v;
  state->line[a.variable] = a.line;
}

YAML::Node FlowMap() {
  YAML::Node node(YAML::NodeType::Map);
  node.SetStyle(YAML::EmitterStyle::Flow);
  return node;
}

YAML::Node Channels(double phi, double theta, double psi) {
  YAML::Node node = FlowMap();
  node["phi"] = ShortestNumber(phi);
  node["theta"] = ShortestNumber(theta);
  node["psi"] = ShortestNumber(psi);
  return node;
}

// Everything one group's config is made from.
class GroupConverter {
 public:
  GroupConverter(const Deck& deck, const DeckState& state, int group)
      : state_(state),
        where_(deck.source + " group " + std::to_string(group)) {}

  YAML::Node Convert(const std::string& name,
                     const std::string& data_file,
                     std::vector<std::string>* ignored) const;

 private:
  double Require(const char* variable, const char* key) const {
    if (!state_.Has(variable)) {
      throw InputError(where_ + ": " + variable + " (" + key +
                       ") is not set in this group or an earlier one");
    }
    return state_.Number(variable, 0.0);
  }
  const std::map<int, DeckValue>* Array(const char* name) const {
    const auto it = state_.arrays.find(name);
    return it == state_.arrays.end() ? nullptr : &it->second;
  }
  ModelKind Model() const;
  YAML::Node Parameters(ModelKind model,
                        std::vector<std::string>* ignored) const;
  void Options(YAML::Node* y, std::vector<std::string>* ignored) const;

  const DeckState& state_;
  std::string where_;
};

ModelKind GroupConverter::Model() const {
  int largest = 0;
  for (const char* name : {"AACON", "NCON"}) {
    const auto* array = Array(name);
    if (array != nullptr && !array->empty()) {
      largest = std::max(largest, array->rbegin()->first);
    }
  }
  const bool asymmetric = state_.Number("NC", 0) == 72 || state_.Has("IZ") ||
                          state_.Has("IZX") || largest > 30;
  const ModelKind model =
      asymmetric ? ModelKind::kAsymmetric : ModelKind::kSymmetric;
  if (largest > NumParameters(model)) {
    throw InputError(where_ + ": AACON/NCON index " + std::to_string(largest) +
                     " is beyond the " + std::to_string(NumParameters(model)) +
                     " parameters of the " + ModelName(model) + " program");
  }
  return model;
}

YAML::Node GroupConverter::Parameters(ModelKind model,
                                      std::vector<std::string>* ignored) const {
  const auto* aacon = Array("AACON");
  const auto* ncon = Array("NCON");
  const auto& table = ParameterTable(model);
  YAML::Node parameters(YAML::NodeType::Map);
  for (int i = 1; i <= NumParameters(model); ++i) {
    double value = 0.0;
    bool free = false;
    if (aacon != nullptr && aacon->count(i)) value = aacon->at(i).number;
    if (ncon != nullptr && ncon->count(i)) free = ncon->at(i).number != 0.0;
    if (model == ModelKind::kAsymmetric && i == 60 && state_.Has("IZX")) {
      value = state_.Number("IZX", 0);
    }
    const ParameterInfo& info = table[i - 1];
    if (info.scaling == Scaling::kUnused) {
      if (value != 0.0 || free) {
        ignored->push_back("AACON(" + std::to_string(i) + ") (spare slot " +
                           info.name + ")");
      }
      continue;
    }
    if (value == 0.0 && !free) continue;
    YAML::Node setting = FlowMap();
    setting["value"] = ShortestNumber(value);
    setting["free"] = free;
    parameters[info.name] = setting;
  }
  return parameters;
}

void GroupConverter::Options(YAML::Node* y,
                             std::vector<std::string>* ignored) const {
  const DeckState& s = state_;
  if (s.Has("SIGPHI") || s.Has("SIGTHA") || s.Has("SIGPSI")) {
    (*y)["sigma"] = Channels(s.Number("SIGPHI", 1.0),
                             s.Number("SIGTHA", 1.0),
                             s.Number("SIGPSI", 1.0));
  }
  if (s.Number("NSESWH", 0) == 1) {
    // STHA and AMTHA: the spellings of the asymmetric listing.
    const double stheta =
        s.Has("STHTA") ? s.Number("STHTA", 0) : s.Number("STHA", 0);
    const double btheta =
        s.Has("AMTHTA") ? s.Number("AMTHTA", 0) : s.Number("AMTHA", 0);
    YAML::Node noise(YAML::NodeType::Map);
    noise["sigma"] = Channels(s.Number("SPHI", 0), stheta, s.Number("SPSI", 0));
    noise["bias"] =
        Channels(s.Number("AMPHI", 0), btheta, s.Number("AMPSI", 0));
    noise["seed"] = 1;
    (*y)["noise"] = noise;
  }
  YAML::Node solver(YAML::NodeType::Map);
  if (s.Has("NITER")) {
    solver["max_iterations"] = static_cast<long>(s.Number("NITER", 50));
  }
  if (s.Has("BOUND"))
    solver["tolerance"] = ShortestNumber(s.Number("BOUND", 0));
  if (s.Has("DTMIN")) solver["step"] = ShortestNumber(s.Number("DTMIN", 0));
  if (solver.size() > 0) (*y)["solver"] = solver;
  if (s.Number("NSWTCH", 0) != 0) {
    YAML::Node simulate(YAML::NodeType::Map);
    simulate["dt"] = ShortestNumber(Require("DTGEN", "simulate.dt"));
    simulate["samples"] =
        static_cast<long>(Require("NTOT", "simulate.samples"));
    (*y)["simulate"] = simulate;
  } else if (s.Has("NTOT")) {
    ignored->push_back("NTOT (array size; the data file sets the samples)");
  }
}

YAML::Node GroupConverter::Convert(const std::string& name,
                                   const std::string& data_file,
                                   std::vector<std::string>* ignored) const {
  const DeckState& s = state_;
  const ModelKind model = Model();
  YAML::Node y(YAML::NodeType::Map);
  y["name"] = name;
  y["model"] = ModelName(model);
  y["incidence"] =
      s.Number("IANGLE", 0) == 0 ? "velocity_ratio" : "angle_of_attack";
  YAML::Node body(YAML::NodeType::Map);
  body["area"] = ShortestNumber(Require("AREA", "body.area"));
  body["diameter"] = ShortestNumber(Require("DIA", "body.diameter"));
  body["Ix"] = ShortestNumber(Require("IX", "body.Ix"));
  body["Iy"] = ShortestNumber(Require("IY", "body.Iy"));
  if (model == ModelKind::kAsymmetric) {
    body["Iz"] = ShortestNumber(Require("IZ", "body.Iz"));
  }
  y["body"] = body;
  YAML::Node flow(YAML::NodeType::Map);
  flow["velocity"] = ShortestNumber(Require("U", "flow.velocity"));
  flow["density"] = ShortestNumber(Require("RO", "flow.density"));
  y["flow"] = flow;
  y["parameters"] = Parameters(model, ignored);
  y["initial_conditions"] = s.Number("INLCON", 0) == 0 ? "from_data" : "given";
  if (s.Number("NSWTCH", 0) == 0 && !data_file.empty()) {
    YAML::Node data(YAML::NodeType::Map);
    data["file"] = data_file;
    data["start"] = static_cast<long>(s.Number("NSTART", 1));
    data["fraction"] = ShortestNumber(s.Number("SAMPLE", 1.0));
    data["every"] = static_cast<long>(s.Number("NDELTA", 1));
    y["data"] = data;
  }
  Options(&y, ignored);
  for (const std::string& v : IgnoredVariables()) {
    if (s.Has(v)) ignored->push_back(v);
  }
  return y;
}

// Emits `node` as YAML: the values of name, file and start_from keys
// double-quoted (a deck or record called "null" or "a: b" stays a
// string), parameters with their AACON index as a comment.
void Emit(YAML::Emitter& y,
          const YAML::Node& node,
          ModelKind model,
          const std::string& key) {
  if (node.IsScalar()) {
    if (key == "name" || key == "file" || key == "start_from") {
      y << YAML::DoubleQuoted;
    }
    y << node.Scalar();
    return;
  }
  if (node.Style() == YAML::EmitterStyle::Flow) y << YAML::Flow;
  if (node.IsSequence()) {
    y << YAML::BeginSeq;
    for (const YAML::Node& item : node) Emit(y, item, model, "");
    y << YAML::EndSeq;
    return;
  }
  y << YAML::BeginMap;
  for (const auto& item : node) {
    const std::string name = item.first.Scalar();
    y << YAML::Key << name << YAML::Value;
    Emit(y, item.second, model, name);
    if (key == "parameters") {
      y << YAML::Comment("AACON(" +
                         std::to_string(FindParameter(model, name) + 1) + ")");
    }
  }
  y << YAML::EndMap;
}

std::string Header(const Deck& deck, int group) {
  std::string text = "converted from " + deck.source + ", NAMELIST group " +
                     std::to_string(group);
  if (!deck.titles.empty()) text += " (" + deck.titles.front() + ")";
  return text;
}

ModelKind ModelOf(const DeckConfig& config) {
  return config.config["model"].Scalar() == "asymmetric"
             ? ModelKind::kAsymmetric
             : ModelKind::kSymmetric;
}

std::string Ignored(const DeckConfig& config) {
  std::string list = "group " + std::to_string(config.run.group) +
                     ", ignored (no meaning today):";
  for (const std::string& v : config.run.ignored) list += " " + v + ";";
  return list;
}

}  // namespace

std::vector<DeckConfig> DeckConfigs(const Deck& deck,
                                    const std::string& data_file) {
  const std::string stem = std::filesystem::path(deck.source).stem().string();
  std::vector<DeckConfig> configs;
  DeckState state;
  bool update_next = false;
  for (size_t g = 0; g < deck.groups.size(); ++g) {
    const DeckGroup& group = deck.groups[g];
    if (group.name != "NAM") {
      throw InputError(deck.source + ":" + std::to_string(group.line) + ": &" +
                       group.name + ": the programs read NAMELIST /NAM/ only");
    }
    for (const DeckAssignment& a : group.assignments) {
      Apply(deck.source, a, &state);
    }
    DeckConfig config;
    DeckRun& run = config.run;
    run.group = static_cast<int>(g) + 1;
    run.name =
        deck.groups.size() == 1 ? stem : stem + "-" + std::to_string(run.group);
    if (update_next && !configs.empty()) {
      run.start_from = configs.back().run.name;
    }
    config.config = GroupConverter(deck, state, run.group)
                        .Convert(run.name, data_file, &run.ignored);
    update_next = state.Number("IUPDAT", 0) == 1;
    configs.push_back(config);
  }
  return configs;
}

std::string DeckConfigYaml(const Deck& deck, const DeckConfig& config) {
  YAML::Emitter y;
  y << YAML::Comment(Header(deck, config.run.group)) << YAML::Newline;
  Emit(y, config.config, ModelOf(config), "");
  if (!config.run.ignored.empty())
    y << YAML::Newline << YAML::Comment(Ignored(config));
  return std::string(y.c_str()) + "\n";
}

std::string DeckYaml(const Deck& deck, const std::vector<DeckConfig>& configs) {
  if (configs.size() == 1) return DeckConfigYaml(deck, configs[0]);
  YAML::Emitter y;
  y << YAML::Comment("converted from " + deck.source + ": " +
                     std::to_string(configs.size()) +
                     " NAMELIST groups, one run each (start_from: IUPDAT = 1)");
  for (const DeckConfig& config : configs) {
    if (!config.run.ignored.empty()) {
      y << YAML::Newline << YAML::Comment(Ignored(config));
    }
  }
  y << YAML::Newline;
  y << YAML::BeginMap << YAML::Key << "runs" << YAML::Value << YAML::BeginSeq;
  for (const DeckConfig& config : configs) {
    YAML::Node run = YAML::Clone(config.config);
    if (!config.run.start_from.empty())
      run["start_from"] = config.run.start_from;
    Emit(y, run, ModelOf(config), "");
  }
  y << YAML::EndSeq << YAML::EndMap;
  return std::string(y.c_str()) + "\n";
}

}  // namespace fit3dof
