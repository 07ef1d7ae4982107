// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The config reader: YAML tree -> validated Case. Strict: unknown keys are
// errors (a misspelt key silently ignored is a wrong fit), every number
// must be finite, and every message carries file, line and key. The YAML
// text checks live in config_node.cc, the writer in config_writer.cc.

#include "fit3dof/config.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "config_node.h"
#include "fit3dof/input_error.h"
#include "fit3dof/time_history.h"
#include "node_reader.h"

namespace fit3dof {
namespace {

namespace fs = std::filesystem;

class ConfigReader : public NodeReader {
 public:
  ConfigReader(std::string source,
               std::string base_dir,
               bool node_lines,
               const KeyLines* key_lines,
               std::string label)
      : NodeReader(std::move(source), node_lines, key_lines, std::move(label)),
        base_dir_(std::move(base_dir)) {}

  Case Read(const YAML::Node& root);

 private:
  void ReadBody(const YAML::Node& node, Case* c) const;
  void ReadFlow(const YAML::Node& node, Case* c) const;
  void ReadParameters(const YAML::Node& node, Case* c) const;
  // value_optional: initial conditions, which from_data can supply.
  ParameterSetting ReadParameter(const YAML::Node& node,
                                 const std::string& key,
                                 bool value_optional) const;
  // `{tied: <name>, factor: <number>}` for the parameter at `position`.
  ParameterSetting ReadTie(const YAML::Node& node,
                           const std::string& key,
                           int position,
                           const Case& c) const;
  // Every tie's source free or frozen but itself untied.
  void CheckTies(const YAML::Node& node, const Case& c) const;
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
  // sigma: {phi, theta, psi} in deg, any of them `auto`, or `sigma: auto`.
  void ReadSigma(const YAML::Node& node, Case* c) const;
  void ReadSolver(const YAML::Node& node, Case* c) const;
  void ReadSimulate(const YAML::Node& node, Case* c) const;
  void ReadProcessNoise(const YAML::Node& node, Case* c) const;
  void ReadFitProcessNoise(const YAML::Node& node, Case* c) const;
  void CheckProcessNoise(const YAML::Node& root, const Case& c) const;
  void CheckPhysics(const YAML::Node& root, const Case& c) const;

  std::string base_dir_;
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
             "process_noise",
             "simulate"});
  Case c;
  c.source = source();
  c.name = fs::path(source()).stem().string();
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
  if (root["sigma"]) ReadSigma(root["sigma"], &c);
  ReadSegments(root, &c);
  if (root["noise"]) ReadNoise(root["noise"], &c);
  if (root["solver"]) ReadSolver(root["solver"], &c);
  if (root["simulate"]) ReadSimulate(root["simulate"], &c);
  if (root["process_noise"]) ReadFitProcessNoise(root["process_noise"], &c);
  CheckProcessNoise(root, c);
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
        item.second.IsMap() && item.second["tied"]
            ? ReadTie(item.second, key, position, *c)
            : ReadParameter(
                  item.second, key, IsInitialCondition(c->model, position));
    if (table[position].scaling == Scaling::kUnused &&
        (setting.value != 0.0 || setting.free)) {
      Fail(item.first, key, "is a spare slot that no equation uses");
    }
    c->parameters[position] = setting;
  }
  CheckTies(node, *c);
  c->SettleTies();
}

ParameterSetting ConfigReader::ReadTie(const YAML::Node& node,
                                       const std::string& key,
                                       int position,
                                       const Case& c) const {
  CheckKeys(node, key, {"tied", "factor"});
  const auto& table = ParameterTable(c.model);
  const std::string source = String(node["tied"], key + ".tied");
  ParameterSetting setting;
  setting.tied_to = FindParameter(c.model, source);
  if (setting.tied_to < 0) {
    Fail(node["tied"],
         key + ".tied",
         "unknown parameter '" + source + "' of the " + ModelName(c.model) +
             " model");
  }
  if (IsInitialCondition(c.model, position) ||
      IsInitialCondition(c.model, setting.tied_to)) {
    Fail(node["tied"],
         key + ".tied",
         "initial conditions belong to each segment and cannot be tied");
  }
  if (setting.tied_to == position ||
      table[setting.tied_to].scaling == Scaling::kUnused) {
    Fail(node["tied"], key + ".tied", "expected another parameter in use");
  }
  if (node["factor"]) {
    setting.tie_factor = Number(node["factor"], key + ".factor");
  }
  return setting;
}

void ConfigReader::CheckTies(const YAML::Node& node, const Case& c) const {
  const auto& table = ParameterTable(c.model);
  for (const auto& item : node) {
    const std::string name = item.first.as<std::string>();
    const ParameterSetting& p = c.parameters[FindParameter(c.model, name)];
    if (!p.tied() || !c.parameters[p.tied_to].tied()) continue;
    Fail(item.second["tied"],
         "parameters." + name + ".tied",
         table[p.tied_to].name +
             " is itself tied; tie to the parameter it follows");
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

void ConfigReader::ReadSigma(const YAML::Node& node, Case* c) const {
  auto is_auto = [](const YAML::Node& n) {
    return n.IsDefined() && n.IsScalar() && n.Scalar() == "auto";
  };
  if (is_auto(node)) {
    c->sigma_auto = {{true, true, true}};
    return;
  }
  if (!node.IsMap()) {
    Fail(node, "sigma", "expected {phi, theta, psi} in deg, or auto");
  }
  CheckKeys(node, "sigma", {"phi", "theta", "psi"});
  for (int ch = 0; ch < 3; ++ch) {
    const YAML::Node n = node[ChannelName(ch)];
    const std::string key = Join("sigma", ChannelName(ch));
    if (!n.IsDefined()) Fail(node, key, "missing (required)");
    if (is_auto(n)) {
      c->sigma_auto[ch] = true;
      continue;
    }
    c->sigma[ch] = Number(n, key);
    if (!(c->sigma[ch] > 0.0)) {
      Fail(n, key, "must be positive (deg) or auto, got " + n.Scalar());
    }
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
    const std::string method = String(node["method"], "solver.method");
    if (!StringToFitMethod(method, &c->solver.method)) {
      Fail(node["method"],
           "solver.method",
           "expected levenberg_marquardt, gauss_newton or filter_error, got '" +
               method + "'");
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

void ConfigReader::ReadFitProcessNoise(const YAML::Node& node, Case* c) const {
  CheckKeys(node, "process_noise", {"roll", "pitch", "yaw"});
  ProcessNoiseModel& m = c->process_noise;
  const char* const axes[3] = {"roll", "pitch", "yaw"};
  for (int axis = 0; axis < 3; ++axis) {
    const YAML::Node v = node[axes[axis]];
    if (!v) continue;
    const std::string key = std::string("process_noise.") + axes[axis];
    if (v.IsScalar() && v.Scalar() == "auto") {
      m.estimated[axis] = true;
    } else {
      m.intensity[axis] = NonNegative(v, key);
    }
  }
}

void ConfigReader::CheckProcessNoise(const YAML::Node& root,
                                     const Case& c) const {
  const bool filter = c.solver.method == FitMethod::kFilterError;
  if (filter && !c.process_noise.enabled()) {
    Fail(root["solver"]["method"],
         "solver.method",
         "filter_error needs process_noise: {roll: auto, pitch: auto, yaw: "
         "auto} (auto or an intensity in deg/s^1.5 per axis)");
  }
  if (!filter && root["process_noise"]) {
    Fail(root["process_noise"],
         "process_noise",
         "used only by solver: {method: filter_error}");
  }
}

void ConfigReader::ReadProcessNoise(const YAML::Node& node, Case* c) const {
  const std::string key = "simulate.process_noise";
  CheckKeys(node, key, {"roll", "pitch", "yaw", "correlation_time", "seed"});
  ProcessNoiseOptions& p = c->simulate.process_noise;
  const char* const axes[3] = {"roll", "pitch", "yaw"};
  for (int axis = 0; axis < 3; ++axis) {
    if (node[axes[axis]]) {
      // The RMS of the random moment coefficient about that axis.
      p.rms[axis] = NonNegative(node[axes[axis]], key + "." + axes[axis]);
    }
  }
  if (node["correlation_time"]) {
    p.correlation_time =
        Positive(node["correlation_time"], key + ".correlation_time");
  }
  if (node["seed"]) {
    p.seed = static_cast<std::uint64_t>(
        Integer(node["seed"], key + ".seed", 0, 1L << 53));
  }
}

void ConfigReader::ReadSimulate(const YAML::Node& node, Case* c) const {
  CheckKeys(node, "simulate", {"duration", "dt", "samples", "process_noise"});
  if (node["process_noise"]) ReadProcessNoise(node["process_noise"], c);
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
  // The bearing moment fades beyond bearing_angle (bearing_moment.h): it
  // needs one, and there is no default to fall back on silently.
  const int bearing = Layout(c.model).bearing;
  const ParameterSetting& moment = c.parameters[bearing];
  const ParameterSetting& angle = c.parameters[bearing + 1];
  if ((moment.free || moment.value != 0.0) && !(angle.value > 0.0)) {
    Fail(root["parameters"],
         "parameters.bearing_angle",
         "Cm_bearing needs bearing_angle > 0 (deg), the angle where the "
         "bearing moment saturates");
  }
  if (angle.value < 0.0) {
    Fail(root["parameters"],
         "parameters.bearing_angle",
         "must be > 0 (deg), got " + ShortestNumber(angle.value));
  }
  // The signed square's line is taken over +-cal_range (parameters.h):
  // a negative range has no meaning, and diagnose would replace it.
  const ParameterSetting& range = c.parameters[Layout(c.model).cal_range];
  if (range.value < 0.0) {
    Fail(root["parameters"],
         "parameters.cal_range",
         "must be >= 0 (deg; 0 takes no line), got " +
             ShortestNumber(range.value));
  }
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
