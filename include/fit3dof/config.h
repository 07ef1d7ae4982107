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

// The same motion in the asymmetric program (body axes, I_zx): every
// symmetric term with an exact asymmetric image is mapped to it (Cm_alpha
// to Cm_alpha and -Cn_beta, Cm_q to Cm_q and Cn_r, the cubic terms to the
// alpha^3, alpha beta^2, ... terms, Magnus, roll, tunnel, offsets, roll
// interaction), free flags with them. Throws InputError when the case uses
// a symmetric term without an image (the |delta| terms, Cm_q_beta2,
// Cm_r_alpha_beta, Cm_p_alpha_delta2, Cm_alphadot). Initial conditions that
// are given are converted from Euler rates to body rates.
Case ToAsymmetric(const Case& c);

}  // namespace fit3dof

#endif  // FIT3DOF_CONFIG_H_
