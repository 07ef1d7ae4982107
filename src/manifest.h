// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A batch manifest turned into runs. Accepted forms:
//   - a YAML file with `defaults:` (config keys deep-merged into every run)
//     and `runs:` (each a config fragment with `name`, and/or `config:`
//     naming a config file, plus overrides, `start_from:` and `diagnose:`;
//     or `together:`, naming runs whose records it fits with one model:
//     run_group.h);
//   - a directory: every *.yaml / *.yml config in it is a run;
//   - a single config file: one run;
//   - a legacy NAMELIST deck (namelist.h): one run per group.
// Relative data paths resolve against the file that wrote them.

#ifndef FIT3DOF_SRC_MANIFEST_H_
#define FIT3DOF_SRC_MANIFEST_H_

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "config_node.h"

namespace fit3dof {

// The batch's lock file in its output directory (batch.cc).
inline constexpr char kBatchLockName[] = ".fit3dof.lock";

struct RunSpec {
  std::string name;
  YAML::Node config;       // merged config, data paths absolute
  std::string source;      // for messages: "manifest.yaml run 'x'"
  std::string base_dir;    // for any path still relative
  std::string start_from;  // predecessor run (IUPDAT), or empty
  bool diagnose = false;   // run the discrepancy workflow (issue 6)
  // The runs whose records this run fits with one model (run_group.h).
  std::vector<std::string> together;
  std::string chain_root;  // first run of its start_from chain
  std::string hash;        // of the merged config and its predecessors
  bool node_lines = true;  // false: config's nodes lost their lines (merged)
  KeyLines key_lines;      // merged: where each key was written
  std::string label;       // merged: "run 'x'", after a key's line
  std::string load_error;  // a config file that could not be read fails
                           // its run with this message
};

// Throws InputError for a manifest that cannot be read (not YAML, no runs,
// duplicate names, unknown or cyclic start_from). Problems inside a run's
// config are found when the run is executed, so they fail that run only.
// `deck_data` is the data file for the fitting groups of a deck.
std::vector<RunSpec> LoadManifest(const std::string& path,
                                  const std::string& deck_data = "");

// 64-bit FNV-1a as 16 hex digits: stable across platforms and runs.
std::string StableHash(const std::string& text);

// StableHash of a file's bytes, read in chunks ("unreadable" if it cannot
// be opened: the run then fails and is redone next time).
std::string FileHash(const std::string& path);

// The data files a (merged, resolved) run config names.
std::vector<std::string> DataFiles(const YAML::Node& config);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_MANIFEST_H_
