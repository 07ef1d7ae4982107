// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Fits that diagnose repeats, done once. Its search refits the same model
// from the same start more than once: the model without each step for the
// pruning and again for a tie's stand-in, the model as it stands for every
// round's held-out prediction, a swap that lands on a model already
// fitted. On the suite's slowest record (Table 6 with a bearing moment, a
// calibration error and a roll torque) 7 of 43 fits were such repeats.
// FitSamples is a pure function of the case and the data, so a fit of an
// equal case (operator==, case.h, and the same `source`, which the fit's
// warnings name) to equal data is returned from the memo, and the
// diagnosis stays the same bit for bit (the suite's diagnosis.json files
// are identical with and without it).

#ifndef FIT3DOF_SRC_FIT_MEMO_H_
#define FIT3DOF_SRC_FIT_MEMO_H_

#include <vector>

#include "fit3dof/case.h"
#include "fit3dof/fit.h"
#include "fit3dof/time_history.h"
#include "recent_memo.h"

namespace fit3dof {

// FitSamples(c, data), or the result of an earlier call with an equal case
// (and source) and equal data among the most recent kFitMemoCapacity fits of
// the process. Thread-safe; a fit that throws is not remembered (the next call
// throws again).
FitResult MemoizedFitSamples(const Case& c,
                             const std::vector<TimeHistory>& data);

// How many fits the memo keeps (the oldest goes first): more than one
// diagnosis makes, its second searches included (with 64, a pair of runs
// searched five times over had its repeats pushed out and refitted: 4.1 s,
// 2.4 s with 256), few enough that a batch of diagnoses holds a few tens of
// MB.
inline constexpr int kFitMemoCapacity = 256;

// Calls and hits since the process started (for tests and benchmarks).
using FitMemoCounts = MemoCounts;
FitMemoCounts GetFitMemoCounts();

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_FIT_MEMO_H_
