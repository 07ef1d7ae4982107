// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The command line. Thin: parses flags, calls the library, maps errors to
// exit codes (0 success, 1 the job ran but failed, 2 bad input).

#include <gflags/gflags.h>
#include <glog/logging.h>

#include <cstdio>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "fit3dof/config.h"
#include "fit3dof/fit.h"
#include "fit3dof/fit_report.h"
#include "fit3dof/input_error.h"
#include "fit3dof/simulator.h"
#include "fit3dof/time_history.h"

// clang-format off
DEFINE_string(out, "", "Output file (simulate: CSV of t, phi, theta, psi).");
DEFINE_string(out_dir, "", "Output directory (fit: report.json, fit.csv).");
// clang-format on

namespace fit3dof {
namespace {

constexpr char kUsage[] =
    "fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion\n"
    "\n"
    "  fit3dof simulate CONFIG --out=FILE.csv   motion from the config\n"
    "  fit3dof fit CONFIG --out_dir=DIR          fit the config's data\n"
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

int FitCommand(const std::vector<std::string>& args) {
  if (args.size() != 1) throw InputError("fit: expected one CONFIG argument");
  if (FLAGS_out_dir.empty()) throw InputError("fit: --out_dir=DIR is required");
  const Case c = LoadConfig(args[0]);
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

int main(int argc, char** argv) {
  FLAGS_logtostderr = true;
  gflags::SetUsageMessage(fit3dof::kUsage);
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  google::InitGoogleLogging(argv[0]);
  return fit3dof::Run(argc, argv);
}
