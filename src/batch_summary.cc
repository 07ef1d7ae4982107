// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A batch's summary (batch.h): summary.csv and summary.json written, read
// back for --merge, shards merged; and the run statuses' spellings.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "csv_field.h"
#include "fit3dof/atomic_file.h"
#include "fit3dof/batch.h"
#include "fit3dof/input_error.h"
#include "json_values.h"

namespace fit3dof {
namespace {

namespace fs = std::filesystem;
// Ordered: summary.json lists each run's parameters as the fit ordered
// them, and ReadSummary keeps that order for --merge.
using json = nlohmann::ordered_json;

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

std::string CsvNumber(double x) {
  if (!std::isfinite(x)) return "";
  char out[32];
  std::snprintf(out, sizeof(out), "%.12g", x);
  return out;
}

}  // namespace

const char* RunStatusToString(RunStatus status) {
  switch (status) {
    case RunStatus::kConverged:
      return "converged";
    case RunStatus::kNotConverged:
      return "not converged";
    case RunStatus::kFailed:
      return "failed";
    case RunStatus::kInterrupted:
      return "interrupted";
  }
  return "unknown";
}

bool StringToRunStatus(const std::string& text, RunStatus* status) {
  for (RunStatus s : {RunStatus::kConverged,
                      RunStatus::kNotConverged,
                      RunStatus::kFailed,
                      RunStatus::kInterrupted}) {
    if (text == RunStatusToString(s)) {
      *status = s;
      return true;
    }
  }
  return false;
}

int BatchSummary::NumFailed() const {
  int failed = 0;
  for (const RunResult& r : runs) failed += r.status != RunStatus::kConverged;
  return failed;
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
  std::string csv = "name,status,adequacy,reason,iterations,probable_error";
  // The standard error (the one to quote) leads; Eq. 27's RMS error beside.
  for (const std::string& c : columns) {
    csv += "," + c + "," + c + "_se," + c + "_rms";
  }
  csv += "\n";
  json runs = json::array();
  int converged = 0, not_converged = 0, failed = 0;
  for (const RunResult& r : summary.runs) {
    converged += r.status == RunStatus::kConverged;
    not_converged += r.status == RunStatus::kNotConverged;
    failed += r.status == RunStatus::kFailed;
    std::map<std::string, const RunParameter*> by_name;
    for (const RunParameter& p : r.free) by_name[p.name] = &p;
    const char* status = RunStatusToString(r.status);
    csv +=
        CsvField(r.name) + "," + status + "," + CsvField(r.adequacy) + "," +
        CsvField(r.reason) + "," +
        (r.status == RunStatus::kFailed ? "" : std::to_string(r.iterations)) +
        "," + CsvNumber(r.probable_error);
    json parameters = json::object();
    for (const std::string& c : columns) {
      const auto it = by_name.find(c);
      if (it == by_name.end()) {
        csv += ",,,";
        continue;
      }
      const RunParameter& p = *it->second;
      csv += "," + CsvNumber(p.value) + "," + CsvNumber(p.standard_error) +
             "," + CsvNumber(p.rms_error);
      parameters[c] = {
          {"value", JsonNumber(Round12(p.value))},
          {"standard_error", JsonNumber(Round12(p.standard_error))},
          {"rms_error", JsonNumber(Round12(p.rms_error))}};
    }
    csv += "\n";
    runs.push_back({{"name", r.name},
                    {"status", status},
                    {"adequacy", r.adequacy},
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
    std::ifstream file(path);
    in = json::parse(file);
  } catch (const json::exception& e) {
    throw InputError(path + ": not valid JSON: " + e.what());
  }
  BatchSummary summary;
  for (const json& run : in["runs"]) {
    RunResult r;
    r.name = run.value("name", "");
    const std::string status = run.value("status", "");
    if (!StringToRunStatus(status, &r.status)) {
      throw InputError(path + ": run '" + r.name + "': unknown status '" +
                       status + "'");
    }
    r.reason = run.value("reason", "");
    r.adequacy = run.value("adequacy", "");
    r.iterations = run.value("iterations", 0);
    r.probable_error = NumberFromJson(run["probable_error"]);
    r.model = run.value("model", "");
    for (const auto& [name, p] : run["parameters"].items()) {
      r.free.push_back({name,
                        NumberFromJson(p["value"]),
                        NumberFromJson(p["rms_error"]),
                        NumberFromJson(p["standard_error"])});
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
