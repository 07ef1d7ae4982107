// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// NodeReader reads typed values out of a YAML tree and fails with a located
// message: "file:line: key: what was expected". It is the base of the
// config reader; merged trees (a manifest run) lost their nodes' lines, so
// their messages take the line from a KeyLines map instead.

#ifndef FIT3DOF_SRC_NODE_READER_H_
#define FIT3DOF_SRC_NODE_READER_H_

#include <yaml-cpp/yaml.h>

#include <limits>
#include <set>
#include <string>

#include "config_node.h"

namespace fit3dof {

class NodeReader {
 public:
  // Messages name `source` and the node's line; with `node_lines` false
  // the line of the key (or its nearest parent) in `key_lines`, then
  // `label` ("run 'x'").
  NodeReader(std::string source,
             bool node_lines,
             const KeyLines* key_lines,
             std::string label);

  // Throws InputError "where: key: message".
  [[noreturn]] void Fail(const YAML::Node& node,
                         const std::string& key,
                         const std::string& message) const;

  // Fails on a non-mapping or on a key outside `allowed`, listing them.
  void CheckKeys(const YAML::Node& node,
                 const std::string& path,
                 const std::set<std::string>& allowed) const;

  // "path.key", or "key" at the top level.
  static std::string Join(const std::string& path, const std::string& key);

  // A finite number.
  double Number(const YAML::Node& node, const std::string& key) const;
  double Positive(const YAML::Node& node, const std::string& key) const;
  double NonNegative(const YAML::Node& node, const std::string& key) const;
  // An integer in [min, max]; the default max fits an int.
  long Integer(const YAML::Node& node,
               const std::string& key,
               long min,
               long max = std::numeric_limits<int>::max()) const;
  bool Bool(const YAML::Node& node, const std::string& key) const;
  std::string String(const YAML::Node& node, const std::string& key) const;
  // parent[key], failing "missing (required)" when absent or null.
  YAML::Node Required(const YAML::Node& parent,
                      const std::string& path,
                      const std::string& key) const;

  const std::string& source() const { return source_; }

 private:
  // "file:line" of `key` or of its nearest parent in key_lines_; empty
  // when there are no key lines or none matches.
  std::string KeyLine(std::string key) const;

  std::string source_;
  bool node_lines_;  // false for merged trees, whose nodes lost their lines
  const KeyLines* key_lines_;  // for merged trees: where each key came from
  std::string label_;          // "run 'x'", after a key's line
};

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_NODE_READER_H_
