// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// What the diagnosis loop (diagnose.cc) is built from: the candidate case
// of a catalog effect (effect_catalog.cc) and its score test
// (score_test.cc).

#ifndef FIT3DOF_SRC_DIAGNOSE_INTERNAL_H_
#define FIT3DOF_SRC_DIAGNOSE_INTERNAL_H_

#include <string>
#include <vector>

#include "fit3dof/case.h"
#include "fit3dof/diagnose.h"
#include "fit3dof/time_history.h"

namespace fit3dof {

// The case `at` with the effect's parameters free at zero (converted to the
// asymmetric program when the effect needs it), their names in `added`;
// false when the effect does not apply or is already in the model.
bool CandidateCase(const Case& at,
                   const Effect& effect,
                   Case* out,
                   std::vector<std::string>* added);

// The score (Lagrange-multiplier) statistic of the candidate's `added`
// parameters at the current solution, on the samples the fit used (one
// record per segment); see diagnose.h.
CandidateScore Score(const Case& candidate,
                     const std::vector<std::string>& added,
                     const std::string& id,
                     const std::vector<TimeHistory>& data);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_DIAGNOSE_INTERNAL_H_
