// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A Case written back as a config (CaseToYaml, config.h), through
// YAML::Emitter: names and paths are double-quoted strings whatever they
// hold, numbers are the shortest decimals that read back as the same
// doubles. config_writer_test checks load(write(c)) == c for every config
// in configs/.

#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "config_node.h"
#include "fit3dof/config.h"
#include "fit3dof/parameters.h"
#include "fit3dof/time_history.h"

namespace fit3dof {

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

namespace {

// DataSelection's "no limit" for t_start / t_end.
constexpr double kNoTimeLimit = 1e299;

void Number(YAML::Emitter& y, const char* key, double x) {
  y << YAML::Key << key << YAML::Value << ShortestNumber(x);
}

void Text(YAML::Emitter& y, const char* key, const std::string& text) {
  y << YAML::Key << key << YAML::Value << YAML::DoubleQuoted << text;
}

void Word(YAML::Emitter& y, const char* key, const std::string& word) {
  y << YAML::Key << key << YAML::Value << word;
}

void Flag(YAML::Emitter& y, const char* key, bool value) {
  Word(y, key, value ? "true" : "false");
}

void Channels(YAML::Emitter& y, const char* key, const ChannelValues& v) {
  y << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginMap;
  Number(y, "phi", v.phi);
  Number(y, "theta", v.theta);
  Number(y, "psi", v.psi);
  y << YAML::EndMap;
}

// A tied parameter (case.h) is written as its tie, its value following.
void Tie(YAML::Emitter& y,
         const std::string& name,
         const ParameterSetting& p,
         const std::string& source) {
  y << YAML::Key << name << YAML::Value << YAML::Flow << YAML::BeginMap;
  Word(y, "tied", source);
  Number(y, "factor", p.tie_factor);
  y << YAML::EndMap;
}

void Setting(YAML::Emitter& y,
             const std::string& name,
             const ParameterSetting& p) {
  y << YAML::Key << name << YAML::Value << YAML::Flow << YAML::BeginMap;
  if (p.auto_start) {
    Word(y, "value", "auto");
  } else {
    Number(y, "value", p.value);
  }
  Flag(y, "free", p.free);
  y << YAML::EndMap;
}

bool IsDefault(const ParameterSetting& p) {
  return p.value == 0.0 && !p.free && !p.auto_start && !p.tied();
}

void WriteModel(YAML::Emitter& y, const Case& c) {
  Text(y, "name", c.name);
  Word(y, "model", ModelName(c.model));
  Word(y, "incidence", IncidenceName(c.incidence));
  y << YAML::Key << "body" << YAML::Value << YAML::Flow << YAML::BeginMap;
  Number(y, "area", c.body.area);
  Number(y, "diameter", c.body.diameter);
  Number(y, "Ix", c.body.Ix);
  Number(y, "Iy", c.body.Iy);
  if (c.model == ModelKind::kAsymmetric) Number(y, "Iz", c.body.Iz);
  y << YAML::EndMap;
  y << YAML::Key << "flow" << YAML::Value << YAML::Flow << YAML::BeginMap;
  Number(y, "velocity", c.flow.velocity);
  Number(y, "dynamic_pressure", c.flow.dynamic_pressure);
  y << YAML::EndMap;
}

// The whole table, initial conditions included (they are the defaults the
// segments started from); parameters at zero and frozen are left out.
void WriteParameters(YAML::Emitter& y, const Case& c) {
  const auto& table = ParameterTable(c.model);
  y << YAML::Key << "parameters" << YAML::Value << YAML::BeginMap;
  for (int i = 0; i < NumParameters(c.model); ++i) {
    const ParameterSetting& p = c.parameters[i];
    if (p.tied()) {
      Tie(y, table[i].name, p, table[p.tied_to].name);
    } else if (!IsDefault(p)) {
      Setting(y, table[i].name, p);
    }
  }
  y << YAML::EndMap;
}

void WriteData(YAML::Emitter& y, const Segment& s) {
  const DataSelection& d = s.selection;
  y << YAML::Key << "data" << YAML::Value << YAML::BeginMap;
  Text(y, "file", s.data_file);
  y << YAML::Key << "start" << YAML::Value << d.start;
  Number(y, "fraction", d.fraction);
  y << YAML::Key << "every" << YAML::Value << d.every;
  if (d.t_start > -kNoTimeLimit) Number(y, "t_start", d.t_start);
  if (d.t_end < kNoTimeLimit) Number(y, "t_end", d.t_end);
  Word(y, "outliers", OutlierPolicyName(s.outliers));
  y << YAML::EndMap;
}

void WriteSegments(YAML::Emitter& y, const Case& c) {
  const auto& table = ParameterTable(c.model);
  const int first = Layout(c.model).first_initial;
  y << YAML::Key << "segments" << YAML::Value << YAML::BeginSeq;
  for (const Segment& s : c.segments) {
    y << YAML::BeginMap;
    Text(y, "name", s.name);
    WriteData(y, s);
    Word(y,
         "initial_conditions",
         s.initial_conditions == InitialConditionMode::kFromData ? "from_data"
                                                                 : "given");
    y << YAML::Key << "parameters" << YAML::Value << YAML::BeginMap;
    for (int j = 0; j < 6; ++j) Setting(y, table[first + j].name, s.initial[j]);
    y << YAML::EndMap << YAML::EndMap;
  }
  y << YAML::EndSeq;
}

// sigma: auto channels are written as auto (their starting weight is the
// default 1 deg the reader gives them).
void WriteSigma(YAML::Emitter& y, const Case& c) {
  y << YAML::Key << "sigma" << YAML::Value << YAML::Flow << YAML::BeginMap;
  for (int ch = 0; ch < 3; ++ch) {
    if (c.sigma_auto[ch]) {
      Word(y, ChannelName(ch), "auto");
    } else {
      Number(y, ChannelName(ch), c.sigma[ch]);
    }
  }
  y << YAML::EndMap;
}

void WriteOptions(YAML::Emitter& y, const Case& c) {
  WriteSigma(y, c);
  const NoiseOptions& n = c.noise;
  if (!(n == NoiseOptions{})) {
    y << YAML::Key << "noise" << YAML::Value << YAML::BeginMap;
    Flag(y, "enabled", n.enabled);
    Channels(y, "sigma", n.sigma);
    Channels(y, "bias", n.bias);
    y << YAML::Key << "seed" << YAML::Value << n.seed;
    y << YAML::EndMap;
  }
  const SolverOptions& s = c.solver;
  y << YAML::Key << "solver" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "max_iterations" << YAML::Value << s.max_iterations;
  Number(y, "tolerance", s.tolerance);
  Number(y, "step", s.step);
  Flag(y, "continuation", s.continuation);
  Word(y, "method", FitMethodToString(s.method));
  Number(y, "max_probable_error", s.max_probable_error);
  Flag(y, "multi_start", s.multi_start);
  y << YAML::Key << "starts" << YAML::Value << s.starts;
  y << YAML::EndMap;
  const ProcessNoiseModel& noise = c.process_noise;
  if (noise.enabled()) {
    y << YAML::Key << "process_noise" << YAML::Value << YAML::Flow
      << YAML::BeginMap;
    const char* const axes[3] = {"roll", "pitch", "yaw"};
    for (int axis = 0; axis < 3; ++axis) {
      if (noise.estimated[axis]) {
        Word(y, axes[axis], "auto");
      } else if (noise.intensity[axis] > 0.0) {
        Number(y, axes[axis], noise.intensity[axis]);
      }
    }
    y << YAML::EndMap;
  }
  const SimulateOptions& m = c.simulate;
  if (m.dt > 0.0) {
    y << YAML::Key << "simulate" << YAML::Value << YAML::Flow << YAML::BeginMap;
    Number(y, "dt", m.dt);
    if (m.samples > 0) {
      y << YAML::Key << "samples" << YAML::Value << m.samples;
    } else {
      Number(y, "duration", m.duration);
    }
    const ProcessNoiseOptions& p = m.process_noise;
    if (p.enabled()) {
      y << YAML::Key << "process_noise" << YAML::Value << YAML::BeginMap;
      Number(y, "roll", p.rms[0]);
      Number(y, "pitch", p.rms[1]);
      Number(y, "yaw", p.rms[2]);
      Number(y, "correlation_time", p.correlation_time);
      y << YAML::Key << "seed" << YAML::Value << p.seed;
      y << YAML::EndMap;
    }
    y << YAML::EndMap;
  }
}

}  // namespace

std::string CaseToYaml(const Case& c) {
  YAML::Emitter y;
  y << YAML::BeginMap;
  WriteModel(y, c);
  WriteParameters(y, c);
  if (!c.segments.empty()) WriteSegments(y, c);
  WriteOptions(y, c);
  y << YAML::EndMap;
  return std::string(y.c_str()) + "\n";
}

}  // namespace fit3dof
