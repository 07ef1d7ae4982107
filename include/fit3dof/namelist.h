// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The report's input decks (Table 4): Fortran NAMELIST groups
//
//   TITLE CARD
//   &NAM NSWTCH=0, NITER=50, AREA=0.390, AACON(1)=-0.2, 0.0,
//        NCON=1,1,0,0,1,1,18*0,6*1, BOUND=1.0D-6, ... &END
//
// (also terminated by '/' or $END; `r*value` repeats; .TRUE./.T./T
// logicals; D exponents; '!' comments; text outside groups is a title card).
// A deck is read group by group like the 1978 program did: each READ
// changes only the variables it names, so every group's configuration is
// the state after all groups so far. AACON/NCON map by index to the named
// parameters of the symmetric (NC = 30) or asymmetric (NC = 72, or IZ/IZX
// given) program; the switches map to config keys (table in namelist.cc).
// IUPDAT = 1 chains the next group to this one (start_from).

#ifndef FIT3DOF_NAMELIST_H_
#define FIT3DOF_NAMELIST_H_

#include <string>
#include <vector>

namespace fit3dof {

struct DeckValue {
  enum Kind { kNumber, kLogical, kString, kNull } kind = kNull;
  double number = 0.0;
  bool logical = false;
  std::string text;
};

struct DeckAssignment {
  std::string variable;  // upper case
  int index = 0;         // 1-based first index given as VAR(i), 0 if none
  std::vector<DeckValue> values;
  int line = 0;
};

struct DeckGroup {
  std::string name;  // e.g. NAM
  int line = 0;
  std::vector<DeckAssignment> assignments;
};

struct Deck {
  std::string source;
  std::vector<std::string> titles;  // card images outside the groups
  std::vector<DeckGroup> groups;
};

// Throws InputError naming the line for malformed syntax.
Deck ParseDeck(const std::string& text, const std::string& source);
Deck ReadDeck(const std::string& path);

// One run per group.
struct DeckRun {
  std::string name;  // <deck stem>-<group>
  int group = 0;     // 1-based
  std::string config_yaml;
  std::string start_from;
  std::vector<std::string> ignored;  // variables accepted and ignored
};

// `data_file` is the record the groups with NSWTCH = 0 fit (the 1978
// program found it by IGPNO/IBLKNO in a direct-access file); it may be
// empty. Throws InputError for unknown variables or missing constants,
// naming the line or group.
std::vector<DeckRun> DeckRuns(const Deck& deck, const std::string& data_file);

// True when the file looks like a deck (its first group opens with '&' or
// '$' at the start of a line).
bool IsDeckFile(const std::string& path);

// The Case of a one-group deck (`fit3dof fit DECK --data=FILE`); a deck with
// several groups is a batch. Throws InputError.
struct Case;
Case LoadDeckCase(const std::string& path, const std::string& data_file);

// The YAML for `fit3dof namelist`: a config for a one-group deck, a
// manifest (runs:) for several.
std::string DeckToYaml(const Deck& deck, const std::string& data_file);

}  // namespace fit3dof

#endif  // FIT3DOF_NAMELIST_H_
