// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Loads a YAML config (format: docs/formats.md) into a validated
// Case. Every problem is reported as an InputError whose message names the
// file, the line and the key and says what was expected, e.g.
//
//   run12.yaml:14: parameters.Cm_alfa: unknown parameter of the symmetric
//   model (did you mean Cm_alpha?)
//
// Paths inside a config (data files) are relative to the config's directory.

#ifndef FIT3DOF_CONFIG_H_
#define FIT3DOF_CONFIG_H_

#include <string>

#include "fit3dof/case.h"
#include "fit3dof/model_conversion.h"  // ToAsymmetric, declared there

namespace fit3dof {

// Reads and validates the config at `path`. Throws InputError.
Case LoadConfig(const std::string& path);

// Same, from text. `source` names the text in messages; relative data paths
// are resolved against `base_dir`.
Case ParseConfig(const std::string& text,
                 const std::string& source,
                 const std::string& base_dir);

// A config (YAML) that loads back into the same case; data paths absolute.
std::string CaseToYaml(const Case& c);

}  // namespace fit3dof

#endif  // FIT3DOF_CONFIG_H_
