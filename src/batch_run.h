// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// One run of a batch: its config read (with its predecessor's values when
// it has start_from), fitted or diagnosed, its outputs written, and its
// RunResult made from the FitResult in memory. With --resume, a report
// whose resume key still matches is taken instead of fitting again.

#ifndef FIT3DOF_SRC_BATCH_RUN_H_
#define FIT3DOF_SRC_BATCH_RUN_H_

#include "fit3dof/batch.h"
#include "manifest.h"

namespace fit3dof {

// Never throws for the run's own problems: a run that cannot be done is
// kFailed with the reason (and DIR/NAME/error.txt), a stop request makes
// it kInterrupted with nothing written.
RunResult ExecuteRun(const RunSpec& spec,
                     const RunResult* predecessor,
                     const BatchOptions& options);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_BATCH_RUN_H_
