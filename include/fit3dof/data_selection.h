// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Which samples of a record a fit uses: the report's PART subroutine
// (NSTART, SAMPLE, NDELTA) after an optional time window.

#ifndef FIT3DOF_DATA_SELECTION_H_
#define FIT3DOF_DATA_SELECTION_H_

#include "fit3dof/case.h"
#include "fit3dof/time_history.h"

namespace fit3dof {

// Applies, in order: the time window [t_start, t_end]; the first sample
// `start` (1-based); every `every`-th sample from there; and only samples
// whose time after the first is at most `fraction` of the remaining record.
TimeHistory SelectSamples(const TimeHistory& record,
                          const DataSelection& selection);

// Roll angles made continuous (no jumps of more than 180 deg between
// samples), for records that wrap phi into [0, 360).
std::vector<double> UnwrapDegrees(const std::vector<double>& angles);

}  // namespace fit3dof

#endif  // FIT3DOF_DATA_SELECTION_H_
