// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Runs of a batch fitted together: a manifest run with `together: [a, b,
// ...]` fits (or, with `diagnose: true`, diagnoses) one model to the
// records of the runs it names, each record a segment with its own initial
// conditions (the config's segments:). What one run cannot separate, runs
// at other spin rates or amplitudes can (a roll-synchronous reading error
// from a body-fixed trim moment; dry friction from a damping), and
// diagnose uses them so (diagnose.h).
//
// The runs must share the model: every config key except their name,
// their records (data, segments) and their initial conditions (the six
// initial-condition parameters, initial_conditions). The run's own keys
// (solver:, a parameter freed, ...) apply on top; it starts from the
// runs' configs, not from their results.

#ifndef FIT3DOF_SRC_RUN_GROUP_H_
#define FIT3DOF_SRC_RUN_GROUP_H_

#include <yaml-cpp/yaml.h>

#include <map>
#include <string>
#include <vector>

#include "manifest.h"

namespace fit3dof {

// Gives each run of `specs` that names runs in `together` its joint config:
// the first named run's shared keys, `own` (the together run's own keys by
// run name) on top, and one segment per record of the named runs. Throws
// InputError (naming `path`) for a together list that names a run not in
// `specs`, the run itself, a run twice or a together run (the manifest
// reader has checked that it lists two or more); runs that do not share
// their model fail the together run alone (load_error, naming the first
// key they differ in).
void JoinRuns(const std::string& path,
              const std::map<std::string, YAML::Node>& own,
              std::vector<RunSpec>* specs);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_RUN_GROUP_H_
