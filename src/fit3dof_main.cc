// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The command line. Thin: parses flags, calls the library, maps errors to
// exit codes (0 success, 1 the job ran but failed, 2 bad input).

#include <glog/logging.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "fit3dof/atomic_file.h"
#include "fit3dof/basin.h"
#include "fit3dof/batch.h"
#include "fit3dof/config.h"
#include "fit3dof/diagnose.h"
#include "fit3dof/fit.h"
#include "fit3dof/fit_report.h"
#include "fit3dof/input_error.h"
#include "fit3dof/interrupt.h"
#include "fit3dof/namelist.h"
#include "fit3dof/progress.h"
#include "fit3dof/provenance.h"
#include "fit3dof/simulator.h"
#include "fit3dof/thread_budget.h"
#include "fit3dof/time_history.h"
#include "fit3dof/version.h"

namespace fit3dof {
namespace {

// Every flag of every command; each command accepts only its own (CLI11
// rejects the others with exit status 2).
struct Flags {
  std::vector<std::string> args;  // positional arguments
  std::string out;
  std::string out_dir;
  int jobs = 0;  // 0: not given (one per core)
  std::string shard = "1/1";
  bool resume = false;
  bool merge = false;
  bool progress = true;
  std::string data;
  int starts = 200;
  std::uint64_t seed = 1;
  std::string methods = "gauss_newton,levenberg_marquardt,robust";
  std::vector<std::string> absent;  // diagnose: effects known absent
  bool exact_step = false;          // diagnose: no coarser search step
};
Flags FLAGS;

int Simulate(const std::vector<std::string>& args) {
  if (args.size() != 1) {
    throw InputError("simulate: expected one CONFIG argument");
  }
  if (FLAGS.out.empty())
    throw InputError("simulate: --out=FILE.csv is required");
  const Case c = LoadConfig(args[0]);
  const TimeHistory history = Simulate(c);
  WriteTimeHistory(FLAGS.out, history);
  LOG(INFO) << "wrote " << history.size() << " samples to " << FLAGS.out;
  return 0;
}

// --data as an absolute path (decks name it relative to where you are).
std::string DataFlag() {
  if (FLAGS.data.empty()) return "";
  return std::filesystem::absolute(FLAGS.data).lexically_normal().string();
}

int BatchCommand(const std::vector<std::string>& args) {
  if (FLAGS.out_dir.empty())
    throw InputError("batch: --out_dir=DIR is required");
  if (FLAGS.merge) {
    if (args.empty())
      throw InputError("batch --merge: expected shard output directories");
    std::vector<BatchSummary> parts;
    for (const std::string& dir : args) parts.push_back(ReadSummary(dir));
    const BatchSummary merged = MergeSummaries(parts);
    WriteSummary(FLAGS.out_dir, merged);
    std::cout << "merged " << merged.runs.size() << " runs from " << args.size()
              << " directories into " << FLAGS.out_dir << "\n";
    return merged.NumFailed() > 0 ? 1 : 0;
  }
  if (args.size() != 1)
    throw InputError("batch: expected one MANIFEST argument");
  BatchOptions options;
  options.out_dir = FLAGS.out_dir;
  options.jobs = FLAGS.jobs;
  // Every thread of the batch (its runs and their multi-starts) comes from
  // one budget of --jobs threads.
  if (FLAGS.jobs > 0) SetThreadBudget(FLAGS.jobs);
  options.resume = FLAGS.resume;
  options.progress = FLAGS.progress;
  options.deck_data = DataFlag();
  ParseShard(FLAGS.shard, &options.shard, &options.shards);
  InstallStopHandlers();
  const BatchSummary summary = RunBatch(args[0], options);
  if (summary.interrupted) {
    std::cout << "interrupted: " << summary.runs.size() << " of "
              << summary.planned << " runs done; rerun with --resume\n";
    return 130;
  }
  int resumed = 0;
  for (const RunResult& r : summary.runs) resumed += r.resumed;
  std::cout << summary.runs.size() << " runs (" << resumed << " resumed), "
            << summary.runs.size() - summary.NumFailed() << " converged, "
            << summary.NumFailed() << " failed or not converged; summary in "
            << FLAGS.out_dir << "/summary.csv\n";
  for (const RunResult& r : summary.runs) {
    if (r.status != RunStatus::kConverged) {
      std::cout << "  " << r.name << ": " << RunStatusToString(r.status) << ": "
                << r.reason << "\n";
    }
  }
  return summary.NumFailed() > 0 ? 1 : 0;
}

int NamelistCommand(const std::vector<std::string>& args) {
  if (args.size() != 1)
    throw InputError("namelist: expected one DECK argument");
  const Deck deck = ReadDeck(args[0]);
  const std::string yaml = DeckToYaml(deck, DataFlag());
  for (const DeckRun& run : DeckRuns(deck, DataFlag())) {
    for (const std::string& v : run.ignored) {
      std::cerr << args[0] << " group " << run.group << ": " << v
                << " accepted and ignored\n";
    }
  }
  if (FLAGS.out.empty()) {
    std::cout << yaml;
  } else {
    WriteFileAtomically(FLAGS.out, yaml);
  }
  return 0;
}

int BasinCommand(const std::vector<std::string>& args) {
  if (args.size() != 1) throw InputError("basin: expected one CONFIG argument");
  const Case c = IsDeckFile(args[0]) ? LoadDeckCase(args[0], DataFlag())
                                     : LoadConfig(args[0]);
  BasinOptions options;
  options.starts = FLAGS.starts;
  options.seed = FLAGS.seed;
  if (FLAGS.jobs > 0) SetThreadBudget(FLAGS.jobs);
  options.methods.clear();
  std::string methods = FLAGS.methods;
  for (size_t at = 0; at <= methods.size();) {
    const size_t comma = std::min(methods.find(',', at), methods.size());
    if (comma > at) options.methods.push_back(methods.substr(at, comma - at));
    at = comma + 1;
  }
  // Hundreds of deliberately poor fits: keep their warnings out of the way.
  FLAGS_minloglevel = std::max(FLAGS_minloglevel, 3);
  BasinResult result;
  {
    ProgressLine progress("basin " + c.name);
    result = RunBasinStudy(c, options);
  }
  std::cout << FormatBasin(result);
  if (!FLAGS.out.empty()) WriteFileAtomically(FLAGS.out, BasinJson(result));
  return 0;
}

int DiagnoseCommand(const std::vector<std::string>& args) {
  if (args.size() != 1)
    throw InputError("diagnose: expected one CONFIG argument");
  if (FLAGS.out_dir.empty())
    throw InputError("diagnose: --out_dir=DIR is required");
  const Case c = IsDeckFile(args[0]) ? LoadDeckCase(args[0], DataFlag())
                                     : LoadConfig(args[0]);
  DiagnoseOptions options;
  options.absent = FLAGS.absent;
  options.coarse_search = !FLAGS.exact_step;
  Diagnosis d;
  {
    ProgressLine progress("diagnose " + c.name);
    d = Diagnose(c, options);
  }
  for (size_t i = 0; i < d.fits.size(); ++i) {
    WriteFitOutputs(FLAGS.out_dir + "/step" + std::to_string(i), d.fits[i]);
  }
  WriteFileAtomically(FLAGS.out_dir + "/final.yaml", CaseToYaml(d.final_case));
  WriteFileAtomically(FLAGS.out_dir + "/diagnosis.json", DiagnosisJson(d, c));
  std::cout << FormatDiagnosis(d, DiagnosedNoise(d, c.sigma))
            << "fits of each step: " << FLAGS.out_dir
            << "/step*/ (tools/plot draws them); rerun: " << FLAGS.out_dir
            << "/final.yaml\n";
  // docs/formats.md: 0 for a record explained (or at the noise level).
  return d.verdict == Verdict::kNoiseLevel || d.verdict == Verdict::kExplained
             ? 0
             : 1;
}

int FitCommand(const std::vector<std::string>& args) {
  if (args.size() != 1) throw InputError("fit: expected one CONFIG argument");
  if (FLAGS.out_dir.empty()) throw InputError("fit: --out_dir=DIR is required");
  const Case c = IsDeckFile(args[0]) ? LoadDeckCase(args[0], DataFlag())
                                     : LoadConfig(args[0]);
  FitResult result;
  {
    ProgressLine progress("fit " + c.name);
    result = Fit(c);
  }
  WriteFitOutputs(FLAGS.out_dir, result);
  std::cout << FormatFitTable(result) << std::flush;
  return result.converged ? 0 : 1;
}

using Handler = int (*)(const std::vector<std::string>&);

// Adds a command with its positional arguments and the flags it accepts.
// Nothing is marked required for CLI11: its required check runs before its
// unknown-flag check, and the handlers say what is missing themselves.
CLI::App* Command(CLI::App* app,
                  const char* name,
                  const char* description,
                  const char* positional) {
  CLI::App* sub = app->add_subcommand(name, description);
  sub->add_option(positional, FLAGS.args, positional);
  return sub;
}

void AddData(CLI::App* sub) {
  sub->add_option("--data",
                  FLAGS.data,
                  "NAMELIST decks: the data file (CSV) the fitting groups use");
}

void AddJobs(CLI::App* sub, const char* what) {
  sub->add_option("--jobs", FLAGS.jobs, what)->check(CLI::Range(1, 4096));
}

using Handlers = std::map<CLI::App*, Handler>;

void AddSimulateFitAndBatch(CLI::App* app, Handlers* handlers) {
  CLI::App* simulate = Command(app,
                               "simulate",
                               "motion from the config's parameters "
                               "(NSWTCH 1/2)",
                               "CONFIG");
  simulate->add_option("--out", FLAGS.out, "CSV of t, phi, theta, psi");
  (*handlers)[simulate] = &Simulate;

  CLI::App* fit =
      Command(app, "fit", "fit the config's data (NSWTCH 0)", "CONFIG");
  fit->add_option("--out_dir", FLAGS.out_dir, "report.json and fit.csv");
  AddData(fit);
  (*handlers)[fit] = &FitCommand;

  CLI::App* batch = app->add_subcommand(
      "batch",
      "reduce a campaign: a manifest, a directory of configs, a "
      "config or a deck (or --merge shard directories)");
  batch->add_option("MANIFEST", FLAGS.args, "MANIFEST, or DIR... with --merge");
  batch->add_option("--out_dir", FLAGS.out_dir, "one directory per run");
  AddJobs(batch, "runs in parallel (default: one per core)");
  batch->add_option("--shard", FLAGS.shard, "run only the K-th of N slices");
  batch->add_flag("--resume",
                  FLAGS.resume,
                  "skip runs whose report was made from the same data, "
                  "config and version");
  batch->add_flag("--merge",
                  FLAGS.merge,
                  "merge the summaries of shard output directories");
  batch->add_flag("--progress,!--noprogress",
                  FLAGS.progress,
                  "live progress line on a terminal (default true)");
  AddData(batch);
  (*handlers)[batch] = &BatchCommand;
}

void AddNamelistBasinAndDiagnose(CLI::App* app, Handlers* handlers) {
  CLI::App* namelist = Command(
      app, "namelist", "convert a legacy NAMELIST deck to YAML", "DECK");
  namelist->add_option("--out", FLAGS.out, "YAML file (default: stdout)");
  AddData(namelist);
  (*handlers)[namelist] = &NamelistCommand;

  CLI::App* basin = Command(app, "basin", "convergence-basin study", "CONFIG");
  basin->add_option("--starts", FLAGS.starts, "starting guesses drawn")
      ->check(CLI::Range(1, 1000000));
  basin->add_option("--seed", FLAGS.seed, "seed of the draws");
  basin->add_option("--methods",
                    FLAGS.methods,
                    "comma-separated: gauss_newton, levenberg_marquardt, "
                    "continuation, robust, filter_error");
  basin->add_option("--out", FLAGS.out, "JSON of the study");
  AddJobs(basin, "fits in parallel (default: one per core)");
  AddData(basin);
  (*handlers)[basin] = &BasinCommand;

  CLI::App* diagnose =
      Command(app, "diagnose", "find, name and add missing effects", "CONFIG");
  diagnose->add_option("--out_dir",
                       FLAGS.out_dir,
                       "each step's fit, diagnosis.json, final.yaml");
  diagnose
      ->add_option("--absent",
                   FLAGS.absent,
                   "catalog effects or probes known absent (ids, "
                   "comma-separated): never tried, never widen the error "
                   "bars")
      ->delimiter(',');
  diagnose->add_flag("--exact_step",
                     FLAGS.exact_step,
                     "integrate every fit at the config's solver.step (by "
                     "default the search takes the coarsest step within 0.1 "
                     "of each value's error of it)");
  AddData(diagnose);
  (*handlers)[diagnose] = &DiagnoseCommand;
}

// Parses the command line; false with the exit status in *status when the
// run ends here (help, version, or a parse error, reported on stderr).
bool Parse(CLI::App* app, int argc, char** argv, int* status) {
  try {
    app->parse(argc, argv);
    return true;
  } catch (const CLI::CallForHelp& e) {
    *status = app->exit(e);  // prints the help of the command asked; 0
  } catch (const CLI::CallForAllHelp& e) {
    *status = app->exit(e);
  } catch (const CLI::CallForVersion& e) {
    *status = app->exit(e);
  } catch (const CLI::ExtrasError& e) {
    // "The following argument(s) were not expected: --x --y"
    const std::string what = e.what();
    const size_t colon = what.find(": ");
    std::cerr << "fit3dof: unknown flag '"
              << (colon == std::string::npos ? what : what.substr(colon + 2))
              << "' for this command (fit3dof COMMAND --help lists its "
                 "flags)\n";
    *status = 2;
  } catch (const CLI::ParseError& e) {
    std::cerr << "fit3dof: " << e.what()
              << " (fit3dof --help lists the commands, fit3dof COMMAND "
                 "--help their flags)\n";
    *status = 2;
  }
  return false;
}

// `fit3dof help [COMMAND]`.
int Help(const CLI::App& app,
         const Handlers& handlers,
         const std::string& topic) {
  if (topic.empty()) {
    std::cout << app.help();
    return 0;
  }
  for (const auto& [sub, handler] : handlers) {
    if (sub->get_name() == topic) {
      std::cout << sub->help();
      return 0;
    }
  }
  std::cerr << "fit3dof: help: no command '" << topic << "'\n";
  return 2;
}

// Runs the command parsed; InputError is exit status 2, any other failure
// of the job 1.
int Dispatch(const Handlers& handlers) {
  for (const auto& [sub, handler] : handlers) {
    if (!sub->parsed()) continue;
    try {
      return handler(FLAGS.args);
    } catch (const InputError& e) {
      std::cerr << "fit3dof: " << e.what() << "\n";
      return 2;
    } catch (const std::exception& e) {
      std::cerr << "fit3dof: " << e.what() << "\n";
      return 1;
    }
  }
  return 2;  // unreachable: require_subcommand(1)
}

int Run(int argc, char** argv) {
  CLI::App app(
      "fit3dof " FIT3DOF_VERSION
      ": aerodynamic coefficients from 3DOF gas-bearing motion\n"
      "Exit status: 0 success, 1 the job ran but failed, 2 bad input, 130 "
      "interrupted.",
      "fit3dof");
  app.set_version_flag("--version", "fit3dof " FIT3DOF_VERSION);
  app.require_subcommand(1, 1);
  int verbosity = 0;
  app.add_option("-v,--v",
                 verbosity,
                 "log every iteration (1) like the report's listing")
      ->check(CLI::Range(0, 9));
  Handlers handlers;
  AddSimulateFitAndBatch(&app, &handlers);
  AddNamelistBasinAndDiagnose(&app, &handlers);
  CLI::App* help = app.add_subcommand("help", "help on a command");
  std::string topic;
  help->add_option("COMMAND", topic, "a command");

  bool known = argc < 2 || argv[1][0] == '-' || std::string(argv[1]) == "help";
  for (const auto& [sub, handler] : handlers) {
    known |= argc >= 2 && sub->get_name() == argv[1];
  }
  if (!known) {
    std::cerr << "fit3dof: unknown command '" << argv[1]
              << "' (fit3dof --help lists the commands)\n";
    return 2;
  }
  int status = 0;
  if (!Parse(&app, argc, argv, &status)) return status;
  FLAGS_v = verbosity;
  if (help->parsed()) return Help(app, handlers, topic);
  return Dispatch(handlers);
}

// Keeps the memory a fit frees for the next evaluation. A Jacobian of an
// 800-sample record (its sensitivities, and Ceres' compressed-row copy of
// it) takes a few hundred kilobytes, above glibc's threshold for serving a
// block from mmap and for trimming the heap: each evaluation had its
// buffers mapped afresh and page-faulted in, zeroed, and returned to the
// system (page faults were a tenth of a Table 6 diagnosis' cycles). Kept,
// the process holds at most its peak. Diagnoses alone, least of three
// interleaved runs (2026-11-30): two Table 6 triples 0.80x and 0.89x the
// time, 3-s runs and a pair of them within 2% (smaller buffers);
// diagnosis.json the same.
void KeepFreedMemory() {
#ifdef __GLIBC__
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
}

}  // namespace
}  // namespace fit3dof

int main(int argc, char** argv) {
  fit3dof::KeepFreedMemory();
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(argv[0]);
  fit3dof::SetCommandLine(argc, argv);
  return fit3dof::Run(argc, argv);
}
