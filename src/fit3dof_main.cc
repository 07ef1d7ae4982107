// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The command line. Thin: parses flags, calls the library, maps errors to
// exit codes (0 success, 1 the job ran but failed, 2 bad input).

#include <gflags/gflags.h>
#include <glog/logging.h>

#include <cstdio>
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
#include "fit3dof/simulator.h"
#include "fit3dof/time_history.h"

// clang-format off
DEFINE_string(out, "", "Output file (simulate: CSV of t, phi, theta, psi).");
DEFINE_string(out_dir, "", "Output directory (fit: report.json, fit.csv; batch: one per run).");
DEFINE_int32(jobs, 0, "batch: runs in parallel (0: one per core).");
DEFINE_string(shard, "1/1", "batch: run only the K-th of N slices, K/N.");
DEFINE_bool(resume, false, "batch: skip runs whose report exists for the same config.");
DEFINE_bool(merge, false, "batch: merge the summaries of shard output directories.");
DEFINE_bool(progress, true, "batch: live progress line on a terminal.");
DEFINE_string(data, "", "NAMELIST decks: the data file (CSV) the fitting groups use.");
DEFINE_int32(starts, 200, "basin: starting guesses drawn from the box.");
DEFINE_uint64(seed, 1, "basin: seed of the draws.");
DEFINE_string(methods, "gauss_newton,levenberg_marquardt,robust",
              "basin: methods to compare, comma-separated.");
// clang-format on

namespace fit3dof {
namespace {

constexpr char kUsage[] =
    "fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion\n"
    "\n"
    "  fit3dof simulate CONFIG --out=FILE.csv   motion from the config\n"
    "  fit3dof fit CONFIG --out_dir=DIR          fit the config's data\n"
    "  fit3dof batch MANIFEST --out_dir=DIR [--jobs=N] [--shard=K/N] "
    "[--resume]\n"
    "  fit3dof batch --merge DIR... --out_dir=DIR\n"
    "  fit3dof namelist DECK [--data=FILE.csv] [--out=FILE.yaml]\n"
    "  fit3dof basin CONFIG [--starts=200] [--methods=...] [--out=FILE.json]\n"
    "  fit3dof diagnose CONFIG --out_dir=DIR      find, name and add missing "
    "effects\n"
    "\n"
    "fit and batch also take a NAMELIST deck (with --data=FILE.csv).\n"
    "\n"
    "Exit status: 0 success, 1 the job ran but failed, 2 bad input.";

int Simulate(const std::vector<std::string>& args) {
  if (args.size() != 1) {
    throw InputError("simulate: expected one CONFIG argument");
  }
  if (FLAGS_out.empty())
    throw InputError("simulate: --out=FILE.csv is required");
  const Case c = LoadConfig(args[0]);
  const TimeHistory history = Simulate(c);
  WriteTimeHistory(FLAGS_out, history);
  LOG(INFO) << "wrote " << history.size() << " samples to " << FLAGS_out;
  return 0;
}

// --data as an absolute path (decks name it relative to where you are).
std::string DataFlag() {
  if (FLAGS_data.empty()) return "";
  return std::filesystem::absolute(FLAGS_data).lexically_normal().string();
}

int BatchCommand(const std::vector<std::string>& args) {
  if (FLAGS_out_dir.empty())
    throw InputError("batch: --out_dir=DIR is required");
  if (FLAGS_merge) {
    if (args.empty())
      throw InputError("batch --merge: expected shard output directories");
    std::vector<BatchSummary> parts;
    for (const std::string& dir : args) parts.push_back(ReadSummary(dir));
    const BatchSummary merged = MergeSummaries(parts);
    WriteSummary(FLAGS_out_dir, merged);
    std::cout << "merged " << merged.runs.size() << " runs from " << args.size()
              << " directories into " << FLAGS_out_dir << "\n";
    return merged.NumFailed() > 0 ? 1 : 0;
  }
  if (args.size() != 1)
    throw InputError("batch: expected one MANIFEST argument");
  BatchOptions options;
  options.out_dir = FLAGS_out_dir;
  options.jobs = FLAGS_jobs;
  options.resume = FLAGS_resume;
  options.progress = FLAGS_progress;
  options.deck_data = DataFlag();
  ParseShard(FLAGS_shard, &options.shard, &options.shards);
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
            << FLAGS_out_dir << "/summary.csv\n";
  for (const RunResult& r : summary.runs) {
    if (r.status != "converged") {
      std::cout << "  " << r.name << ": " << r.status << ": " << r.reason
                << "\n";
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
  if (FLAGS_out.empty()) {
    std::cout << yaml;
  } else {
    WriteFileAtomically(FLAGS_out, yaml);
  }
  return 0;
}

int BasinCommand(const std::vector<std::string>& args) {
  if (args.size() != 1) throw InputError("basin: expected one CONFIG argument");
  const Case c = IsDeckFile(args[0]) ? LoadDeckCase(args[0], DataFlag())
                                     : LoadConfig(args[0]);
  BasinOptions options;
  options.starts = FLAGS_starts;
  options.seed = FLAGS_seed;
  options.jobs = FLAGS_jobs;
  options.methods.clear();
  std::string methods = FLAGS_methods;
  for (size_t at = 0; at <= methods.size();) {
    const size_t comma = std::min(methods.find(',', at), methods.size());
    if (comma > at) options.methods.push_back(methods.substr(at, comma - at));
    at = comma + 1;
  }
  // Hundreds of deliberately poor fits: keep their warnings out of the way.
  FLAGS_minloglevel = std::max(FLAGS_minloglevel, 3);
  const BasinResult result = RunBasinStudy(c, options);
  std::cout << FormatBasin(result);
  if (!FLAGS_out.empty()) WriteFileAtomically(FLAGS_out, BasinJson(result));
  return 0;
}

int DiagnoseCommand(const std::vector<std::string>& args) {
  if (args.size() != 1)
    throw InputError("diagnose: expected one CONFIG argument");
  if (FLAGS_out_dir.empty())
    throw InputError("diagnose: --out_dir=DIR is required");
  const Case c = IsDeckFile(args[0]) ? LoadDeckCase(args[0], DataFlag())
                                     : LoadConfig(args[0]);
  const Diagnosis d = Diagnose(c, DiagnoseOptions());
  for (size_t i = 0; i < d.fits.size(); ++i) {
    WriteFitOutputs(FLAGS_out_dir + "/step" + std::to_string(i), d.fits[i]);
  }
  WriteFileAtomically(FLAGS_out_dir + "/final.yaml", CaseToYaml(d.final_case));
  WriteFileAtomically(FLAGS_out_dir + "/diagnosis.json", DiagnosisJson(d, c));
  std::cout << FormatDiagnosis(d, c.sigma)
            << "fits of each step: " << FLAGS_out_dir
            << "/step*/ (tools/plot draws them); rerun: " << FLAGS_out_dir
            << "/final.yaml\n";
  return d.final.at_noise_level ? 0 : 1;
}

int FitCommand(const std::vector<std::string>& args) {
  if (args.size() != 1) throw InputError("fit: expected one CONFIG argument");
  if (FLAGS_out_dir.empty()) throw InputError("fit: --out_dir=DIR is required");
  const Case c = IsDeckFile(args[0]) ? LoadDeckCase(args[0], DataFlag())
                                     : LoadConfig(args[0]);
  const FitResult result = Fit(c);
  WriteFitOutputs(FLAGS_out_dir, result);
  std::cout << FormatFitTable(result) << std::flush;
  return result.converged ? 0 : 1;
}

int Run(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << kUsage << "\n";
    return 2;
  }
  const std::string command = argv[1];
  std::vector<std::string> args(argv + 2, argv + argc);
  using Handler = int (*)(const std::vector<std::string>&);
  const std::map<std::string, Handler> commands = {
      {"simulate", &Simulate},
      {"fit", &FitCommand},
      {"batch", &BatchCommand},
      {"namelist", &NamelistCommand},
      {"basin", &BasinCommand},
      {"diagnose", &DiagnoseCommand},
  };
  const auto it = commands.find(command);
  if (it == commands.end()) {
    std::cerr << "fit3dof: unknown command '" << command << "'\n\n"
              << kUsage << "\n";
    return 2;
  }
  try {
    return it->second(args);
  } catch (const InputError& e) {
    std::cerr << "fit3dof: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "fit3dof: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace
}  // namespace fit3dof

// gflags exits with status 1 on an unknown flag; bad input is status 2.
bool KnownFlags(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--") break;
    if (arg.size() < 2 || arg[0] != '-') continue;
    arg = arg.substr(arg[1] == '-' ? 2 : 1);
    const std::string name = arg.substr(0, arg.find('='));
    gflags::CommandLineFlagInfo info;
    if (gflags::GetCommandLineFlagInfo(name.c_str(), &info)) continue;
    if (name.rfind("no", 0) == 0 &&
        gflags::GetCommandLineFlagInfo(name.substr(2).c_str(), &info) &&
        info.type == "bool") {
      continue;
    }
    std::cerr << "fit3dof: unknown flag '" << argv[i]
              << "' (fit3dof --help lists the flags)\n";
    return false;
  }
  return true;
}

int main(int argc, char** argv) {
  FLAGS_logtostderr = true;
  if (!KnownFlags(argc, argv)) return 2;
  gflags::SetUsageMessage(fit3dof::kUsage);
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  google::InitGoogleLogging(argv[0]);
  return fit3dof::Run(argc, argv);
}
