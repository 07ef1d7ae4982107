// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The NAMELIST deck parser (namelist.h): card images -> Deck, and the
// public entry points. The variables' meaning and their config keys are in
// deck_config.cc.

#include "fit3dof/namelist.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "config_node.h"
#include "deck_config.h"
#include "fit3dof/case.h"
#include "fit3dof/input_error.h"
#include "fit3dof/parameters.h"

namespace fit3dof {
namespace {

class DeckParser {
 public:
  DeckParser(const std::string& text, const std::string& source)
      : text_(text), source_(source) {}

  Deck Parse() {
    Deck deck;
    deck.source = source_;
    std::string title;
    while (!AtEnd()) {
      SkipComment();
      const char c = Peek();
      if (c == '&' || c == '$') {
        if (!Trim(title).empty()) deck.titles.push_back(Trim(title));
        title.clear();
        deck.groups.push_back(Group());
      } else if (c == '\n') {
        if (!Trim(title).empty()) deck.titles.push_back(Trim(title));
        title.clear();
        Advance();
      } else {
        title += c;
        Advance();
      }
    }
    if (!Trim(title).empty()) deck.titles.push_back(Trim(title));
    if (deck.groups.empty()) {
      throw InputError(source_ + ": no NAMELIST group (&NAM ... &END) found");
    }
    return deck;
  }

 private:
  [[noreturn]] void Fail(const std::string& message) const {
    throw InputError(source_ + ":" + std::to_string(line_) + ": " + message);
  }
  bool AtEnd() const { return pos_ >= text_.size(); }
  char Peek(size_t ahead = 0) const {
    return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0';
  }
  void Advance() {
    if (Peek() == '\n') ++line_;
    ++pos_;
  }
  static std::string Trim(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t\r");
    if (a == std::string::npos) return "";
    return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
  }
  void SkipComment() {
    if (Peek() == '!') {
      while (!AtEnd() && Peek() != '\n') Advance();
    }
  }
  // Skips blanks, newlines, comments and (if `commas`) commas.
  void SkipSpace(bool commas) {
    while (!AtEnd()) {
      const char c = Peek();
      if (c == '!') {
        SkipComment();
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\n' ||
                 (commas && c == ',')) {
        Advance();
      } else {
        break;
      }
    }
  }
  std::string Word() {
    std::string w;
    while (!AtEnd() && (std::isalnum(static_cast<unsigned char>(Peek())) ||
                        Peek() == '_')) {
      w += static_cast<char>(std::toupper(static_cast<unsigned char>(Peek())));
      Advance();
    }
    return w;
  }
  bool AtTerminator() {
    const char c = Peek();
    if (c == '/') return true;
    if (c == '&' || c == '$') return true;
    return false;
  }
  // True when the text ahead is NAME= or NAME( (the next assignment).
  bool AtAssignment() const {
    size_t p = pos_;
    if (p >= text_.size() ||
        !std::isalpha(static_cast<unsigned char>(text_[p]))) {
      return false;
    }
    while (p < text_.size() &&
           (std::isalnum(static_cast<unsigned char>(text_[p])) ||
            text_[p] == '_')) {
      ++p;
    }
    while (p < text_.size() && (text_[p] == ' ' || text_[p] == '\t')) ++p;
    return p < text_.size() && (text_[p] == '=' || text_[p] == '(');
  }

  DeckGroup Group() {
    DeckGroup group;
    group.line = line_;
    Advance();  // & or $
    group.name = Word();
    if (group.name.empty()) Fail("expected a group name after '&'");
    if (group.name == "END") Fail("&END without a group to close");
    while (true) {
      SkipSpace(true);
      if (AtEnd()) {
        Fail("group &" + group.name + " (line " + std::to_string(group.line) +
             ") is not closed by &END or /");
      }
      if (Peek() == '/') {
        Advance();
        return group;
      }
      if (Peek() == '&' || Peek() == '$') {
        Advance();
        const std::string word = Word();
        if (word == "END") return group;
        Fail("group &" + group.name + " is not closed before &" + word);
      }
      group.assignments.push_back(Assignment());
    }
  }

  DeckAssignment Assignment() {
    DeckAssignment a;
    a.line = line_;
    if (!std::isalpha(static_cast<unsigned char>(Peek()))) {
      Fail(std::string("expected a variable name, found '") + Peek() + "'");
    }
    a.variable = Word();
    SkipSpace(false);
    if (Peek() == '(') {
      Advance();
      SkipSpace(false);
      std::string digits;
      while (std::isdigit(static_cast<unsigned char>(Peek()))) {
        digits += Peek();
        Advance();
      }
      SkipSpace(false);
      if (digits.empty() || Peek() != ')') {
        Fail(a.variable + ": expected an index like " + a.variable + "(5)");
      }
      Advance();
      a.index = std::atoi(digits.c_str());
      if (a.index < 1) Fail(a.variable + ": indices start at 1");
      SkipSpace(false);
    }
    if (Peek() != '=') Fail(a.variable + ": expected '=' after the name");
    Advance();
    while (true) {
      SkipSpace(true);
      if (AtEnd() || AtTerminator() || AtAssignment()) break;
      Values(a.variable, &a.values);
    }
    if (a.values.empty()) Fail(a.variable + ": no value after '='");
    return a;
  }

  // One constant, or r*constant (r copies), appended to `out`.
  void Values(const std::string& variable, std::vector<DeckValue>* out) {
    std::string token;
    if (Peek() == '\'' || Peek() == '"') {
      const char quote = Peek();
      Advance();
      DeckValue v;
      v.kind = DeckValue::kString;
      while (true) {
        if (AtEnd() || Peek() == '\n') Fail(variable + ": unterminated string");
        if (Peek() == quote) {
          Advance();
          if (Peek() != quote) break;
        }
        v.text += Peek();
        Advance();
      }
      out->push_back(v);
      return;
    }
    while (!AtEnd() && !std::isspace(static_cast<unsigned char>(Peek())) &&
           Peek() != ',' && Peek() != '/' && Peek() != '!' &&
           !(Peek() == '&' && !token.empty()) && Peek() != '$') {
      token += Peek();
      Advance();
    }
    int repeat = 1;
    const size_t star = token.find('*');
    if (star != std::string::npos) {
      const std::string count = token.substr(0, star);
      char* end = nullptr;
      const long r = std::strtol(count.c_str(), &end, 10);
      if (count.empty() || *end != '\0' || r < 1) {
        Fail(variable + ": bad repeat count in '" + token + "'");
      }
      // No array of the deck is longer than the asymmetric program's
      // parameter list: a larger count is a typing error (and 10^9 copies
      // would take gigabytes).
      const int longest = NumParameters(ModelKind::kAsymmetric);
      if (r > longest) {
        Fail(variable + ": repeat count " + count + " in '" + token +
             "' exceeds the longest array (" + std::to_string(longest) +
             " elements)");
      }
      repeat = static_cast<int>(r);
      token = token.substr(star + 1);
      if (token.empty()) {  // r* : r null values
        for (int i = 0; i < repeat; ++i) out->push_back(DeckValue{});
        return;
      }
    }
    const DeckValue v = Constant(variable, token);
    for (int i = 0; i < repeat; ++i) out->push_back(v);
  }

  DeckValue Constant(const std::string& variable, const std::string& token) {
    std::string upper;
    for (char c : token)
      upper += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    DeckValue v;
    if (upper == ".TRUE." || upper == ".T." || upper == "T" ||
        upper == ".FALSE." || upper == ".F." || upper == "F") {
      v.kind = DeckValue::kLogical;
      v.logical = upper[0] == 'T' || upper[1] == 'T';
      return v;
    }
    std::string number = upper;
    for (char& c : number) {
      if (c == 'D') c = 'E';
    }
    char* end = nullptr;
    const double x = std::strtod(number.c_str(), &end);
    if (!token.empty() && std::isalpha(static_cast<unsigned char>(token[0]))) {
      Fail(variable + ": expected a value, found '" + token +
           "' (a variable needs '=' after its name)");
    }
    if (number.empty() || *end != '\0' || !std::isfinite(x) ||
        number.find_first_of("0123456789") == std::string::npos) {
      Fail(variable + ": '" + token + "' is not a number, logical or string");
    }
    v.kind = DeckValue::kNumber;
    v.number = x;
    return v;
  }

  const std::string& text_;
  std::string source_;
  size_t pos_ = 0;
  int line_ = 1;
};

}  // namespace
Deck ParseDeck(const std::string& text, const std::string& source) {
  return DeckParser(text, source).Parse();
}

Deck ReadDeck(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the deck");
  std::stringstream text;
  text << in.rdbuf();
  return ParseDeck(text.str(), path);
}

std::vector<DeckRun> DeckRuns(const Deck& deck, const std::string& data_file) {
  std::vector<DeckRun> runs;
  for (const DeckConfig& config : DeckConfigs(deck, data_file)) {
    runs.push_back(config.run);
    runs.back().config_yaml = DeckConfigYaml(deck, config);
  }
  return runs;
}

bool IsDeckFile(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    if (line[first] == '&' || line[first] == '$') return true;
  }
  return false;
}

Case LoadDeckCase(const std::string& path, const std::string& data_file) {
  const std::vector<DeckConfig> configs =
      DeckConfigs(ReadDeck(path), data_file);
  if (configs.size() != 1) {
    throw InputError(path + ": the deck has " + std::to_string(configs.size()) +
                     " groups; run it with fit3dof batch");
  }
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return ParseConfigNode(configs[0].config, path, dir.empty() ? "." : dir);
}

std::string DeckToYaml(const Deck& deck, const std::string& data_file) {
  return DeckYaml(deck, DeckConfigs(deck, data_file));
}

}  // namespace fit3dof
