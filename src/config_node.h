// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// YAML-level helpers shared by the config loader and the batch manifest
// (kept out of the public headers so that users of the library need not see
// yaml-cpp).

#ifndef FIT3DOF_SRC_CONFIG_NODE_H_
#define FIT3DOF_SRC_CONFIG_NODE_H_

#include <yaml-cpp/yaml.h>

#include <map>
#include <string>

#include "fit3dof/case.h"

namespace fit3dof {

// Where each key of a merged config was written: key path as the config
// reader names it ("data.fraction", "segments[0].data", "parameters.Cm_q")
// to "file:line" of the file that set it last.
using KeyLines = std::map<std::string, std::string>;

// Records the line of every key under `node` (read from `file`) in `lines`,
// with `prefix` the path of `node` itself ("" for a config's root).
void RecordKeyLines(const YAML::Node& node,
                    const std::string& file,
                    const std::string& prefix,
                    KeyLines* lines);

// A config from an already parsed YAML node (e.g. a merged manifest run).
// Messages name `source` and the node's line; with `node_lines` false (a
// merged tree, whose copied nodes lost their lines) the line of the key in
// `key_lines` (or of its nearest parent key) followed by `label`, or
// `source` alone when the key is not there ("manifest.yaml:14: run 'x'").
Case ParseConfigNode(const YAML::Node& root,
                     const std::string& source,
                     const std::string& base_dir,
                     bool node_lines = true,
                     const KeyLines* key_lines = nullptr,
                     const std::string& label = "");

// Parses YAML text strictly: one document, keys plain and unique in each
// mapping, every string valid UTF-8. InputError names `source` and the line.
YAML::Node ParseYamlText(const std::string& text, const std::string& source);

// ParseYamlText of a file's contents.
YAML::Node LoadYamlFile(const std::string& path);

// True if `text` is well-formed UTF-8.
bool IsValidUtf8(const std::string& text);

// Makes data.file and segments[].data.file absolute against base_dir: a
// relative path means relative to the file that wrote it.
void ResolveDataPaths(const std::string& base_dir, YAML::Node* node);

// Deep merge: mappings merge key by key, anything else in `overrides`
// replaces what `base` has. Returns a new tree.
YAML::Node MergeYaml(const YAML::Node& base, const YAML::Node& overrides);

// The shortest decimal that reads back as the same double (with a decimal
// point, so YAML reads it as a number of the right kind).
std::string ShortestNumber(double x);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_CONFIG_NODE_H_
