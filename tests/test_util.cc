// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "test_util.h"

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "fit3dof/config.h"
#include "fit3dof/noise.h"
#include "fit3dof/simulator.h"

namespace fit3dof::testing {

namespace fs = std::filesystem;

const nlohmann::json& PaperResults() {
  static const nlohmann::json results = [] {
    std::ifstream in(SourcePath("tests/data/report_numbers.json"));
    if (!in)
      throw std::runtime_error("cannot read tests/data/report_numbers.json");
    return nlohmann::json::parse(in);
  }();
  return results;
}

bool PlainBuildOnly() {
  static const bool skips =
      kSanitized && std::getenv("FIT3DOF_SANITIZE_ALL") == nullptr;
  return skips;
}

std::string SourcePath(const std::string& relative) {
  return std::string(FIT3DOF_SOURCE_DIR) + "/" + relative;
}

std::string ScratchDirectory(const std::string& name) {
  const fs::path dir = fs::current_path() / "scratch" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

void WriteText(const std::string& path, const std::string& text) {
  const fs::path p(path);
  if (p.has_parent_path()) fs::create_directories(p.parent_path());
  std::ofstream out(path);
  out << text;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

CommandResult RunFit3dof(const std::string& arguments) {
  const std::string command =
      std::string(FIT3DOF_BINARY) + " " + arguments + " 2>&1";
  CommandResult result;
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0) {
    result.output.append(buffer, n);
  }
  const int status = ::pclose(pipe);
  result.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string WriteNoisyRecord(const Case& truth,
                             const std::vector<double>& times,
                             std::uint64_t seed,
                             const std::string& path) {
  TimeHistory data = SimulateAt(truth, truth.Values(), times);
  NoiseOptions noise;
  noise.enabled = true;
  noise.sigma = {0.01, 0.01, 0.01};
  noise.seed = seed;
  AddNoise(noise, &data);
  WriteTimeHistory(path, data);
  return path;
}

std::vector<double> ShortRecordTimes() {
  std::vector<double> times;
  for (double t = 0.0; t <= 3.0; t += 0.0645) times.push_back(t);
  return times;
}

bool InPipeline(const FitResult& fit, const std::string& prefix) {
  return std::any_of(
      fit.pipeline.begin(), fit.pipeline.end(), [&](const std::string& line) {
        return line.rfind(prefix, 0) == 0;
      });
}

std::vector<TimeHistory> FittedSamples(const FitResult& fit) {
  std::vector<TimeHistory> data;
  for (const SegmentFit& s : fit.segments) data.push_back(s.data);
  return data;
}

Case ShortRun(const std::string& dir,
              const std::string& terms,
              std::uint64_t seed) {
  const std::string config = dir + "/short.yaml";
  WriteText(config,
            "name: short\n"
            "model: symmetric\n"
            "body: {area: 0.3491, diameter: 0.6667, Ix: 0.0301, Iy: 0.2583}\n"
            "flow: {velocity: 2900.0, dynamic_pressure: 460.0}\n"
            "parameters:\n"
            "  Cm_alpha: -0.23\n"
            "  Cm_q: -5.5\n" +
                terms +
                "  phidot0: 30.0\n"
                "  theta0: 8.0\n"
                "sigma: {phi: 0.01, theta: 0.01, psi: 0.01}\n"
                "solver: {step: 0.002}\n");
  Case c = LoadConfig(config);
  std::vector<double> times;
  for (double t = 0.0; t <= 3.0; t += 0.06435) times.push_back(t);
  Segment s;
  s.name = "short";
  s.data_file = WriteNoisyRecord(c, times, seed, dir + "/data.csv");
  for (int j = 0; j < 6; ++j) s.initial[j].free = true;
  c.segments = {s};
  c.source = config;
  return c;
}

}  // namespace fit3dof::testing
