// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/batch.h"

#include <fcntl.h>
#include <glog/logging.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "config_node.h"
#include "csv_field.h"
#include "fit3dof/atomic_file.h"
#include "fit3dof/config.h"
#include "fit3dof/diagnose.h"
#include "fit3dof/fit.h"
#include "fit3dof/fit_report.h"
#include "fit3dof/input_error.h"
#include "fit3dof/interrupt.h"
#include "fit3dof/thread_budget.h"
#include "fit3dof/version.h"
#include "json_values.h"
#include "manifest.h"

namespace fit3dof {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// Summaries carry 12 significant digits (report.json keeps every digit):
// runs computed on different threads can differ in the last bits (Eigen's
// vectorized reductions depend on where the heap puts a buffer), and a
// summary must not depend on how the batch was scheduled, resumed or
// sharded.
double Round12(double x) {
  if (!std::isfinite(x)) return x;
  char text[32];
  std::snprintf(text, sizeof(text), "%.12g", x);
  return std::strtod(text, nullptr);
}
double FromJson(const json& x) {
  return x.is_number() ? x.get<double>() : kNaN;
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

RunResult FromReport(const json& report) {
  RunResult r;
  r.name = report.value("name", "");
  const bool converged = report.value("converged", false);
  r.status = converged ? "converged" : "not converged";
  r.reason = converged ? "" : report.value("termination", "");
  if (report.contains("diagnosis")) r.reason = report["diagnosis"];
  r.iterations = report.value("iterations", 0);
  r.probable_error = FromJson(report["probable_error"]);
  r.model = report.value("model", "");
  for (const auto& [name, p] : report["parameters"].items()) {
    RunParameter parameter{
        name, FromJson(p["value"]), FromJson(p["rms_error"])};
    r.values.push_back(parameter);
    if (p.value("free", false)) r.free.push_back(parameter);
  }
  return r;
}

// The IUPDAT chain: a run starts from its predecessor's final values.
void ApplyStartValues(const RunResult& previous, Case* c) {
  if (previous.model != ModelName(c->model)) {
    throw InputError(c->source + ": start_from: run '" + previous.name +
                     "' used the " + previous.model + " model");
  }
  VLOG(1) << c->name << ": start_from " << previous.name << " with "
          << previous.values.size() << " values";
  for (const RunParameter& p : previous.values) {
    const int position = FindParameter(c->model, p.name);
    if (position < 0 || !std::isfinite(p.value)) continue;
    c->parameters[position].value = p.value;
    const int first = Layout(c->model).first_initial;
    if (IsInitialCondition(c->model, position)) {
      for (Segment& s : c->segments)
        s.initial[position - first].value = p.value;
    }
  }
}

// What a finished run's report must match to be kept by --resume: the
// merged config and its start_from chain (spec.hash), the bytes of every
// data file, the predecessor's own key and the fit3dof version.
std::string ResumeKey(const RunSpec& spec, const RunResult* predecessor) {
  std::string text = spec.hash + "\nfit3dof " FIT3DOF_VERSION "\n";
  for (const std::string& file : DataFiles(spec.config)) {
    text += file + " " + FileHash(file) + "\n";
  }
  if (predecessor != nullptr) text += "after " + predecessor->resume_key;
  return StableHash(text);
}

RunResult Execute(const RunSpec& spec,
                  const RunResult* predecessor,
                  const BatchOptions& options) {
  const std::string dir = options.out_dir + "/" + spec.name;
  const std::string report_path = dir + "/report.json";
  const std::string key = ResumeKey(spec, predecessor);
  if (options.resume && fs::exists(report_path)) {
    try {
      const json report = json::parse(ReadFile(report_path));
      if (report.value("resume_key", "") == key) {
        RunResult r = FromReport(report);
        r.name = spec.name;
        r.resumed = true;
        r.resume_key = key;
        return r;
      }
    } catch (const json::exception&) {
      // A damaged report: run again.
    }
  }
  RunResult r;
  r.name = spec.name;
  r.resume_key = key;
  try {
    if (!spec.load_error.empty()) throw InputError(spec.load_error);
    if (predecessor != nullptr && predecessor->status == "failed") {
      throw InputError("start_from: run '" + predecessor->name + "' failed (" +
                       predecessor->reason + ")");
    }
    Case c = ParseConfigNode(spec.config,
                             spec.source,
                             spec.base_dir,
                             spec.node_lines,
                             &spec.key_lines,
                             spec.label);
    c.name = spec.name;
    if (predecessor != nullptr) ApplyStartValues(*predecessor, &c);
    FitResult fit;
    std::string diagnosis_note;
    if (spec.diagnose) {
      // The discrepancy workflow: the run's report is its final fit.
      const Diagnosis d = Diagnose(c, DiagnoseOptions());
      for (size_t i = 0; i < d.fits.size(); ++i) {
        WriteFitOutputs(dir + "/step" + std::to_string(i), d.fits[i]);
      }
      WriteFileAtomically(dir + "/final.yaml", CaseToYaml(d.final_case));
      WriteFileAtomically(dir + "/diagnosis.json", DiagnosisJson(d, c));
      fit = d.fits.back();
      for (const DiagnosisStep& step : d.steps) {
        diagnosis_note +=
            (diagnosis_note.empty() ? "added " : ", ") + step.effect;
      }
      diagnosis_note += (diagnosis_note.empty() ? "" : "; ") + d.verdict;
    } else {
      fit = Fit(c);
    }
    json report = json::parse(ReportJson(fit));
    report["config_hash"] = spec.hash;
    report["resume_key"] = key;
    if (!spec.start_from.empty()) report["start_from"] = spec.start_from;
    if (spec.diagnose) report["diagnosis"] = diagnosis_note;
    YAML::Emitter config;
    config << spec.config;
    WriteFileAtomically(dir + "/config.yaml",
                        std::string(config.c_str()) + "\n");
    WriteFileAtomically(dir + "/fit.csv", FitComparisonCsv(fit));
    WriteFileAtomically(report_path, report.dump(2) + "\n");
    fs::remove(dir + "/error.txt");
    r = FromReport(report);
    r.name = spec.name;
    r.resume_key = key;
    if (spec.diagnose) r.reason = diagnosis_note;
  } catch (const Interrupted&) {
    // Abandoned: nothing of this run is written; --resume redoes it.
    r.status = "interrupted";
  } catch (const std::exception& e) {
    r.status = "failed";
    r.reason = e.what();
    r.probable_error = kNaN;
    std::error_code ec;
    fs::remove(report_path, ec);
    fs::remove(dir + "/fit.csv", ec);
    try {
      WriteFileAtomically(dir + "/error.txt", r.reason + "\n");
    } catch (const std::exception&) {
    }
  }
  return r;
}

std::string Clock(double seconds) {
  const int s = static_cast<int>(seconds + 0.5);
  char out[32];
  std::snprintf(
      out, sizeof(out), "%02d:%02d:%02d", s / 3600, (s / 60) % 60, s % 60);
  return out;
}

std::string CsvNumber(double x) {
  if (!std::isfinite(x)) return "";
  char out[32];
  std::snprintf(out, sizeof(out), "%.12g", x);
  return out;
}

// The output directory's lock (DIR/.fit3dof.lock, holding the pid): a
// second batch into the same directory would mix two campaigns. A lock
// whose process is gone is taken over.
class DirectoryLock {
 public:
  explicit DirectoryLock(const std::string& dir)
      : path_(dir + "/" + kBatchLockName) {
    for (int attempt = 0; attempt < 2; ++attempt) {
      const int fd =
          ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
      if (fd >= 0) {
        const std::string pid = std::to_string(::getpid()) + "\n";
        const bool written = ::write(fd, pid.data(), pid.size()) ==
                             static_cast<ssize_t>(pid.size());
        ::close(fd);
        if (!written) break;
        return;
      }
      if (errno != EEXIST) break;
      const long holder = std::atol(ReadFile(path_).c_str());
      if (holder > 0 &&
          (::kill(static_cast<pid_t>(holder), 0) == 0 || errno == EPERM)) {
        throw InputError(dir + ": another fit3dof batch (pid " +
                         std::to_string(holder) +
                         ") is writing into this directory (lock " + path_ +
                         "); wait for it or choose another --out_dir");
      }
      LOG(WARNING) << path_ << ": taking over the lock of pid " << holder
                   << ", which is gone";
      ::unlink(path_.c_str());
    }
    throw InputError(path_ +
                     ": cannot create the lock file: " + std::strerror(errno));
  }
  ~DirectoryLock() { ::unlink(path_.c_str()); }
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

 private:
  std::string path_;
};

// Temporaries left by a run that was killed mid-write.
void RemoveTemporaries(const std::string& dir) {
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec);
       !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    if (it->is_regular_file(ec) &&
        IsTemporaryFileName(it->path().filename().string())) {
      LOG(INFO) << "removing " << it->path().string()
                << " (left by an interrupted run)";
      fs::remove(it->path(), ec);
    }
  }
}

}  // namespace

int BatchSummary::NumFailed() const {
  int failed = 0;
  for (const RunResult& r : runs) failed += r.status != "converged";
  return failed;
}

void ParseShard(const std::string& text, int* shard, int* shards) {
  int k = 0, n = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%d/%d%c", &k, &n, &tail) != 2 || n < 1 ||
      k < 1 || k > n) {
    throw InputError("--shard=" + text + ": expected K/N with 1 <= K <= N");
  }
  *shard = k;
  *shards = n;
}

BatchSummary RunBatch(const std::string& manifest,
                      const BatchOptions& options) {
  if (options.out_dir.empty())
    throw InputError("batch: --out_dir=DIR is required");
  std::vector<RunSpec> all = LoadManifest(manifest, options.deck_data);
  std::vector<RunSpec> specs;
  for (const RunSpec& s : all) {
    const std::uint64_t h = std::stoull(StableHash(s.chain_root), nullptr, 16);
    if (static_cast<int>(h % options.shards) == options.shard - 1)
      specs.push_back(s);
  }
  std::map<std::string, int> index;
  for (size_t i = 0; i < specs.size(); ++i)
    index[specs[i].name] = static_cast<int>(i);
  const int n = static_cast<int>(specs.size());
  std::error_code ec;
  fs::create_directories(options.out_dir, ec);
  if (ec) {
    throw InputError(options.out_dir +
                     ": cannot create the output directory: " + ec.message());
  }
  const DirectoryLock lock(options.out_dir);
  if (options.resume) RemoveTemporaries(options.out_dir);

  enum State { kPending, kRunning, kDone };
  std::vector<State> state(n, kPending);
  std::vector<RunResult> results(n);
  std::mutex mutex;
  std::condition_variable changed;
  int running = 0, done = 0, failed = 0;
  const auto start = std::chrono::steady_clock::now();
  const bool tty = options.progress && ::isatty(STDERR_FILENO);

  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                         start)
        .count();
  };
  // Caller holds the mutex.
  auto show = [&] {
    if (!tty) return;
    const double t = elapsed();
    std::string eta = "--:--:--";
    if (done > 0) eta = Clock(t / done * (n - done));
    std::fprintf(
        stderr,
        "\r\033[K%d/%d done, %d running, %d failed, %s elapsed, ~%s left",
        done,
        n,
        running,
        failed,
        Clock(t).c_str(),
        eta.c_str());
    std::fflush(stderr);
  };
  auto ready = [&](int i) {
    if (state[i] != kPending) return false;
    const std::string& before = specs[i].start_from;
    return before.empty() || state[index.at(before)] == kDone;
  };

  auto worker = [&] {
    while (true) {
      int pick = -1;
      {
        std::unique_lock<std::mutex> guard(mutex);
        changed.wait(guard, [&] {
          pick = -1;
          if (StopRequested()) return true;
          bool pending = false;
          for (int i = 0; i < n && pick < 0; ++i) {
            pending |= state[i] == kPending;
            if (ready(i)) pick = i;
          }
          return pick >= 0 || !pending;
        });
        if (pick < 0) return;
        state[pick] = kRunning;
        ++running;
        show();
      }
      const RunSpec& spec = specs[pick];
      const RunResult* predecessor = spec.start_from.empty()
                                         ? nullptr
                                         : &results[index.at(spec.start_from)];
      RunResult result = Execute(spec, predecessor, options);
      {
        std::lock_guard<std::mutex> lock(mutex);
        results[pick] = std::move(result);
        state[pick] = kDone;
        --running;
        ++done;
        const RunResult& r = results[pick];
        if (r.status != "converged") ++failed;
        if (!tty) {
          LOG(INFO) << "[" << done << "/" << n << "] " << r.name << ": "
                    << r.status << (r.resumed ? " (resumed)" : "")
                    << (r.reason.empty() ? "" : " (" + r.reason + ")");
        }
        show();
      }
      changed.notify_all();
    }
  };

  // At most the budget's threads compute at once, whatever jobs says.
  int jobs = options.jobs > 0 ? std::min(options.jobs, ThreadBudget())
                              : ThreadBudget();
  jobs = std::max(1, std::min(jobs, std::max(n, 1)));
  std::atomic<bool> ticking{tty};
  std::thread ticker([&] {
    while (ticking) {
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
      std::lock_guard<std::mutex> lock(mutex);
      if (ticking) show();
    }
  });
  // Workers borrow their threads from the process's budget
  // (thread_budget.h), which the fits' multi-starts share.
  ParallelFor(jobs, [&](int) { worker(); });
  ticking = false;
  ticker.join();
  if (tty) std::fprintf(stderr, "\n");

  BatchSummary summary;
  summary.planned = n;
  summary.interrupted = StopRequested();
  for (int i = 0; i < n; ++i) {
    // What finished; runs not started or abandoned are left for --resume.
    if (state[i] == kDone && results[i].status != "interrupted") {
      summary.runs.push_back(results[i]);
    }
  }
  std::sort(
      summary.runs.begin(),
      summary.runs.end(),
      [](const RunResult& a, const RunResult& b) { return a.name < b.name; });
  LOG(INFO) << "batch: " << n << " runs, " << n - failed << " converged, "
            << failed << " failed or not converged, " << Clock(elapsed())
            << " (" << jobs << " jobs)";
  WriteSummary(options.out_dir, summary);
  return summary;
}

void WriteSummary(const std::string& dir, const BatchSummary& summary) {
  // Columns of the free parameters, in order of first appearance.
  std::vector<std::string> columns;
  std::set<std::string> seen;
  for (const RunResult& r : summary.runs) {
    for (const RunParameter& p : r.free) {
      if (seen.insert(p.name).second) columns.push_back(p.name);
    }
  }
  std::string csv = "name,status,reason,iterations,probable_error";
  for (const std::string& c : columns) csv += "," + c + "," + c + "_rms";
  csv += "\n";
  json runs = json::array();
  int converged = 0, not_converged = 0, failed = 0;
  for (const RunResult& r : summary.runs) {
    converged += r.status == "converged";
    not_converged += r.status == "not converged";
    failed += r.status == "failed";
    std::map<std::string, const RunParameter*> by_name;
    for (const RunParameter& p : r.free) by_name[p.name] = &p;
    csv += CsvField(r.name) + "," + r.status + "," + CsvField(r.reason) + "," +
           (r.status == "failed" ? "" : std::to_string(r.iterations)) + "," +
           CsvNumber(r.probable_error);
    json parameters = json::object();
    for (const std::string& c : columns) {
      const auto it = by_name.find(c);
      if (it == by_name.end()) {
        csv += ",,";
        continue;
      }
      csv += "," + CsvNumber(it->second->value) + "," +
             CsvNumber(it->second->rms_error);
      parameters[c] = {
          {"value", JsonNumber(Round12(it->second->value))},
          {"rms_error", JsonNumber(Round12(it->second->rms_error))}};
    }
    csv += "\n";
    runs.push_back({{"name", r.name},
                    {"status", r.status},
                    {"reason", r.reason},
                    {"iterations", r.iterations},
                    {"probable_error", JsonNumber(Round12(r.probable_error))},
                    {"model", r.model},
                    {"parameters", parameters}});
  }
  json out = {{"runs", runs},
              {"counts",
               {{"total", summary.runs.size()},
                {"converged", converged},
                {"not_converged", not_converged},
                {"failed", failed}}}};
  WriteFileAtomically(dir + "/summary.csv", csv);
  WriteFileAtomically(dir + "/summary.json", out.dump(2) + "\n");
}

BatchSummary ReadSummary(const std::string& dir) {
  const std::string path = dir + "/summary.json";
  if (!fs::exists(path))
    throw InputError(path + ": not found (not a batch output directory?)");
  json in;
  try {
    in = json::parse(ReadFile(path));
  } catch (const json::exception& e) {
    throw InputError(path + ": not valid JSON: " + e.what());
  }
  BatchSummary summary;
  for (const json& run : in["runs"]) {
    RunResult r;
    r.name = run.value("name", "");
    r.status = run.value("status", "");
    r.reason = run.value("reason", "");
    r.iterations = run.value("iterations", 0);
    r.probable_error = FromJson(run["probable_error"]);
    r.model = run.value("model", "");
    for (const auto& [name, p] : run["parameters"].items()) {
      r.free.push_back({name, FromJson(p["value"]), FromJson(p["rms_error"])});
    }
    summary.runs.push_back(r);
  }
  return summary;
}

BatchSummary MergeSummaries(const std::vector<BatchSummary>& parts) {
  BatchSummary merged;
  std::set<std::string> names;
  for (const BatchSummary& part : parts) {
    for (const RunResult& r : part.runs) {
      if (!names.insert(r.name).second) {
        throw InputError("batch --merge: run '" + r.name +
                         "' appears in two shards");
      }
      merged.runs.push_back(r);
    }
  }
  std::sort(
      merged.runs.begin(),
      merged.runs.end(),
      [](const RunResult& a, const RunResult& b) { return a.name < b.name; });
  return merged;
}

}  // namespace fit3dof
