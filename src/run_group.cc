// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Runs of a batch fitted together (run_group.h).

#include "run_group.h"

#include <set>
#include <string>
#include <vector>

#include "config_node.h"
#include "fit3dof/input_error.h"
#include "fit3dof/parameters.h"

namespace fit3dof {
namespace {

// The names of the six initial-condition parameters of the config's model,
// in the table's order.
std::vector<std::string> InitialConditionNames(const YAML::Node& config) {
  const YAML::Node model = config["model"];
  const bool asymmetric = model.IsDefined() && model.IsScalar() &&
                          model.Scalar() == ModelName(ModelKind::kAsymmetric);
  const ModelKind kind =
      asymmetric ? ModelKind::kAsymmetric : ModelKind::kSymmetric;
  const std::vector<ParameterInfo>& table = ParameterTable(kind);
  std::vector<std::string> names;
  for (int j = 0; j < 6; ++j) {
    names.push_back(table[Layout(kind).first_initial + j].name);
  }
  return names;
}

// A run's config without what is its own: its name, its records and its
// initial conditions.
YAML::Node SharedPart(const YAML::Node& config) {
  YAML::Node shared = YAML::Clone(config);
  for (const char* key : {"name", "data", "segments", "initial_conditions"}) {
    shared.remove(key);
  }
  YAML::Node parameters = shared["parameters"];
  if (parameters.IsDefined() && parameters.IsMap()) {
    for (const std::string& name : InitialConditionNames(config)) {
      parameters.remove(name);
    }
  }
  return shared;
}

// The run's initial-condition parameters as its config gives them.
YAML::Node OwnInitialConditions(const YAML::Node& config) {
  YAML::Node own(YAML::NodeType::Map);
  const YAML::Node parameters = config["parameters"];
  if (!parameters.IsDefined() || !parameters.IsMap()) return own;
  for (const std::string& name : InitialConditionNames(config)) {
    if (parameters[name].IsDefined()) {
      own[name] = YAML::Clone(parameters[name]);
    }
  }
  return own;
}

// The first key (dotted into mappings) whose values differ between the
// mappings `a` and `b`; empty when they are equal.
std::string FirstDifference(const YAML::Node& a, const YAML::Node& b) {
  std::set<std::string> keys;
  for (const auto& item : a) keys.insert(item.first.Scalar());
  for (const auto& item : b) keys.insert(item.first.Scalar());
  for (const std::string& key : keys) {
    const YAML::Node x = a[key];
    const YAML::Node y = b[key];
    if (x.IsDefined() != y.IsDefined()) return key;
    if (YAML::Dump(x) == YAML::Dump(y)) continue;
    if (x.IsMap() && y.IsMap()) {
      // The same keys in another order are equal.
      const std::string inner = FirstDifference(x, y);
      if (inner.empty()) continue;
      return key + "." + inner;
    }
    return key;
  }
  return "";
}

// Appends one segment per record of run `m` to `segments`, each with the
// run's initial conditions (a segment's own over them); false when the run
// has no record.
bool AppendRecords(const RunSpec& m, YAML::Node* segments) {
  const YAML::Node& c = m.config;
  const YAML::Node initial = OwnInitialConditions(c);
  auto segment = [&](const std::string& name, const YAML::Node& from) {
    YAML::Node s = YAML::Clone(from);
    s["name"] = name;
    if (!s["initial_conditions"] && c["initial_conditions"]) {
      s["initial_conditions"] = YAML::Clone(c["initial_conditions"]);
    }
    YAML::Node parameters = YAML::Clone(initial);
    if (s["parameters"]) parameters.reset(MergeYaml(initial, s["parameters"]));
    if (parameters.size() > 0) s["parameters"] = parameters;
    segments->push_back(s);
  };
  if (c["data"]) {
    YAML::Node record(YAML::NodeType::Map);
    record["data"] = YAML::Clone(c["data"]);
    segment(m.name, record);
    return true;
  }
  const YAML::Node list = c["segments"];
  if (!list.IsDefined() || !list.IsSequence() || list.size() == 0) {
    return false;
  }
  for (size_t i = 0; i < list.size(); ++i) {
    if (!list[i].IsMap()) {
      segments->push_back(YAML::Clone(list[i]));  // the config reader says
      continue;
    }
    const std::string own = list[i]["name"] ? list[i]["name"].Scalar()
                                            : "segment" + std::to_string(i + 1);
    segment(m.name + "." + own, list[i]);
  }
  return true;
}

// The together run `g`'s config from its runs `members` and its own keys.
void Join(const std::vector<const RunSpec*>& members,
          const YAML::Node& own,
          RunSpec* g) {
  const YAML::Node shared = SharedPart(members[0]->config);
  YAML::Node segments(YAML::NodeType::Sequence);
  std::string problem;
  for (const RunSpec* m : members) {
    const std::string key = FirstDifference(shared, SharedPart(m->config));
    if (problem.empty() && !key.empty()) {
      problem = "runs '" + members[0]->name + "' and '" + m->name +
                "' differ in " + key +
                " (one model is fitted to all their records: they may "
                "differ only in their data and initial conditions)";
    }
    if (!AppendRecords(*m, &segments) && problem.empty()) {
      problem = "run '" + m->name + "' has no data";
    }
  }
  if (!problem.empty()) g->load_error = g->source + ": together: " + problem;
  YAML::Node config;
  config.reset(MergeYaml(shared, own));
  config["name"] = g->name;
  config["segments"] = segments;
  g->config.reset(config);
}

}  // namespace

void JoinRuns(const std::string& path,
              const std::map<std::string, YAML::Node>& own,
              std::vector<RunSpec>* specs) {
  std::map<std::string, const RunSpec*> by_name;
  for (const RunSpec& s : *specs) by_name.emplace(s.name, &s);
  for (RunSpec& g : *specs) {
    if (g.together.empty()) continue;
    const std::string where = g.source + ": together: ";
    std::vector<const RunSpec*> members;
    std::set<std::string> seen;
    for (const std::string& name : g.together) {
      const auto it = by_name.find(name);
      if (it == by_name.end() || name == g.name) {
        throw InputError(where + "no other run named '" + name + "' in " +
                         path);
      }
      if (!it->second->together.empty()) {
        throw InputError(where + "run '" + name +
                         "' is a together run itself; name its runs");
      }
      if (!seen.insert(name).second) {
        throw InputError(where + "run '" + name + "' is named twice");
      }
      members.push_back(it->second);
    }
    const auto mine = own.find(g.name);
    Join(members,
         mine == own.end() ? YAML::Node(YAML::NodeType::Map) : mine->second,
         &g);
  }
}

}  // namespace fit3dof
