// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// One run of a batch (batch_run.h).

#include "batch_run.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "config_node.h"
#include "fit3dof/atomic_file.h"
#include "fit3dof/config.h"
#include "fit3dof/diagnose.h"
#include "fit3dof/fit.h"
#include "fit3dof/fit_report.h"
#include "fit3dof/input_error.h"
#include "fit3dof/interrupt.h"
#include "fit3dof/version.h"
#include "json_values.h"
#include "report_json.h"

namespace fit3dof {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// The run's result from its fit, the parameters in the fit's order (the
// table's, then each segment's own initial conditions).
RunResult FromFit(const FitResult& fit) {
  RunResult r;
  r.name = fit.name;
  r.status = fit.converged ? RunStatus::kConverged : RunStatus::kNotConverged;
  r.reason = fit.converged ? "" : fit.termination;
  r.adequacy = fit.adequacy;
  r.iterations = fit.iterations;
  r.probable_error = fit.probable_error;
  r.model = ModelName(fit.model);
  for (const ParameterEstimate& e : fit.parameters) {
    const RunParameter parameter{
        e.name, e.value, e.rms_error, e.standard_error};
    r.values.push_back(parameter);
    if (e.free) r.free.push_back(parameter);
  }
  // The filter-error fit's intensities join the summary's columns
  // (process_noise_pitch, _se, _rms: both errors the curvature's).
  for (const ProcessNoiseEstimate& e : fit.process_noise) {
    r.free.push_back({"process_noise_" + e.axis,
                      e.intensity,
                      e.standard_error,
                      e.standard_error});
  }
  return r;
}

// The result of a run an earlier batch finished, from its report.json
// (read in file order: the parameters as the fit ordered them).
RunResult FromReport(const json& report) {
  RunResult r;
  r.name = report.value("name", "");
  const bool converged = report.value("converged", false);
  r.status = converged ? RunStatus::kConverged : RunStatus::kNotConverged;
  r.reason = converged ? "" : report.value("termination", "");
  if (report.contains("diagnosis")) r.reason = report["diagnosis"];
  r.adequacy = report.value("adequacy", "");
  r.iterations = report.value("iterations", 0);
  r.probable_error = NumberFromJson(report["probable_error"]);
  r.model = report.value("model", "");
  for (const auto& [name, p] : report["parameters"].items()) {
    const RunParameter parameter{name,
                                 NumberFromJson(p["value"]),
                                 NumberFromJson(p["rms_error"]),
                                 NumberFromJson(p["standard_error"])};
    r.values.push_back(parameter);
    if (p.value("free", false)) r.free.push_back(parameter);
  }
  // As FromFit: roll, pitch, yaw (not the JSON object's key order).
  for (const char* axis : {"roll", "pitch", "yaw"}) {
    if (!report.contains("process_noise") ||
        !report["process_noise"].contains(axis)) {
      continue;
    }
    const json& e = report["process_noise"][axis];
    r.free.push_back({std::string("process_noise_") + axis,
                      NumberFromJson(e["intensity"]),
                      NumberFromJson(e["standard_error"]),
                      NumberFromJson(e["standard_error"])});
  }
  return r;
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
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

// The earlier batch's result when --resume finds its report with the same
// key; false when there is none (or it is damaged) and the run must be done.
bool Resumed(const std::string& report_path,
             const std::string& key,
             RunResult* r) {
  if (!fs::exists(report_path)) return false;
  try {
    const json report = json::parse(ReadFile(report_path));
    if (report.value("resume_key", "") != key) return false;
    *r = FromReport(report);
    r->resumed = true;
    return true;
  } catch (const json::exception&) {
    return false;  // a damaged report: run again
  }
}

// Fits (or diagnoses) the run's case and writes its outputs into `dir`.
RunResult Perform(const RunSpec& spec,
                  const RunResult* predecessor,
                  const std::string& dir,
                  const std::string& key) {
  if (!spec.load_error.empty()) throw InputError(spec.load_error);
  if (predecessor != nullptr && predecessor->status == RunStatus::kFailed) {
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
    fit = d.FinalFit();
    for (const DiagnosisStep& step : d.steps) {
      diagnosis_note +=
          (diagnosis_note.empty() ? "added " : ", ") + step.effect;
    }
    diagnosis_note += std::string(diagnosis_note.empty() ? "" : "; ") +
                      VerdictToString(d.verdict);
  } else {
    fit = Fit(c);
  }
  json report = ReportObject(fit);
  report["config_hash"] = spec.hash;
  report["resume_key"] = key;
  if (!spec.start_from.empty()) report["start_from"] = spec.start_from;
  if (spec.diagnose) report["diagnosis"] = diagnosis_note;
  YAML::Emitter config;
  config << spec.config;
  WriteFileAtomically(dir + "/config.yaml", std::string(config.c_str()) + "\n");
  WriteFileAtomically(dir + "/fit.csv", FitComparisonCsv(fit));
  WriteFileAtomically(dir + "/report.json", report.dump(2) + "\n");
  fs::remove(dir + "/error.txt");
  RunResult r = FromFit(fit);
  if (spec.diagnose) r.reason = diagnosis_note;
  return r;
}

}  // namespace

RunResult ExecuteRun(const RunSpec& spec,
                     const RunResult* predecessor,
                     const BatchOptions& options) {
  const std::string dir = options.out_dir + "/" + spec.name;
  const std::string key = ResumeKey(spec, predecessor);
  RunResult r;
  if (options.resume && Resumed(dir + "/report.json", key, &r)) {
    // r is the earlier batch's
  } else {
    try {
      r = Perform(spec, predecessor, dir, key);
    } catch (const Interrupted&) {
      // Abandoned: nothing of this run is written; --resume redoes it.
      r.status = RunStatus::kInterrupted;
    } catch (const std::exception& e) {
      r.status = RunStatus::kFailed;
      r.reason = e.what();
      r.probable_error = kNaN;
      std::error_code ec;
      fs::remove(dir + "/report.json", ec);
      fs::remove(dir + "/fit.csv", ec);
      try {
        WriteFileAtomically(dir + "/error.txt", r.reason + "\n");
      } catch (const std::exception&) {
      }
    }
  }
  r.name = spec.name;
  r.resume_key = key;
  return r;
}

}  // namespace fit3dof
