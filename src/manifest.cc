// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A batch manifest turned into runs (manifest.h): YAML manifests with
// defaults and start_from chains, directories of configs, decks.

#include "manifest.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include "config_node.h"
#include "deck_config.h"
#include "fit3dof/input_error.h"
#include "fit3dof/namelist.h"
#include "run_group.h"

namespace fit3dof {
namespace {

namespace fs = std::filesystem;

std::string Emit(const YAML::Node& node) {
  YAML::Emitter out;
  out << node;
  return out.c_str();
}

std::string Where(const std::string& path, const YAML::Node& node) {
  return node.Mark().line >= 0
             ? path + ":" + std::to_string(node.Mark().line + 1)
             : path;
}

// The run names of a manifest entry's together: (run_group.h).
std::vector<std::string> Together(const std::string& where,
                                  const YAML::Node& entry) {
  const YAML::Node list = entry["together"];
  if (!list.IsSequence()) {
    throw InputError(where + ": together: expected a list of run names");
  }
  std::vector<std::string> names;
  for (const YAML::Node& name : list) {
    if (!name.IsScalar()) {
      throw InputError(where + ": together: expected a list of run names");
    }
    names.push_back(name.Scalar());
  }
  if (names.size() < 2) {
    throw InputError(where + ": together: expected two or more runs");
  }
  // Its records and starting values are its runs'.
  for (const char* key : {"config", "data", "segments", "start_from"}) {
    if (entry[key]) {
      throw InputError(where + ": " + key +
                       ": a together run takes its records and starting "
                       "values from the runs it names; give " +
                       key + " to them");
    }
  }
  return names;
}

// Runs from a YAML manifest with runs: (and defaults:).
std::vector<RunSpec> FromManifest(const std::string& path,
                                  const YAML::Node& root) {
  const std::string dir = fs::path(path).parent_path().string();
  const std::string base = dir.empty() ? "." : dir;
  for (const auto& item : root) {
    const std::string key = item.first.Scalar();
    if (key != "defaults" && key != "runs") {
      throw InputError(Where(path, item.first) + ": " + key +
                       ": unknown key of a manifest (expected defaults and "
                       "runs)");
    }
  }
  YAML::Node defaults = YAML::Clone(root["defaults"]);
  if (defaults.IsDefined() && !defaults.IsNull()) {
    if (!defaults.IsMap()) {
      throw InputError(Where(path, root["defaults"]) +
                       ": defaults: expected a mapping of config keys");
    }
    ResolveDataPaths(base, &defaults);
  } else {
    defaults = YAML::Node(YAML::NodeType::Map);
  }
  const YAML::Node runs = root["runs"];
  if (!runs.IsSequence() || runs.size() == 0) {
    throw InputError(Where(path, root) + ": runs: expected a non-empty list");
  }
  std::vector<RunSpec> specs;
  std::map<std::string, YAML::Node> own;  // the together runs' own keys
  for (size_t i = 0; i < runs.size(); ++i) {
    const YAML::Node entry = runs[i];
    const std::string where =
        Where(path, entry) + ": runs[" + std::to_string(i) + "]";
    if (!entry.IsMap()) throw InputError(where + ": expected a mapping");
    RunSpec spec;
    if (entry["together"]) spec.together = Together(where, entry);
    spec.base_dir = base;
    // Note: assigning one YAML::Node to another writes through to the node
    // the left side refers to; reset() rebinds the handle instead.
    YAML::Node merged = YAML::Clone(defaults);
    RecordKeyLines(defaults, path, "", &spec.key_lines);
    if (entry["config"]) {
      const fs::path file = fs::path(base) / entry["config"].Scalar();
      YAML::Node config = LoadYamlFile(file.string());
      if (!config.IsMap()) {
        throw InputError(file.string() + ": expected a config (a mapping)");
      }
      ResolveDataPaths(file.parent_path().string(), &config);
      RecordKeyLines(config, file.string(), "", &spec.key_lines);
      merged.reset(MergeYaml(merged, config));
      spec.name =
          config["name"] ? config["name"].Scalar() : file.stem().string();
    }
    RecordKeyLines(entry, path, "", &spec.key_lines);
    YAML::Node overrides = YAML::Clone(entry);
    overrides.remove("config");
    if (overrides["start_from"]) {
      if (!overrides["start_from"].IsScalar()) {
        throw InputError(where + ": start_from: expected the name of a run");
      }
      spec.start_from = overrides["start_from"].Scalar();
      overrides.remove("start_from");
    }
    if (overrides["diagnose"]) {
      try {
        spec.diagnose = overrides["diagnose"].as<bool>();
      } catch (const YAML::Exception&) {
        throw InputError(where + ": diagnose: expected true or false");
      }
      overrides.remove("diagnose");
    }
    overrides.remove("together");
    ResolveDataPaths(base, &overrides);
    merged.reset(MergeYaml(merged, overrides));
    if (merged["name"]) spec.name = merged["name"].Scalar();
    if (spec.name.empty()) {
      throw InputError(where + ": a run needs a name (or a config: file)");
    }
    merged["name"] = spec.name;
    spec.config = merged;
    spec.node_lines = false;
    spec.label = "run '" + spec.name + "'";
    spec.source = Where(path, entry) + ": " + spec.label;
    if (!spec.together.empty()) own[spec.name] = overrides;
    specs.push_back(spec);
  }
  JoinRuns(path, own, &specs);
  return specs;
}

std::vector<RunSpec> FromDirectory(const std::string& path) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(path)) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file() && (ext == ".yaml" || ext == ".yml")) {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    throw InputError(path + ": the directory holds no .yaml configs");
  }
  std::vector<RunSpec> specs;
  for (const fs::path& file : files) {
    RunSpec spec;
    spec.base_dir = file.parent_path().string();
    YAML::Node config(YAML::NodeType::Map);
    try {
      config.reset(LoadYamlFile(file.string()));
    } catch (const InputError& e) {
      // A broken file fails its own run, named after the file.
      spec.load_error = e.what();
    }
    if (config.IsMap()) ResolveDataPaths(spec.base_dir, &config);
    spec.name = config.IsMap() && config["name"] && config["name"].IsScalar()
                    ? config["name"].Scalar()
                    : file.stem().string();
    if (config.IsMap()) config["name"] = spec.name;
    spec.config = config;
    spec.source = file.string();
    specs.push_back(spec);
  }
  return specs;
}

// Chain roots, cycle check and hashes that cover each run's predecessors.
void Link(const std::string& path, std::vector<RunSpec>* specs) {
  std::map<std::string, RunSpec*> by_name;
  const std::regex safe("[A-Za-z0-9._+-]+");
  for (RunSpec& s : *specs) {
    if (!std::regex_match(s.name, safe) || s.name == "." || s.name == "..") {
      throw InputError(path + ": run name '" + s.name +
                       "' must use only letters, digits and . _ + - (it "
                       "names the run's output directory)");
    }
    if (s.name == "summary.csv" || s.name == "summary.json" ||
        s.name == kBatchLockName) {
      throw InputError(path + ": run name '" + s.name +
                       "' is the name of a file the batch writes into its "
                       "output directory; rename the run");
    }
    if (!by_name.emplace(s.name, &s).second) {
      throw InputError(path + ": run name '" + s.name + "' is used twice");
    }
  }
  for (RunSpec& s : *specs) {
    if (!s.start_from.empty() && by_name.count(s.start_from) == 0) {
      throw InputError(s.source + ": start_from: no run named '" +
                       s.start_from + "'");
    }
  }
  std::map<std::string, std::string> hashes;
  for (RunSpec& s : *specs) {
    std::vector<RunSpec*> chain;
    std::set<std::string> seen;
    RunSpec* current = &s;
    while (true) {
      if (!seen.insert(current->name).second) {
        throw InputError(s.source + ": start_from: the chain through '" +
                         current->name + "' is a cycle");
      }
      chain.push_back(current);
      if (current->start_from.empty()) break;
      current = by_name[current->start_from];
    }
    s.chain_root = chain.back()->name;
    std::string text;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      text += Emit((*it)->config) +
              "\n--- diagnose: " + ((*it)->diagnose ? "true" : "false") + "\n";
    }
    s.hash = StableHash(text);
  }
}

}  // namespace

namespace {

// 64-bit FNV-1a, continued from `h` over `size` bytes.
constexpr std::uint64_t kFnvOffset = 1469598103934665603ull;
std::uint64_t Fnv1a(const unsigned char* bytes, size_t size, std::uint64_t h) {
  for (size_t i = 0; i < size; ++i) {
    h ^= bytes[i];
    h *= 1099511628211ull;
  }
  return h;
}

std::string Hex(std::uint64_t h) {
  char out[17];
  std::snprintf(
      out, sizeof(out), "%016llx", static_cast<unsigned long long>(h));
  return out;
}

}  // namespace

std::string StableHash(const std::string& text) {
  return Hex(Fnv1a(reinterpret_cast<const unsigned char*>(text.data()),
                   text.size(),
                   kFnvOffset));
}

std::string FileHash(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return "unreadable";
  std::uint64_t h = kFnvOffset;
  std::vector<unsigned char> buffer(1 << 20);
  size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), file)) > 0) {
    h = Fnv1a(buffer.data(), n, h);
  }
  std::fclose(file);
  return Hex(h);
}

std::vector<std::string> DataFiles(const YAML::Node& config) {
  std::vector<std::string> files;
  // operator[] of a const node gives an invalid node for a missing key, on
  // which IsMap() throws: ask IsDefined() first.
  auto add = [&](const YAML::Node& data) {
    if (data.IsDefined() && data.IsMap() && data["file"].IsDefined() &&
        data["file"].IsScalar()) {
      files.push_back(data["file"].Scalar());
    }
  };
  if (!config.IsMap()) return files;
  add(config["data"]);
  const YAML::Node segments = config["segments"];
  if (segments.IsDefined() && segments.IsSequence()) {
    for (const YAML::Node& s : segments) {
      if (s.IsDefined() && s.IsMap()) add(s["data"]);
    }
  }
  return files;
}

std::vector<RunSpec> LoadManifest(const std::string& path,
                                  const std::string& deck_data) {
  std::vector<RunSpec> specs;
  if (fs::is_directory(path)) {
    specs = FromDirectory(path);
  } else if (!fs::exists(path)) {
    throw InputError(path + ": no such manifest, config, deck or directory");
  } else if (IsDeckFile(path)) {
    const Deck deck = ReadDeck(path);
    const std::string dir = fs::path(path).parent_path().string();
    for (const DeckConfig& group : DeckConfigs(deck, deck_data)) {
      const DeckRun& run = group.run;
      RunSpec spec;
      spec.name = run.name;
      spec.config = group.config;
      spec.base_dir = dir.empty() ? "." : dir;
      ResolveDataPaths(spec.base_dir, &spec.config);
      spec.start_from = run.start_from;
      spec.source = path + " group " + std::to_string(run.group);
      spec.node_lines = false;  // lines of the generated YAML, not the deck
      specs.push_back(spec);
    }
  } else {
    const YAML::Node root = LoadYamlFile(path);
    if (!root.IsMap()) {
      throw InputError(path +
                       ": expected a manifest (defaults:, runs:) or "
                       "a config");
    }
    if (root["runs"]) {
      specs = FromManifest(path, root);
    } else {
      RunSpec spec;
      const fs::path file(path);
      spec.base_dir =
          file.parent_path().empty() ? "." : file.parent_path().string();
      spec.config = root;  // not a clone: its nodes keep their lines
      ResolveDataPaths(spec.base_dir, &spec.config);
      spec.name = root["name"] ? root["name"].Scalar() : file.stem().string();
      spec.config["name"] = spec.name;
      spec.source = path;
      specs.push_back(spec);
    }
  }
  Link(path, &specs);
  return specs;
}

}  // namespace fit3dof
