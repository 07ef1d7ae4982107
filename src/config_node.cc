// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// YAML text in (config_node.h): strict parsing of one document, the
// character and UTF-8 checks yaml-cpp does not make, key lines of merged
// trees, data paths made absolute, and the manifest's deep merge.

#include "config_node.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "fit3dof/input_error.h"

namespace fit3dof {

namespace fs = std::filesystem;

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
    for (size_t i = 0; i < segments.size(); ++i) {
      // A segment that is not a mapping is the config reader's to report.
      if (segments[i].IsMap()) resolve(segments[i]["data"]);
    }
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

}  // namespace fit3dof
