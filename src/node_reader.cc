// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Typed, located reading of YAML nodes (node_reader.h).

#include "node_reader.h"

#include <cmath>
#include <sstream>

#include "fit3dof/input_error.h"

namespace fit3dof {

NodeReader::NodeReader(std::string source,
                       bool node_lines,
                       const KeyLines* key_lines,
                       std::string label)
    : source_(std::move(source)),
      node_lines_(node_lines),
      key_lines_(key_lines),
      label_(std::move(label)) {}

void NodeReader::Fail(const YAML::Node& node,
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

std::string NodeReader::KeyLine(std::string key) const {
  if (key_lines_ == nullptr) return "";
  while (!key.empty()) {
    const auto found = key_lines_->find(key);
    if (found != key_lines_->end()) return found->second;
    const size_t cut = key.find_last_of(".[");
    key = cut == std::string::npos ? "" : key.substr(0, cut);
  }
  return "";
}

void NodeReader::CheckKeys(const YAML::Node& node,
                           const std::string& path,
                           const std::set<std::string>& allowed) const {
  if (!node.IsMap()) Fail(node, path, "expected a mapping of keys");
  for (const auto& item : node) {
    const std::string key = item.first.as<std::string>();
    if (allowed.count(key) == 0) {
      std::string list;
      for (const std::string& a : allowed) {
        list += (list.empty() ? "" : ", ") + a;
      }
      Fail(item.first,
           Join(path, key),
           "unknown key (expected one of: " + list + ")");
    }
  }
}

std::string NodeReader::Join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

double NodeReader::Number(const YAML::Node& node,
                          const std::string& key) const {
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

double NodeReader::Positive(const YAML::Node& node,
                            const std::string& key) const {
  const double value = Number(node, key);
  if (!(value > 0.0)) Fail(node, key, "must be positive, got " + node.Scalar());
  return value;
}

double NodeReader::NonNegative(const YAML::Node& node,
                               const std::string& key) const {
  const double value = Number(node, key);
  if (value < 0.0) {
    Fail(node, key, "must not be negative, got " + node.Scalar());
  }
  return value;
}

long NodeReader::Integer(const YAML::Node& node,
                         const std::string& key,
                         long min,
                         long max) const {
  const double value = Number(node, key);
  if (value != std::floor(value) || value < min || value > max) {
    Fail(node,
         key,
         "expected an integer from " + std::to_string(min) + " to " +
             std::to_string(max) + ", got " + node.Scalar());
  }
  return static_cast<long>(value);
}

bool NodeReader::Bool(const YAML::Node& node, const std::string& key) const {
  if (!node.IsScalar()) Fail(node, key, "expected true or false");
  try {
    return node.as<bool>();
  } catch (const YAML::Exception&) {
    Fail(node, key, "expected true or false, got '" + node.Scalar() + "'");
  }
}

std::string NodeReader::String(const YAML::Node& node,
                               const std::string& key) const {
  if (!node.IsScalar()) Fail(node, key, "expected a string");
  return node.Scalar();
}

YAML::Node NodeReader::Required(const YAML::Node& parent,
                                const std::string& path,
                                const std::string& key) const {
  const YAML::Node node = parent[key];
  if (!node.IsDefined() || node.IsNull()) {
    Fail(parent, Join(path, key), "missing (required)");
  }
  return node;
}

}  // namespace fit3dof
