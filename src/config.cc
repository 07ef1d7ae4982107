// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// YAML config loading with strict validation: unknown keys are errors (a
// misspelt key silently ignored is a wrong fit), every number must be finite,
// and every message carries file, line and key.

#include "fit3dof/config.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "config_node.h"
#include "fit3dof/input_error.h"

namespace fit3dof {
namespace {

namespace fs = std::filesystem;

class ConfigReader {
 public:
  ConfigReader(std::string source,
               std::string base_dir,
               bool node_lines,
               const KeyLines* key_lines = nullptr,
               std::string label = "")
      : source_(std::move(source)),
        base_dir_(std::move(base_dir)),
        node_lines_(node_lines),
        key_lines_(key_lines),
        label_(std::move(label)) {}

  Case Read(const YAML::Node& root);

 private:
  [[noreturn]] void Fail(const YAML::Node& node,
                         const std::string& key,
                         const std::string& message) const {
    std::ostringstream out;
    const std::string line = KeyLine(key);
    if (!line.empty()) {
      out << line;
      if (!label_.empty()) out << ": " << label_;
    } else {
      out << source_;
      if (node_lines_ && node.IsDefined() && node.Mark().line >= 0) {
        out << ":" << node.Mark().line + 1;
      }
    }
    out << ": " << key << ": " << message;
    throw InputError(out.str());
  }

  // "file:line" of `key` or of its nearest parent in key_lines_; empty
  // when there are no key lines or none matches.
  std::string KeyLine(std::string key) const {
    if (key_lines_ == nullptr) return "";
    while (!key.empty()) {
      const auto found = key_lines_->find(key);
      if (found != key_lines_->end()) return found->second;
      const size_t cut = key.find_last_of(".[");
      key = cut == std::string::npos ? "" : key.substr(0, cut);
    }
    return "";
  }

  void CheckKeys(const YAML::Node& node,
                 const std::string& path,
                 const std::set<std::string>& allowed) const {
    if (!node.IsMap()) Fail(node, path, "expected a mapping of keys");
    for (const auto& item : node) {
      const std::string key = item.first.as<std::string>();
      if (allowed.count(key) == 0) {
        std::string list;
        for (const std::string& a : allowed)
          list += (list.empty() ? "" : ", ") + a;
        Fail(item.first,
             Join(path, key),
             "unknown key (expected one of: " + list + ")");
      }
    }
  }

  static std::string Join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  double Number(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) Fail(node, key, "expected a number");
    double value = 0.0;
    try {
      value = node.as<double>();
    } catch (const YAML::Exception&) {
      Fail(node, key, "expected a number, got '" + node.Scalar() + "'");
    }
    if (!std::isfinite(value)) {
      Fail(node, key, "expected a finite number, got '" + node.Scalar() + "'");
    }
    return value;
  }

  double Positive(const YAML::Node& node, const std::string& key) const {
    const double value = Number(node, key);
    if (!(value > 0.0))
      Fail(node, key, "must be positive, got " + node.Scalar());
    return value;
  }

  double NonNegative(const YAML::Node& node, const std::string& key) const {
    const double value = Number(node, key);
    if (value < 0.0)
      Fail(node, key, "must not be negative, got " + node.Scalar());
    return value;
  }

  // An integer in [min, max]; the default max fits an int.
  long Integer(const YAML::Node& node,
               const std::string& key,
               long min,
               long max = std::numeric_limits<int>::max()) const {
    const double value = Number(node, key);
    if (value != std::floor(value) || value < min || value > max) {
      Fail(node,
           key,
           "expected an integer from " + std::to_string(min) + " to " +
               std::to_string(max) + ", got " + node.Scalar());
    }
    return static_cast<long>(value);
  }

  bool Bool(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) Fail(node, key, "expected true or false");
    try {
      return node.as<bool>();
    } catch (const YAML::Exception&) {
      Fail(node, key, "expected true or false, got '" + node.Scalar() + "'");
    }
  }

  std::string String(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) Fail(node, key, "expected a string");
    return node.Scalar();
  }

  const YAML::Node Required(const YAML::Node& parent,
                            const std::string& path,
                            const std::string& key) const {
    const YAML::Node node = parent[key];
    if (!node.IsDefined() || node.IsNull()) {
      Fail(parent, Join(path, key), "missing (required)");
    }
    return node;
  }

  void ReadBody(const YAML::Node& node, Case* c) const;
  void ReadFlow(const YAML::Node& node, Case* c) const;
  void ReadParameters(const YAML::Node& node, Case* c) const;
  // value_optional: initial conditions, which from_data can supply.
  ParameterSetting ReadParameter(const YAML::Node& node,
                                 const std::string& key,
                                 bool value_optional) const;
  ChannelValues ReadChannels(const YAML::Node& node,
                             const std::string& path,
                             bool all_required,
                             double fallback) const;
  void ReadData(const YAML::Node& node,
                const std::string& path,
                Segment* s) const;
  InitialConditionMode ReadInitialConditions(const YAML::Node& node,
                                             const std::string& key) const;
  void ReadSegments(const YAML::Node& root, Case* c) const;
  void ReadNoise(const YAML::Node& node, Case* c) const;
  void ReadSolver(const YAML::Node& node, Case* c) const;
  void ReadSimulate(const YAML::Node& node, Case* c) const;
  void CheckPhysics(const YAML::Node& root, const Case& c) const;

  std::string source_;
  std::string base_dir_;
  bool node_lines_;  // false for merged trees, whose nodes lost their lines
  const KeyLines* key_lines_;  // for merged trees: where each key came from
  std::string label_;          // "run 'x'", after a key's line
};

Case ConfigReader::Read(const YAML::Node& root) {
  if (!root.IsMap()) Fail(root, "(top level)", "expected a mapping of keys");
  CheckKeys(root,
            "",
            {"name",
             "model",
             "incidence",
             "body",
             "flow",
             "parameters",
             "initial_conditions",
             "data",
             "segments",
             "sigma",
             "noise",
             "solver",
             "simulate"});
  Case c;
  c.source = source_;
  c.name = fs::path(source_).stem().string();
  if (root["name"]) c.name = String(root["name"], "name");

  const std::string model = String(Required(root, "", "model"), "model");
  if (model == "symmetric") {
    c.model = ModelKind::kSymmetric;
  } else if (model == "asymmetric") {
    c.model = ModelKind::kAsymmetric;
  } else {
    Fail(root["model"],
         "model",
         "expected 'symmetric' or 'asymmetric', got '" + model + "'");
  }
  if (root["incidence"]) {
    const std::string incidence = String(root["incidence"], "incidence");
    if (incidence == "velocity_ratio") {
      c.incidence = Incidence::kVelocityRatio;
    } else if (incidence == "angle_of_attack") {
      c.incidence = Incidence::kAngleOfAttack;
    } else {
      Fail(root["incidence"],
           "incidence",
           "expected 'velocity_ratio' (IANGLE = 0) or 'angle_of_attack' "
           "(IANGLE != 0), got '" +
               incidence + "'");
    }
  }
  ReadBody(Required(root, "", "body"), &c);
  ReadFlow(Required(root, "", "flow"), &c);
  c.parameters.assign(NumParameters(c.model), ParameterSetting{});
  if (root["parameters"] && !root["parameters"].IsNull()) {
    ReadParameters(root["parameters"], &c);
  }
  if (root["sigma"]) {
    c.sigma = ReadChannels(root["sigma"], "sigma", true, 1.0);
    if (!(c.sigma.phi > 0 && c.sigma.theta > 0 && c.sigma.psi > 0)) {
      Fail(root["sigma"], "sigma", "every sigma must be positive (deg)");
    }
  }
  ReadSegments(root, &c);
  if (root["noise"]) ReadNoise(root["noise"], &c);
  if (root["solver"]) ReadSolver(root["solver"], &c);
  if (root["simulate"]) ReadSimulate(root["simulate"], &c);
  CheckPhysics(root, c);
  return c;
}

void ConfigReader::ReadBody(const YAML::Node& node, Case* c) const {
  const bool asymmetric = c->model == ModelKind::kAsymmetric;
  CheckKeys(node, "body", {"area", "diameter", "Ix", "Iy", "Iz", "Izx"});
  if (node["Izx"]) {
    Fail(node["Izx"],
         "body.Izx",
         "the product of inertia is parameter 60 of the asymmetric model "
         "(fittable): give it under parameters");
  }
  c->body.area = Positive(Required(node, "body", "area"), "body.area");
  c->body.diameter =
      Positive(Required(node, "body", "diameter"), "body.diameter");
  c->body.Ix = Positive(Required(node, "body", "Ix"), "body.Ix");
  c->body.Iy = Positive(Required(node, "body", "Iy"), "body.Iy");
  if (asymmetric) {
    c->body.Iz = Positive(Required(node, "body", "Iz"), "body.Iz");
  } else {
    c->body.Iz = c->body.Iy;
    if (node["Iz"]) {
      const double iz = Positive(node["Iz"], "body.Iz");
      if (std::abs(iz - c->body.Iy) > 1e-12 * c->body.Iy) {
        Fail(node["Iz"],
             "body.Iz",
             "the symmetric model needs Iy = Iz (one transverse inertia I); "
             "use model: asymmetric for Iy != Iz");
      }
    }
  }
  const Body& b = c->body;
  // Principal moments of a rigid body obey the triangle inequality.
  if (b.Ix > b.Iy + b.Iz || b.Iy > b.Ix + b.Iz || b.Iz > b.Ix + b.Iy) {
    Fail(node,
         "body",
         "Ix, Iy, Iz cannot be the moments of inertia of a rigid body (each "
         "must not exceed the sum of the other two)");
  }
}

void ConfigReader::ReadFlow(const YAML::Node& node, Case* c) const {
  CheckKeys(node, "flow", {"velocity", "dynamic_pressure", "density"});
  c->flow.velocity =
      Positive(Required(node, "flow", "velocity"), "flow.velocity");
  const bool has_q = node["dynamic_pressure"].IsDefined();
  const bool has_rho = node["density"].IsDefined();
  if (has_q == has_rho) {
    Fail(node,
         "flow",
         "give exactly one of dynamic_pressure (lbf/ft^2) or density "
         "(slug/ft^3)");
  }
  if (has_q) {
    c->flow.dynamic_pressure =
        Positive(node["dynamic_pressure"], "flow.dynamic_pressure");
  } else {
    const double rho = Positive(node["density"], "flow.density");
    c->flow.dynamic_pressure = 0.5 * rho * c->flow.velocity * c->flow.velocity;
  }
}

ParameterSetting ConfigReader::ReadParameter(const YAML::Node& node,
                                             const std::string& key,
                                             bool value_optional) const {
  ParameterSetting setting;
  if (node.IsScalar()) {
    setting.value = Number(node, key);
    return setting;
  }
  CheckKeys(node, key, {"value", "free", "start"});
  if (node["free"]) setting.free = Bool(node["free"], key + ".free");
  const bool auto_value = node["value"] && node["value"].IsScalar() &&
                          node["value"].Scalar() == "auto";
  if (node["start"]) {
    if (String(node["start"], key + ".start") != "auto") {
      Fail(node["start"], key + ".start", "expected 'auto' (or give value:)");
    }
    if (node["value"] && !auto_value) {
      Fail(node["start"], key + ".start", "give either value: or start: auto");
    }
  }
  if (auto_value || node["start"] || (!node["value"] && setting.free)) {
    if (!setting.free) {
      if (value_optional) return setting;
      Fail(node,
           key,
           "a frozen parameter needs a value (auto starting values are for "
           "free parameters)");
    }
    setting.auto_start = true;
    return setting;
  }
  if (node["value"]) {
    setting.value = Number(node["value"], key + ".value");
  } else if (!setting.free && !value_optional) {
    Fail(node, key, "a frozen parameter needs a value");
  }
  return setting;
}

void ConfigReader::ReadParameters(const YAML::Node& node, Case* c) const {
  if (!node.IsMap()) Fail(node, "parameters", "expected a mapping of names");
  const auto& table = ParameterTable(c->model);
  std::set<int> seen;
  for (const auto& item : node) {
    const std::string name = item.first.as<std::string>();
    const std::string key = "parameters." + name;
    const int position = FindParameter(c->model, name);
    if (position < 0) {
      std::string message = std::string("unknown parameter of the ") +
                            ModelName(c->model) + " model";
      const std::string hint = SuggestParameter(c->model, name);
      if (!hint.empty()) {
        message += " (did you mean " + hint + "?)";
      } else if (c->model == ModelKind::kSymmetric &&
                 FindParameter(ModelKind::kAsymmetric, name) >= 0) {
        message += " (it belongs to the asymmetric model)";
      }
      Fail(item.first, key, message);
    }
    if (!seen.insert(position).second) {
      Fail(item.first,
           key,
           "given twice (" + table[position].name + " has an alias)");
    }
    const ParameterSetting setting =
        ReadParameter(item.second, key, IsInitialCondition(c->model, position));
    if (table[position].scaling == Scaling::kUnused &&
        (setting.value != 0.0 || setting.free)) {
      Fail(item.first, key, "is a spare slot that no equation uses");
    }
    c->parameters[position] = setting;
  }
}

ChannelValues ConfigReader::ReadChannels(const YAML::Node& node,
                                         const std::string& path,
                                         bool all_required,
                                         double fallback) const {
  CheckKeys(node, path, {"phi", "theta", "psi"});
  ChannelValues v{fallback, fallback, fallback};
  auto read = [&](const char* channel, double* out) {
    const YAML::Node n = node[channel];
    if (!n.IsDefined()) {
      if (all_required) Fail(node, Join(path, channel), "missing (required)");
      return;
    }
    *out = Number(n, Join(path, channel));
  };
  read("phi", &v.phi);
  read("theta", &v.theta);
  read("psi", &v.psi);
  return v;
}

void ConfigReader::ReadData(const YAML::Node& node,
                            const std::string& path,
                            Segment* s) const {
  CheckKeys(
      node,
      path,
      {"file", "start", "fraction", "every", "t_start", "t_end", "outliers"});
  const std::string file =
      String(Required(node, path, "file"), Join(path, "file"));
  const fs::path p(file);
  s->data_file = p.is_absolute() ? file : (fs::path(base_dir_) / p).string();
  if (node["start"]) {
    s->selection.start =
        static_cast<int>(Integer(node["start"], Join(path, "start"), 1));
  }
  if (node["fraction"]) {
    const double f = Number(node["fraction"], Join(path, "fraction"));
    if (!(f > 0.0 && f <= 1.0)) {
      Fail(node["fraction"],
           Join(path, "fraction"),
           "must be in (0, 1], got " + node["fraction"].Scalar());
    }
    s->selection.fraction = f;
  }
  if (node["every"]) {
    s->selection.every =
        static_cast<int>(Integer(node["every"], Join(path, "every"), 1));
  }
  if (node["t_start"]) {
    s->selection.t_start = Number(node["t_start"], Join(path, "t_start"));
  }
  if (node["t_end"]) {
    s->selection.t_end = Number(node["t_end"], Join(path, "t_end"));
  }
  if (s->selection.t_end <= s->selection.t_start) {
    Fail(node, path, "t_end must be later than t_start");
  }
  if (node["outliers"]) {
    const std::string policy = String(node["outliers"], Join(path, "outliers"));
    if (!ParseOutlierPolicy(policy, &s->outliers)) {
      Fail(node["outliers"],
           Join(path, "outliers"),
           "expected 'warn' (name wild points, keep them) or 'reject' (name "
           "them and fit without them), got '" +
               policy + "'");
    }
  }
}

InitialConditionMode ConfigReader::ReadInitialConditions(
    const YAML::Node& node, const std::string& key) const {
  const std::string value = String(node, key);
  if (value == "from_data") return InitialConditionMode::kFromData;
  if (value == "given") return InitialConditionMode::kGiven;
  Fail(node,
       key,
       "expected 'from_data' (INLCON = 0) or 'given' (INLCON != 0), got '" +
           value + "'");
}

void ConfigReader::ReadSegments(const YAML::Node& root, Case* c) const {
  InitialConditionMode mode = InitialConditionMode::kFromData;
  if (root["initial_conditions"]) {
    mode =
        ReadInitialConditions(root["initial_conditions"], "initial_conditions");
  }
  const int first = Layout(c->model).first_initial;
  Segment defaults;
  defaults.initial_conditions = mode;
  for (int j = 0; j < 6; ++j) defaults.initial[j] = c->parameters[first + j];

  const YAML::Node data = root["data"];
  const YAML::Node segments = root["segments"];
  if (data.IsDefined() && segments.IsDefined()) {
    Fail(segments,
         "segments",
         "give either data (one segment) or segments (several), not both");
  }
  if (data.IsDefined()) {
    Segment s = defaults;
    s.name = c->name;
    ReadData(data, "data", &s);
    c->segments.push_back(s);
    return;
  }
  if (!segments.IsDefined()) return;
  if (!segments.IsSequence() || segments.size() == 0) {
    Fail(segments, "segments", "expected a non-empty list of data segments");
  }
  const auto& table = ParameterTable(c->model);
  std::set<std::string> names;
  for (size_t i = 0; i < segments.size(); ++i) {
    const YAML::Node node = segments[i];
    const std::string path = "segments[" + std::to_string(i) + "]";
    CheckKeys(node, path, {"name", "data", "initial_conditions", "parameters"});
    Segment s = defaults;
    s.name = "segment" + std::to_string(i + 1);
    if (node["name"]) s.name = String(node["name"], Join(path, "name"));
    if (!names.insert(s.name).second) {
      Fail(node,
           Join(path, "name"),
           "segment name '" + s.name + "' is used twice");
    }
    ReadData(Required(node, path, "data"), Join(path, "data"), &s);
    if (node["initial_conditions"]) {
      s.initial_conditions = ReadInitialConditions(
          node["initial_conditions"], Join(path, "initial_conditions"));
    }
    const YAML::Node params = node["parameters"];
    if (params.IsDefined() && !params.IsNull()) {
      if (!params.IsMap()) {
        Fail(params, Join(path, "parameters"), "expected a mapping of names");
      }
      for (const auto& item : params) {
        const std::string name = item.first.as<std::string>();
        const std::string key = Join(path, "parameters." + name);
        const int position = FindParameter(c->model, name);
        if (position < 0 || !IsInitialCondition(c->model, position)) {
          std::string allowed;
          for (int j = 0; j < 6; ++j) {
            allowed += (j ? ", " : "") + table[first + j].name;
          }
          Fail(item.first,
               key,
               "a segment sets only its own initial conditions (" + allowed +
                   "); aerodynamic parameters are shared and go under the "
                   "top-level parameters");
        }
        s.initial[position - first] = ReadParameter(item.second, key, true);
      }
    }
    c->segments.push_back(s);
  }
}

void ConfigReader::ReadNoise(const YAML::Node& node, Case* c) const {
  CheckKeys(node, "noise", {"enabled", "sigma", "bias", "seed"});
  c->noise.enabled = true;
  if (node["enabled"])
    c->noise.enabled = Bool(node["enabled"], "noise.enabled");
  if (node["sigma"]) {
    c->noise.sigma = ReadChannels(node["sigma"], "noise.sigma", false, 0.0);
    const ChannelValues& s = c->noise.sigma;
    if (s.phi < 0 || s.theta < 0 || s.psi < 0) {
      Fail(node["sigma"], "noise.sigma", "noise levels must not be negative");
    }
  }
  if (node["bias"]) {
    c->noise.bias = ReadChannels(node["bias"], "noise.bias", false, 0.0);
  }
  if (node["seed"]) {
    // Seeds up to 2^53: every one is exact in the YAML number.
    c->noise.seed = static_cast<std::uint64_t>(
        Integer(node["seed"], "noise.seed", 0, 1L << 53));
  }
}

void ConfigReader::ReadSolver(const YAML::Node& node, Case* c) const {
  CheckKeys(node,
            "solver",
            {"max_iterations",
             "tolerance",
             "step",
             "continuation",
             "method",
             "max_probable_error",
             "multi_start",
             "starts"});
  if (node["method"]) {
    c->solver.method = String(node["method"], "solver.method");
    if (c->solver.method != "levenberg_marquardt" &&
        c->solver.method != "gauss_newton") {
      Fail(node["method"],
           "solver.method",
           "expected levenberg_marquardt or gauss_newton, got '" +
               c->solver.method + "'");
    }
  }
  if (node["max_probable_error"]) {
    c->solver.max_probable_error =
        NonNegative(node["max_probable_error"], "solver.max_probable_error");
  }
  if (node["multi_start"]) {
    c->solver.multi_start = Bool(node["multi_start"], "solver.multi_start");
  }
  if (node["starts"]) {
    c->solver.starts =
        static_cast<int>(Integer(node["starts"], "solver.starts", 0, 1000));
  }
  if (node["continuation"]) {
    c->solver.continuation = Bool(node["continuation"], "solver.continuation");
  }
  if (node["max_iterations"]) {
    c->solver.max_iterations = static_cast<int>(
        Integer(node["max_iterations"], "solver.max_iterations", 1, 1000000));
  }
  if (node["tolerance"]) {
    c->solver.tolerance = Positive(node["tolerance"], "solver.tolerance");
  }
  if (node["step"]) c->solver.step = Positive(node["step"], "solver.step");
}

void ConfigReader::ReadSimulate(const YAML::Node& node, Case* c) const {
  CheckKeys(node, "simulate", {"duration", "dt", "samples"});
  c->simulate.dt = Positive(Required(node, "simulate", "dt"), "simulate.dt");
  const bool has_duration = node["duration"].IsDefined();
  const bool has_samples = node["samples"].IsDefined();
  if (has_duration == has_samples) {
    Fail(node,
         "simulate",
         "give exactly one of duration (s) or samples (count, t = 0 included)");
  }
  if (has_duration) {
    c->simulate.duration = Positive(node["duration"], "simulate.duration");
    const double samples = c->simulate.duration / c->simulate.dt + 1.0;
    if (!(samples <= 1e8)) {
      Fail(node["duration"],
           "simulate.duration",
           "duration / dt gives " + ShortestNumber(std::floor(samples)) +
               " samples; at most 1e8 (is dt in seconds?)");
    }
  } else {
    c->simulate.samples = static_cast<int>(
        Integer(node["samples"], "simulate.samples", 2, 100000000));
  }
}

void ConfigReader::CheckPhysics(const YAML::Node& root, const Case& c) const {
  const int izx = Layout(c.model).product_of_inertia;
  if (izx >= 0) {
    const double v = c.parameters[izx].value;
    if (v * v >= c.body.Ix * c.body.Iz) {
      Fail(root["parameters"],
           "parameters.Izx",
           "|Izx| must be below sqrt(Ix Iz) for a positive-definite inertia");
    }
  }
}

}  // namespace

int SimulateOptions::NumSamples() const {
  if (samples > 0) return samples;
  if (dt <= 0.0) return 0;
  return static_cast<int>(std::floor(duration / dt + 1e-9)) + 1;
}

ModelSpec Case::Spec() const {
  ModelSpec spec;
  spec.model = model;
  spec.incidence = incidence;
  spec.body = body;
  spec.flow = flow;
  spec.max_step = solver.step;
  return spec;
}

std::vector<double> Case::Values() const {
  std::vector<double> values(parameters.size());
  for (size_t i = 0; i < parameters.size(); ++i)
    values[i] = parameters[i].value;
  return values;
}

std::vector<bool> Case::FreeFlags() const {
  std::vector<bool> free(parameters.size());
  for (size_t i = 0; i < parameters.size(); ++i) free[i] = parameters[i].free;
  return free;
}

std::string ShortestNumber(double x) {
  char out[40];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(out, sizeof(out), "%.*g", digits, x);
    if (std::strtod(out, nullptr) == x) break;
  }
  std::string text = out;
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
}

Case ParseConfigNode(const YAML::Node& root,
                     const std::string& source,
                     const std::string& base_dir,
                     bool node_lines,
                     const KeyLines* key_lines,
                     const std::string& label) {
  if (!root.IsDefined() || root.IsNull()) {
    throw InputError(source + ": the config is empty");
  }
  return ConfigReader(source, base_dir, node_lines, key_lines, label)
      .Read(root);
}

void RecordKeyLines(const YAML::Node& node,
                    const std::string& file,
                    const std::string& prefix,
                    KeyLines* lines) {
  auto at = [&](const YAML::Node& n) {
    return file + ":" + std::to_string(n.Mark().line + 1);
  };
  if (node.IsMap()) {
    for (const auto& item : node) {
      if (!item.first.IsScalar()) continue;
      const std::string path = prefix.empty()
                                   ? item.first.Scalar()
                                   : prefix + "." + item.first.Scalar();
      if (item.first.Mark().line >= 0) (*lines)[path] = at(item.first);
      RecordKeyLines(item.second, file, path, lines);
    }
  } else if (node.IsSequence()) {
    for (size_t i = 0; i < node.size(); ++i) {
      const std::string path = prefix + "[" + std::to_string(i) + "]";
      if (node[i].Mark().line >= 0) (*lines)[path] = at(node[i]);
      RecordKeyLines(node[i], file, path, lines);
    }
  }
}

namespace {

// Length of the valid UTF-8 sequence at `s` (0 if invalid): no overlong
// forms, no surrogates, nothing above U+10FFFF.
int Utf8Length(const unsigned char* s, size_t left) {
  const unsigned char c = s[0];
  if (c < 0x80) return 1;
  int n = 0;
  unsigned min = 0;
  unsigned code = 0;
  if ((c & 0xE0) == 0xC0) {
    n = 2, min = 0x80, code = c & 0x1F;
  } else if ((c & 0xF0) == 0xE0) {
    n = 3, min = 0x800, code = c & 0x0F;
  } else if ((c & 0xF8) == 0xF0) {
    n = 4, min = 0x10000, code = c & 0x07;
  } else {
    return 0;
  }
  if (left < static_cast<size_t>(n)) return 0;
  for (int i = 1; i < n; ++i) {
    if ((s[i] & 0xC0) != 0x80) return 0;
    code = (code << 6) | (s[i] & 0x3F);
  }
  if (code < min || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) {
    return 0;
  }
  return n;
}

// Checks what yaml-cpp lets through: a key given twice in one mapping (the
// first would silently win), a key that is not a plain scalar, and text
// that is not UTF-8 (it would reach report.json).
void CheckStrict(const YAML::Node& node, const std::string& source) {
  auto fail = [&](const YAML::Node& at, const std::string& message) {
    throw InputError(source + ":" + std::to_string(at.Mark().line + 1) + ": " +
                     message);
  };
  if (node.IsScalar()) {
    if (!IsValidUtf8(node.Scalar())) {
      fail(node, "the text is not valid UTF-8");
    }
  } else if (node.IsSequence()) {
    for (const YAML::Node& item : node) CheckStrict(item, source);
  } else if (node.IsMap()) {
    std::map<std::string, int> seen;
    for (const auto& item : node) {
      if (!item.first.IsScalar()) {
        fail(item.first,
             "a key must be a plain name (complex keys are not "
             "allowed)");
      }
      CheckStrict(item.first, source);
      const std::string key = item.first.Scalar();
      const auto [at, fresh] = seen.emplace(key, item.first.Mark().line + 1);
      if (!fresh) {
        fail(item.first,
             key + ": given twice in one mapping (first at line " +
                 std::to_string(at->second) + ")");
      }
      CheckStrict(item.second, source);
    }
  }
}

}  // namespace

bool IsValidUtf8(const std::string& text) {
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  for (size_t i = 0; i < text.size();) {
    const int n = Utf8Length(s + i, text.size() - i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

// YAML text is Unicode without control characters other than tab, line
// feed and carriage return. Checked before yaml-cpp sees the text: a NUL
// byte in a comment sends its parser into a loop that never ends (found by
// tests/fuzz/config_fuzzer.cc).
void CheckYamlCharacters(const std::string& text, const std::string& source) {
  int line = 1;
  for (const char ch : text) {
    const auto byte = static_cast<unsigned char>(ch);
    if (byte == '\n') ++line;
    if ((byte < 0x20 && byte != '\t' && byte != '\n' && byte != '\r') ||
        byte == 0x7f) {
      char code[8];
      std::snprintf(code, sizeof(code), "0x%02x", byte);
      throw InputError(source + ":" + std::to_string(line) +
                       ": a control character (" + code +
                       ") where YAML allows only text");
    }
  }
  const auto* bytes = reinterpret_cast<const unsigned char*>(text.data());
  line = 1;
  for (size_t i = 0; i < text.size();) {
    const int n = Utf8Length(bytes + i, text.size() - i);
    if (n == 0) {
      throw InputError(source + ":" + std::to_string(line) +
                       ": the text is not valid UTF-8");
    }
    if (bytes[i] == '\n') ++line;
    i += n;
  }
}

namespace {

// Sees whether a document has any content, and where it starts.
class DocumentProbe : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark& mark) override { start = mark; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override { content = true; }
  void OnScalar(const YAML::Mark&,
                const std::string&,
                YAML::anchor_t,
                const std::string&) override {
    content = true;
  }
  void OnSequenceStart(const YAML::Mark&,
                       const std::string&,
                       YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    content = true;
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&,
                  const std::string&,
                  YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    content = true;
  }
  void OnMapEnd() override {}

  YAML::Mark start;
  bool content = false;
};

}  // namespace

YAML::Node ParseYamlText(const std::string& text, const std::string& source) {
  CheckYamlCharacters(text, source);
  // Not YAML::LoadAll: in yaml-cpp 0.7 it loops for ever, allocating, on
  // some malformed text (a lone ',' is one; yaml-cpp issue 1040, fixed
  // upstream in 0.8). One document is loaded; a second one with content is
  // looked for by parsing at most one more.
  YAML::Node root;
  try {
    root = YAML::Load(text);
    std::istringstream in(text);
    YAML::Parser parser(in);
    DocumentProbe first, second;
    if (parser.HandleNextDocument(first) && parser.HandleNextDocument(second) &&
        second.content) {
      throw InputError(source + ":" + std::to_string(second.start.line + 1) +
                       ": a second YAML document ('---'); a config or "
                       "manifest is one document");
    }
  } catch (const YAML::Exception& e) {
    throw InputError(source + ":" + std::to_string(e.mark.line + 1) +
                     ": not valid YAML: " + e.msg);
  }
  if (!root.IsDefined() || root.IsNull()) return root;
  CheckStrict(root, source);
  return root;
}

YAML::Node LoadYamlFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the file");
  std::stringstream text;
  text << in.rdbuf();
  return ParseYamlText(text.str(), path);
}

void ResolveDataPaths(const std::string& base_dir, YAML::Node* node) {
  if (!node->IsMap()) return;
  auto resolve = [&](YAML::Node data) {
    if (!data.IsMap() || !data["file"] || !data["file"].IsScalar()) return;
    const fs::path file(data["file"].Scalar());
    if (!file.is_absolute()) {
      data["file"] =
          fs::absolute(fs::path(base_dir) / file).lexically_normal().string();
    }
  };
  resolve((*node)["data"]);
  YAML::Node segments = (*node)["segments"];
  if (segments.IsSequence()) {
    for (size_t i = 0; i < segments.size(); ++i) resolve(segments[i]["data"]);
  }
}

YAML::Node MergeYaml(const YAML::Node& base, const YAML::Node& overrides) {
  if (!base.IsDefined() || !base.IsMap() || !overrides.IsMap()) {
    return YAML::Clone(overrides);
  }
  // Built afresh (reading base and overrides only through const handles):
  // YAML::Node assignment writes through to shared nodes.
  YAML::Node out(YAML::NodeType::Map);
  for (const auto& item : base) {
    const std::string key = item.first.Scalar();
    const YAML::Node over = static_cast<const YAML::Node&>(overrides)[key];
    out[key] = over.IsDefined() ? MergeYaml(item.second, over)
                                : YAML::Clone(item.second);
  }
  for (const auto& item : overrides) {
    const std::string key = item.first.Scalar();
    if (!static_cast<const YAML::Node&>(base)[key].IsDefined()) {
      out[key] = YAML::Clone(item.second);
    }
  }
  return out;
}

Case ParseConfig(const std::string& text,
                 const std::string& source,
                 const std::string& base_dir) {
  return ParseConfigNode(ParseYamlText(text, source), source, base_dir);
}

Case LoadConfig(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the config file");
  std::stringstream text;
  text << in.rdbuf();
  const fs::path parent = fs::path(path).parent_path();
  return ParseConfig(text.str(), path, parent.empty() ? "." : parent.string());
}

}  // namespace fit3dof

namespace fit3dof {
namespace {

std::string Setting(const ParameterSetting& p) {
  if (p.auto_start) return "{value: auto, free: true}";
  return "{value: " + ShortestNumber(p.value) +
         ", free: " + (p.free ? "true" : "false") + "}";
}

}  // namespace

std::string CaseToYaml(const Case& c) {
  std::ostringstream y;
  y << "name: " << c.name << "\nmodel: " << ModelName(c.model)
    << "\nincidence: " << IncidenceName(c.incidence) << "\n";
  y << "body: {area: " << ShortestNumber(c.body.area)
    << ", diameter: " << ShortestNumber(c.body.diameter)
    << ", Ix: " << ShortestNumber(c.body.Ix)
    << ", Iy: " << ShortestNumber(c.body.Iy);
  if (c.model == ModelKind::kAsymmetric)
    y << ", Iz: " << ShortestNumber(c.body.Iz);
  y << "}\nflow: {velocity: " << ShortestNumber(c.flow.velocity)
    << ", dynamic_pressure: " << ShortestNumber(c.flow.dynamic_pressure)
    << "}\n";
  y << "parameters:\n";
  const auto& table = ParameterTable(c.model);
  for (int i = 0; i < NumParameters(c.model); ++i) {
    const ParameterSetting& p = c.parameters[i];
    if (IsInitialCondition(c.model, i)) continue;  // per segment below
    if (p.value == 0.0 && !p.free && !p.auto_start) continue;
    y << "  " << table[i].name << ": " << Setting(p) << "\n";
  }
  y << "segments:\n";
  const int first = Layout(c.model).first_initial;
  for (const Segment& s : c.segments) {
    y << "  - name: " << s.name << "\n    data: {file: " << s.data_file
      << ", start: " << s.selection.start
      << ", fraction: " << ShortestNumber(s.selection.fraction)
      << ", every: " << s.selection.every;
    if (s.selection.t_start > -1e299)
      y << ", t_start: " << ShortestNumber(s.selection.t_start);
    if (s.selection.t_end < 1e299)
      y << ", t_end: " << ShortestNumber(s.selection.t_end);
    if (s.outliers != OutlierPolicy::kWarn)
      y << ", outliers: " << OutlierPolicyName(s.outliers);
    y << "}\n    initial_conditions: "
      << (s.initial_conditions == InitialConditionMode::kFromData ? "from_data"
                                                                  : "given")
      << "\n    parameters:\n";
    for (int j = 0; j < 6; ++j) {
      y << "      " << table[first + j].name << ": " << Setting(s.initial[j])
        << "\n";
    }
  }
  y << "sigma: {phi: " << ShortestNumber(c.sigma.phi)
    << ", theta: " << ShortestNumber(c.sigma.theta)
    << ", psi: " << ShortestNumber(c.sigma.psi) << "}\n";
  if (c.noise.enabled) {
    y << "noise:\n  sigma: {phi: " << ShortestNumber(c.noise.sigma.phi)
      << ", theta: " << ShortestNumber(c.noise.sigma.theta)
      << ", psi: " << ShortestNumber(c.noise.sigma.psi)
      << "}\n  bias: {phi: " << ShortestNumber(c.noise.bias.phi)
      << ", theta: " << ShortestNumber(c.noise.bias.theta)
      << ", psi: " << ShortestNumber(c.noise.bias.psi)
      << "}\n  seed: " << c.noise.seed << "\n";
  }
  y << "solver: {max_iterations: " << c.solver.max_iterations
    << ", tolerance: " << ShortestNumber(c.solver.tolerance)
    << ", step: " << ShortestNumber(c.solver.step)
    << ", continuation: " << (c.solver.continuation ? "true" : "false")
    << ", method: " << c.solver.method
    << ", max_probable_error: " << ShortestNumber(c.solver.max_probable_error)
    << ", multi_start: " << (c.solver.multi_start ? "true" : "false")
    << ", starts: " << c.solver.starts << "}\n";
  return y.str();
}

}  // namespace fit3dof
