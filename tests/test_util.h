// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Helpers shared by the tests: where the sources, the report's published
// numbers and the built command are, scratch directories, running the command.

#ifndef FIT3DOF_TESTS_TEST_UTIL_H_
#define FIT3DOF_TESTS_TEST_UTIL_H_

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fit3dof/case.h"
#include "fit3dof/fit.h"

namespace fit3dof::testing {

// True in the ASan/UBSan build (tools/test --sanitize), which runs 10-100x
// slower: loops over noise seeds run a tenth of their repetitions there
// (the statistics are checked by the plain build), and the costliest
// records run in the plain build only (PlainBuildOnly).
#ifdef FIT3DOF_SANITIZED
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

// Whether a test the plain build runs alone (a costly diagnosis: three
// effects, several searches, two runs) skips: in the sanitized build,
// unless FIT3DOF_SANITIZE_ALL is set (tools/test --sanitize --all, 13
// minutes of tests on 2 cores), which runs every one of them under the
// sanitizers.
// A few such records run sanitized anyway, chosen by
// tools/sanitized_coverage for the lines of src/ only they reach.
bool PlainBuildOnly();

// `full`, or a tenth of it (at least 2) in the sanitized build.
inline int Repetitions(int full) {
  return kSanitized ? (full / 10 > 2 ? full / 10 : 2) : full;
}

// The report's published numbers, tests/data/report_numbers.json.
const nlohmann::json& PaperResults();

// A path under the source tree, e.g. SourcePath("configs/report/x.yaml").
std::string SourcePath(const std::string& relative);

// A fresh, empty directory for one test (removed when the process exits
// only if the test passes is not attempted: it lives under the build tree).
std::string ScratchDirectory(const std::string& name);

// Writes text to a file, creating directories.
void WriteText(const std::string& path, const std::string& text);
std::string ReadText(const std::string& path);

struct CommandResult {
  int exit_status = -1;
  std::string output;  // stdout and stderr together
};

// Writes to `path` the motion of `truth` (SimulateAt, its own solver step)
// at `times` with 0.01 deg of noise on each channel (seed `seed`), and
// returns `path`.
std::string WriteNoisyRecord(const Case& truth,
                             const std::vector<double>& times,
                             std::uint64_t seed,
                             const std::string& path);

// The short condition of tools/diagnose_suite (the Section 5.3 sharp cone:
// 3 s at 10 points per pitch cycle, 8 deg of pitching at 30 deg/s of spin)
// as a config written to dir/short.yaml, its truth Cm_alpha = -0.23,
// Cm_q = -5.5 and the parameter lines `terms` ("  name: value\n" each), with
// one segment "short": that truth's record with 0.01 deg of noise (seed
// `seed`, dir/data.csv), its six initial conditions free.
Case ShortRun(const std::string& dir,
              const std::string& terms,
              std::uint64_t seed);

// The short condition's sample times: 3 s at 10 points per cycle of its
// 1.55-Hz motion (0.0645 s apart).
std::vector<double> ShortRecordTimes();

// Whether a line of `fit`'s pipeline starts with `prefix`.
bool InPipeline(const FitResult& fit, const std::string& prefix);

// The samples `fit` was fitted to, one record per segment (as FitSamples
// takes them).
std::vector<TimeHistory> FittedSamples(const FitResult& fit);

// Runs the built fit3dof binary with the given arguments (shell-quoted by
// the caller where needed).
CommandResult RunFit3dof(const std::string& arguments);

}  // namespace fit3dof::testing

#endif  // FIT3DOF_TESTS_TEST_UTIL_H_
