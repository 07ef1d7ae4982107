// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// NAMELIST /NAM/ of both listings (Tables 1 and 2) and Table 4:
//
//   NSWTCH  0 fit, 1/2 generate motion  -> fit, or simulate: block
//   NITER, BOUND, DTMIN                 -> solver.max_iterations, tolerance,
//   step AREA, DIA, IX, IY, IZ               -> body IZX -> parameter Izx
//   (AACON(60)) RO, U                               -> flow.density,
//   flow.velocity AACON(i), NCON(i)                   -> parameters (value,
//   free) NSESWH, SPHI, STHTA, SPSI, AMPHI, AMTHTA, AMPSI                ->
//   noise (seed 1: the 1978 program
//                                          seeded from the clock)
//   SAMPLE, NDELTA, NSTART              -> data.fraction, every, start
//   IUPDAT                              -> the next group: start_from
//   INLCON                              -> initial_conditions
//   IANGLE                              -> incidence
//   DTGEN, NTOT (NSWTCH != 0)           -> simulate.dt, samples
//   SIGPHI, SIGTHA, SIGPSI              -> sigma
//   IGPNO, IBLKNO, IRCGEN, IRCSTR, NC,
//   NTOT (NSWTCH = 0)                   -> accepted and ignored

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

// The deck's variables after some groups: scalars and 1-based arrays.
struct DeckState {
  std::map<std::string, DeckValue> scalars;
  std::map<std::string, std::map<int, DeckValue>> arrays;
  std::map<std::string, int> line;  // where each was last set

  bool Has(const std::string& name) const { return scalars.count(name) > 0; }
  double Number(const std::string& name, double fallback) const {
    const auto it = scalars.find(name);
    if (it == scalars.end()) return fallback;
    if (it->second.kind == DeckValue::kLogical)
      return it->second.logical ? 1 : 0;
    return it->second.number;
  }
};

const std::set<std::string>& ScalarVariables() {
  static const std::set<std::string> names = {
      "NSWTCH", "NTOT",  "NC",     "NITER",  "DTMIN",  "BOUND",  "AREA",
      "DIA",    "IX",    "IY",     "IZ",     "IZX",    "RO",     "U",
      "NSESWH", "SPHI",  "STHTA",  "STHA",   "SPSI",   "AMPHI",  "AMTHTA",
      "AMTHA",  "AMPSI", "SAMPLE", "NDELTA", "IUPDAT", "INLCON", "IANGLE",
      "DTGEN",  "IGPNO", "IBLKNO", "IRCGEN", "SIGPHI", "SIGTHA", "SIGPSI",
      "NSTART", "IRCSTR"};
  return names;
}

const std::set<std::string>& IgnoredVariables() {
  static const std::set<std::string> names = {
      "IGPNO", "IBLKNO", "IRCGEN", "IRCSTR", "NC"};
  return names;
}

void Apply(const std::string& source,
           const DeckAssignment& a,
           DeckState* state) {
  const std::string where = source + ":" + std::to_string(a.line) + ": ";
  if (a.variable == "AACON" || a.variable == "NCON") {
    const int first = a.index > 0 ? a.index : 1;
    for (size_t i = 0; i < a.values.size(); ++i) {
      const DeckValue& v = a.values[i];
      if (v.kind == DeckValue::kNull) continue;
      if (v.kind != DeckValue::kNumber) {
        throw InputError(where + a.variable + ": expected numbers");
      }
      const int index = first + static_cast<int>(i);
      if (index > kMaxParameters) {
        throw InputError(
            where + a.variable + "(" + std::to_string(index) +
            "): beyond the 72 parameters of the asymmetric program");
      }
      state->arrays[a.variable][index] = v;
    }
    state->line[a.variable] = a.line;
    return;
  }
  if (ScalarVariables().count(a.variable) == 0) {
    throw InputError(
        where + a.variable +
        ": not a variable of the report's NAMELIST /NAM/ (Table 4)");
  }
  if (a.index > 1 || a.values.size() != 1) {
    throw InputError(where + a.variable + ": expected a single value");
  }
  if (a.values[0].kind == DeckValue::kString) {
    throw InputError(where + a.variable + ": expected a number");
  }
  // The listing's integer variables (Fortran's I-N rule; IX, IY, IZ, IZX
  // are declared real) hold whole numbers an INTEGER can: anything else is
  // refused here, where the line is known, before it is cast.
  static const std::set<std::string> kIntegers = {"NSWTCH",
                                                  "NTOT",
                                                  "NC",
                                                  "NITER",
                                                  "NSESWH",
                                                  "NDELTA",
                                                  "NSTART",
                                                  "IUPDAT",
                                                  "INLCON",
                                                  "IANGLE",
                                                  "IGPNO",
                                                  "IBLKNO",
                                                  "IRCGEN",
                                                  "IRCSTR"};
  const DeckValue& v = a.values[0];
  if (kIntegers.count(a.variable) > 0 && v.kind == DeckValue::kNumber &&
      !(v.number == std::floor(v.number) &&
        std::abs(v.number) <= 2147483647.0)) {
    throw InputError(where + a.variable +
                     ": expected an integer from -2147483647 to 2147483647");
  }
  state->scalars[a.variable] = v;
  state->line[a.variable] = a.line;
}

// The config of one group, from the state after it.
std::string GroupConfig(const Deck& deck,
                        const DeckState& state,
                        int group,
                        const std::string& name,
                        const std::string& data_file,
                        std::vector<std::string>* ignored) {
  const std::string where = deck.source + " group " + std::to_string(group);
  auto require = [&](const char* variable, const char* key) {
    if (!state.Has(variable)) {
      throw InputError(where + ": " + variable + " (" + key +
                       ") is not set in this group or an earlier one");
    }
    return state.Number(variable, 0.0);
  };
  const auto aacon_it = state.arrays.find("AACON");
  const auto ncon_it = state.arrays.find("NCON");
  int largest = 0;
  if (aacon_it != state.arrays.end() && !aacon_it->second.empty()) {
    largest = aacon_it->second.rbegin()->first;
  }
  if (ncon_it != state.arrays.end() && !ncon_it->second.empty()) {
    largest = std::max(largest, ncon_it->second.rbegin()->first);
  }
  const bool asymmetric = state.Number("NC", 0) == 72 || state.Has("IZ") ||
                          state.Has("IZX") || largest > 30;
  const ModelKind model =
      asymmetric ? ModelKind::kAsymmetric : ModelKind::kSymmetric;
  const auto& table = ParameterTable(model);
  if (largest > NumParameters(model)) {
    throw InputError(where + ": AACON/NCON index " + std::to_string(largest) +
                     " is beyond the " + std::to_string(NumParameters(model)) +
                     " parameters of the " + ModelName(model) + " program");
  }
  const int nswtch = static_cast<int>(state.Number("NSWTCH", 0));
  std::ostringstream y;
  y << "# converted from " << deck.source << ", NAMELIST group " << group;
  if (!deck.titles.empty()) y << " (" << deck.titles.front() << ")";
  y << "\nname: " << name << "\n";
  y << "model: " << ModelName(model) << "\n";
  y << "incidence: "
    << (state.Number("IANGLE", 0) == 0 ? "velocity_ratio" : "angle_of_attack")
    << "\n";
  y << "body:\n  area: " << ShortestNumber(require("AREA", "body.area"))
    << "\n  diameter: " << ShortestNumber(require("DIA", "body.diameter"))
    << "\n  Ix: " << ShortestNumber(require("IX", "body.Ix"))
    << "\n  Iy: " << ShortestNumber(require("IY", "body.Iy")) << "\n";
  if (asymmetric)
    y << "  Iz: " << ShortestNumber(require("IZ", "body.Iz")) << "\n";
  y << "flow:\n  velocity: " << ShortestNumber(require("U", "flow.velocity"))
    << "\n  density: " << ShortestNumber(require("RO", "flow.density")) << "\n";
  y << "parameters:\n";
  for (int i = 1; i <= NumParameters(model); ++i) {
    double value = 0.0;
    bool free = false;
    if (aacon_it != state.arrays.end() && aacon_it->second.count(i)) {
      value = aacon_it->second.at(i).number;
    }
    if (ncon_it != state.arrays.end() && ncon_it->second.count(i)) {
      free = ncon_it->second.at(i).number != 0.0;
    }
    if (asymmetric && i == 60 && state.Has("IZX"))
      value = state.Number("IZX", 0);
    const ParameterInfo& info = table[i - 1];
    if (info.scaling == Scaling::kUnused) {
      if (value != 0.0 || free) {
        ignored->push_back("AACON(" + std::to_string(i) + ") (spare slot " +
                           info.name + ")");
      }
      continue;
    }
    if (value == 0.0 && !free) continue;
    y << "  " << info.name << ": {value: " << ShortestNumber(value)
      << ", free: " << (free ? "true" : "false") << "}  # AACON(" << i << ")\n";
  }
  y << "initial_conditions: "
    << (state.Number("INLCON", 0) == 0 ? "from_data" : "given") << "\n";
  if (nswtch == 0 && !data_file.empty()) {
    y << "data:\n  file: " << data_file
      << "\n  start: " << static_cast<long>(state.Number("NSTART", 1))
      << "\n  fraction: " << ShortestNumber(state.Number("SAMPLE", 1.0))
      << "\n  every: " << static_cast<long>(state.Number("NDELTA", 1)) << "\n";
  }
  if (state.Has("SIGPHI") || state.Has("SIGTHA") || state.Has("SIGPSI")) {
    y << "sigma: {phi: " << ShortestNumber(state.Number("SIGPHI", 1.0))
      << ", theta: " << ShortestNumber(state.Number("SIGTHA", 1.0))
      << ", psi: " << ShortestNumber(state.Number("SIGPSI", 1.0)) << "}\n";
  }
  if (state.Number("NSESWH", 0) == 1) {
    const double stheta =
        state.Has("STHTA") ? state.Number("STHTA", 0) : state.Number("STHA", 0);
    const double btheta = state.Has("AMTHTA") ? state.Number("AMTHTA", 0)
                                              : state.Number("AMTHA", 0);
    y << "noise:  # NSESWH = 1; the 1978 program seeded its RANDU from the "
         "clock\n"
      << "  sigma: {phi: " << ShortestNumber(state.Number("SPHI", 0))
      << ", theta: " << ShortestNumber(stheta)
      << ", psi: " << ShortestNumber(state.Number("SPSI", 0)) << "}\n"
      << "  bias: {phi: " << ShortestNumber(state.Number("AMPHI", 0))
      << ", theta: " << ShortestNumber(btheta)
      << ", psi: " << ShortestNumber(state.Number("AMPSI", 0))
      << "}\n  seed: 1\n";
  }
  y << "solver:\n";
  if (state.Has("NITER")) {
    y << "  max_iterations: " << static_cast<long>(state.Number("NITER", 50))
      << "\n";
  }
  if (state.Has("BOUND"))
    y << "  tolerance: " << ShortestNumber(state.Number("BOUND", 0)) << "\n";
  if (state.Has("DTMIN"))
    y << "  step: " << ShortestNumber(state.Number("DTMIN", 0)) << "\n";
  if (nswtch != 0) {
    y << "simulate:\n  dt: " << ShortestNumber(require("DTGEN", "simulate.dt"))
      << "\n  samples: "
      << static_cast<long>(require("NTOT", "simulate.samples")) << "\n";
  } else if (state.Has("NTOT")) {
    ignored->push_back("NTOT (array size; the data file sets the samples)");
  }
  for (const std::string& v : IgnoredVariables()) {
    if (state.Has(v)) ignored->push_back(v);
  }
  if (!ignored->empty()) {
    y << "# ignored (no meaning today):";
    for (const std::string& v : *ignored) y << " " << v << ";";
    y << "\n";
  }
  return y.str();
}

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
  const std::string stem = std::filesystem::path(deck.source).stem().string();
  std::vector<DeckRun> runs;
  DeckState state;
  bool update_next = false;
  for (size_t g = 0; g < deck.groups.size(); ++g) {
    const DeckGroup& group = deck.groups[g];
    if (group.name != "NAM") {
      throw InputError(deck.source + ":" + std::to_string(group.line) + ": &" +
                       group.name + ": the programs read NAMELIST /NAM/ only");
    }
    for (const DeckAssignment& a : group.assignments)
      Apply(deck.source, a, &state);
    DeckRun run;
    run.group = static_cast<int>(g) + 1;
    run.name =
        deck.groups.size() == 1 ? stem : stem + "-" + std::to_string(run.group);
    if (update_next && !runs.empty()) run.start_from = runs.back().name;
    run.config_yaml =
        GroupConfig(deck, state, run.group, run.name, data_file, &run.ignored);
    update_next = state.Number("IUPDAT", 0) == 1;
    runs.push_back(run);
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
  const std::vector<DeckRun> runs = DeckRuns(ReadDeck(path), data_file);
  if (runs.size() != 1) {
    throw InputError(path + ": the deck has " + std::to_string(runs.size()) +
                     " groups; run it with fit3dof batch");
  }
  YAML::Node config = YAML::Load(runs[0].config_yaml);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return ParseConfigNode(config, path, dir.empty() ? "." : dir);
}

std::string DeckToYaml(const Deck& deck, const std::string& data_file) {
  const std::vector<DeckRun> runs = DeckRuns(deck, data_file);
  if (runs.size() == 1) return runs[0].config_yaml;
  std::ostringstream y;
  y << "# converted from " << deck.source << ": " << runs.size()
    << " NAMELIST groups, one run each\nruns:\n";
  for (const DeckRun& run : runs) {
    std::istringstream lines(run.config_yaml);
    std::string line;
    bool first = true;
    while (std::getline(lines, line)) {
      if (line.rfind("#", 0) == 0) {
        y << "  " << line << "\n";
        continue;
      }
      y << (first ? "  - " : "    ") << line << "\n";
      first = false;
    }
    if (!run.start_from.empty())
      y << "    start_from: " << run.start_from << "  # IUPDAT = 1\n";
  }
  return y.str();
}

}  // namespace fit3dof
