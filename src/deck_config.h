// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A parsed NAMELIST deck (namelist.h) turned into config trees, one per
// group, without going through text: the batch merges them like any
// manifest run, `fit3dof fit DECK` reads its one group into a Case, and
// `fit3dof namelist` writes them through YAML::Emitter.

#ifndef FIT3DOF_SRC_DECK_CONFIG_H_
#define FIT3DOF_SRC_DECK_CONFIG_H_

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "fit3dof/namelist.h"

namespace fit3dof {

struct DeckConfig {
  DeckRun run;        // name, group, start_from, ignored (config_yaml empty)
  YAML::Node config;  // the group's config; data path as given
};

// One config per group (the state after it, as the 1978 program read
// them). Throws InputError for unknown variables or missing constants,
// naming the line or group.
std::vector<DeckConfig> DeckConfigs(const Deck& deck,
                                    const std::string& data_file);

// The config as YAML text: names and paths quoted, each parameter with its
// AACON index as a comment, a first comment naming the deck and group.
std::string DeckConfigYaml(const Deck& deck, const DeckConfig& config);

// What `fit3dof namelist` writes: DeckConfigYaml for one group, a manifest
// (runs:, each with its start_from) for several.
std::string DeckYaml(const Deck& deck, const std::vector<DeckConfig>& configs);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_DECK_CONFIG_H_
