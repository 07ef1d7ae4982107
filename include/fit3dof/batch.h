// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// `fit3dof batch`: a test campaign reduced by one command that can be rerun,
// resumed and spread over machines.
//
//   fit3dof batch MANIFEST --out_dir=DIR [--jobs=N] [--shard=K/N] [--resume]
//   fit3dof batch --merge DIR1 DIR2 ... --out_dir=DIR
//
// Runs execute in parallel on `jobs` threads, each into DIR/<name>/
// (report.json, fit.csv, config.yaml; error.txt when it failed). A run that
// fails never stops the others. DIR/summary.csv and DIR/summary.json hold
// one row per run, sorted by name: status (converged / not converged /
// failed), the reason, iterations, probable error, and the value and RMS
// error of every free parameter (columns <name> and <name>_rms).
//
// A run may take its starting values from an earlier run's result
// (`start_from: <run>`, the report's IUPDAT); it then waits for it. With
// `resume`, runs whose report exists for the same merged config (and the
// same predecessors) are not redone. `shard` K/N keeps only the K-th of N
// disjoint slices (stable by the name of each start_from chain's first
// run), so that a Slurm array or GNU parallel can share a campaign.

#ifndef FIT3DOF_BATCH_H_
#define FIT3DOF_BATCH_H_

#include <string>
#include <vector>

namespace fit3dof {

struct BatchOptions {
  std::string out_dir;
  int jobs = 0;    // 0: the thread budget (thread_budget.h; one per core
                   // unless --jobs set it); never more than the budget
  int shard = 1;   // K of --shard=K/N
  int shards = 1;  // N
  bool resume = false;
  bool progress = true;   // live progress line when stderr is a terminal
  std::string deck_data;  // data file for a NAMELIST deck's fitting groups
};

struct RunParameter {
  std::string name;
  double value = 0.0;
  double rms_error = 0.0;       // Eq. 27; NaN when not determined
  double standard_error = 0.0;  // the one to quote (fit.h); NaN likewise
};

// How a run of a batch ended.
enum class RunStatus {
  kConverged,
  kNotConverged,  // the fit ran and wrote its report, but did not converge
  kFailed,        // bad input or a motion that cannot be integrated
  kInterrupted,   // abandoned at a stop request; not in the summary
};

// "converged" | "not converged" | "failed" | "interrupted": the spelling of
// summary.csv and summary.json.
const char* RunStatusToString(RunStatus status);
// False (and *status untouched) for any other text.
bool StringToRunStatus(const std::string& text, RunStatus* status);

struct RunResult {
  std::string name;
  RunStatus status = RunStatus::kFailed;
  std::string reason;    // why it failed or did not converge
  std::string adequacy;  // of the fit's residuals (fit.h); empty if failed
  int iterations = 0;
  double probable_error = 0.0;       // NaN for a failed run
  std::vector<RunParameter> free;    // the free parameters
  std::vector<RunParameter> values;  // every parameter (for start_from)
  std::string model;
  bool resumed = false;    // taken from an earlier batch
  std::string resume_key;  // what --resume compares (data, config, version)
};

struct BatchSummary {
  std::vector<RunResult> runs;  // the finished runs, sorted by name
  int planned = 0;              // runs of this shard
  bool interrupted = false;     // stopped by Ctrl-C or SIGTERM
  int NumFailed() const;        // failed or not converged
};

// Runs the manifest (a YAML manifest, a directory of configs, a config or a
// NAMELIST deck) and writes summary.csv and summary.json of the runs that
// finished. Holds DIR/.fit3dof.lock meanwhile (a second batch into the same
// directory is an InputError; a lock left by a dead process is taken over).
// With `resume`, temporaries left by a killed run are removed and a run is
// kept only if its report was made from the same data bytes, merged config,
// start_from chain and fit3dof version. After a stop request
// (interrupt.h) no run is started, running ones are abandoned, and the
// summary holds what finished (`interrupted` set). Throws InputError when
// the manifest itself is unusable.
BatchSummary RunBatch(const std::string& manifest, const BatchOptions& options);

// summary.csv and summary.json in `dir`, written atomically.
void WriteSummary(const std::string& dir, const BatchSummary& summary);
BatchSummary ReadSummary(const std::string& dir);

// The runs of several shard outputs as one summary (names must not repeat).
BatchSummary MergeSummaries(const std::vector<BatchSummary>& parts);

// Parses "K/N" (1 <= K <= N); throws InputError.
void ParseShard(const std::string& text, int* shard, int* shards);

}  // namespace fit3dof

#endif  // FIT3DOF_BATCH_H_
