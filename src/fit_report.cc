// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// What a fit writes (fit_report.h): report.json, fit.csv and the table
// printed on the terminal.

#include "fit3dof/fit_report.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "csv_field.h"
#include "fit3dof/atomic_file.h"
#include "fit3dof/version.h"
#include "format.h"
#include "json_values.h"
#include "report_json.h"

namespace fit3dof {

using nlohmann::json;
using nlohmann::ordered_json;

namespace {

// Each channel's residual autocorrelation (lags 1..10), the lag window the
// standard errors used, and the whiteness verdict with its Ljung-Box test.
json ResidualsJson(const SegmentFit& s) {
  json out;
  for (int ch = 0; ch < 3; ++ch) {
    const ResidualStatistics& c = s.channels[ch];
    json lags = json::array();
    for (double rho : c.autocorrelation) lags.push_back(JsonNumber(rho));
    json lines = json::array();
    for (double hz : c.spectral_lines_hz) lines.push_back(JsonNumber(hz));
    json error_lines = json::array();
    for (const ErrorLine& e : c.error_lines) {
      error_lines.push_back({{"frequency_hz", JsonNumber(e.frequency_hz)},
                             {"amplitude_deg", JsonNumber(e.amplitude_deg)},
                             {"kept_share", JsonNumber(e.kept_share)},
                             {"roll_harmonic", e.roll_harmonic},
                             {"calibration_power", e.calibration_power}});
    }
    out[ChannelName(ch)] = {{"autocorrelation", lags},
                            {"lag_window", c.lag_window},
                            {"ljung_box", JsonNumber(c.ljung_box)},
                            {"ljung_box_limit", JsonNumber(c.ljung_box_limit)},
                            {"ljung_box_lags", c.ljung_box_lags},
                            {"white", c.white},
                            {"spectral_lines_hz", lines},
                            {"error_lines", error_lines}};
  }
  return out;
}

// Whether an estimate has error bars: free, or tied to a free parameter
// (its source's, times the factor).
bool HasErrorBars(const ParameterEstimate& e) {
  return e.free || !e.tied_to.empty();
}

}  // namespace

ordered_json ReportObject(const FitResult& r) {
  ordered_json report;
  report["name"] = r.name;
  report["model"] = ModelName(r.model);
  report["converged"] = r.converged;
  report["termination"] = r.termination;
  report["iterations"] = r.iterations;
  report["points"] = r.points;
  report["free_parameters"] = r.free_parameters;
  report["probable_error"] = JsonNumber(r.probable_error);
  report["sum_of_residuals"] = JsonNumber(r.sum_of_residuals);
  report["rms_residual_deg"] = JsonChannels(r.rms_residual_deg);
  report["noise_sigma_deg"] = JsonChannels(r.rms_residual_deg);
  report["adequacy"] = r.adequacy;
  ordered_json parameters = ordered_json::object();
  for (const ParameterEstimate& e : r.parameters) {
    parameters[e.name] = {
        {"value", JsonNumber(e.value)},
        {"standard_error",
         HasErrorBars(e) ? JsonNumber(e.standard_error) : json()},
        {"rms_error", HasErrorBars(e) ? JsonNumber(e.rms_error) : json()},
        {"free", e.free},
        {"units", e.units}};
    if (!e.segment.empty()) parameters[e.name]["segment"] = e.segment;
    if (!e.tied_to.empty()) {
      parameters[e.name]["tied_to"] = e.tied_to;
      parameters[e.name]["tie_factor"] = e.tie_factor;
    }
  }
  report["parameters"] = parameters;
  json matrix = json::array();
  for (int a = 0; a < r.correlation.rows(); ++a) {
    json row = json::array();
    for (int b = 0; b < r.correlation.cols(); ++b) {
      row.push_back(JsonNumber(r.correlation(a, b)));
    }
    matrix.push_back(row);
  }
  report["correlation"] = {{"names", r.correlation_names}, {"matrix", matrix}};
  report["warnings"] = r.warnings;
  report["outliers"] = OutliersJson(r.outliers);
  json segments = json::array();
  for (const SegmentFit& s : r.segments) {
    segments.push_back(
        {{"name", s.name},
         {"points", s.data.size()},
         {"t_start", s.data.t.front()},
         {"t_end", s.data.t.back()},
         {"initial_conditions", s.initial_from_data ? "from_data" : "given"},
         {"rms_residual_deg", JsonChannels(s.rms_residual_deg)},
         {"sigma_deg", JsonChannels(s.sigma_deg)},
         {"noise_sigma_deg",
          JsonChannels({s.channels[0].noise_sigma_deg,
                        s.channels[1].noise_sigma_deg,
                        s.channels[2].noise_sigma_deg})},
         {"residuals", ResidualsJson(s)}});
  }
  report["segments"] = segments;
  json stages = json::array();
  for (const FitResult::Stage& stage : r.stages) {
    stages.push_back(
        {{"points", stage.points}, {"iterations", stage.iterations}});
  }
  report["stages"] = stages;
  report["failed_evaluations"] = r.failed_evaluations;
  report["pipeline"] = r.pipeline;
  if (r.starts_tried > 0) {
    report["multi_start"] = {{"tried", r.starts_tried},
                             {"reached_best", r.starts_reached_best}};
  }
  report["seconds"] = r.seconds;
  // The step the motion was integrated at: in diagnose's step reports a
  // coarser search step, with how far its motion was from the config's.
  report["integration_step"] = r.step;
  if (r.step_chi_square > 0.0) report["step_chi_square"] = r.step_chi_square;
  if (!r.process_noise.empty()) {
    json noise = json::object();
    for (const ProcessNoiseEstimate& e : r.process_noise) {
      noise[e.axis] = {{"intensity", JsonNumber(e.intensity)},
                       {"standard_error", JsonNumber(e.standard_error)},
                       {"estimated", e.estimated},
                       {"units", "deg/s^1.5"}};
    }
    report["process_noise"] = noise;
  }
  json data = json::array();
  for (const DataFileRecord& f : r.provenance.data) {
    data.push_back({{"path", f.path},
                    {"sha256", f.sha256.empty() ? json() : json(f.sha256)},
                    {"bytes", f.bytes}});
  }
  report["provenance"] = {{"fit3dof_version", FIT3DOF_VERSION},
                          {"config", r.provenance.config},
                          {"data", data},
                          {"date", r.provenance.date},
                          {"command_line", r.provenance.command_line}};
  return report;
}

std::string ReportJson(const FitResult& r) {
  return ReportObject(r).dump(2) + "\n";
}

std::string FitComparisonCsv(const FitResult& r) {
  std::string out = "t,phi,phi_fit,theta,theta_fit,psi,psi_fit,segment\n";
  char line[256];
  for (const SegmentFit& s : r.segments) {
    for (int i = 0; i < s.data.size(); ++i) {
      std::snprintf(line,
                    sizeof(line),
                    "%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,",
                    s.data.t[i],
                    s.data.phi[i],
                    s.computed[3 * i],
                    s.data.theta[i],
                    s.computed[3 * i + 1],
                    s.data.psi[i],
                    s.computed[3 * i + 2]);
      out += line;
      out += CsvField(s.name) + "\n";
    }
  }
  return out;
}

namespace {

// An error bar as the table prints it.
std::string ErrorText(const ParameterEstimate& e, double error) {
  if (!HasErrorBars(e)) return "(frozen)";
  if (!std::isfinite(error)) return "undetermined";
  return FormatNumber("%.3g", error);
}

}  // namespace

std::string FormatFitTable(const FitResult& r) {
  std::string out;
  char line[256];
  std::snprintf(line,
                sizeof(line),
                "%s: %s model, %d points, %d free parameters, %s after %d "
                "iterations (%.3f s)\n",
                r.name.c_str(),
                ModelName(r.model),
                r.points,
                r.free_parameters,
                r.converged ? "converged" : "NOT CONVERGED",
                r.iterations,
                r.seconds);
  out += line;
  if (!r.converged) out += "  " + r.termination + "\n";
  std::snprintf(line,
                sizeof(line),
                "probable error %.4g   sum of residuals %.4g   rms residual "
                "(deg): phi %.4g  theta %.4g  psi %.4g\n\n",
                r.probable_error,
                r.sum_of_residuals,
                r.rms_residual_deg.phi,
                r.rms_residual_deg.theta,
                r.rms_residual_deg.psi);
  out += line;
  std::snprintf(line,
                sizeof(line),
                "  %-26s %15s %12s %12s  %s\n",
                "parameter",
                "value",
                "std error",
                "rms error",
                "units");
  out += line;
  for (const ParameterEstimate& e : r.parameters) {
    if (!HasErrorBars(e) && e.value == 0.0) continue;
    const std::string standard = ErrorText(e, e.standard_error);
    const std::string rms = ErrorText(e, e.rms_error);
    // A tied parameter says whose value it follows.
    const std::string units =
        e.tied_to.empty()
            ? e.units
            : e.units + "  (tied: " + FormatNumber("%g", e.tie_factor) + " x " +
                  e.tied_to + ")";
    std::snprintf(line,
                  sizeof(line),
                  "  %-26s %15.7g %12s %12s  %s\n",
                  e.name.c_str(),
                  e.value,
                  standard.c_str(),
                  HasErrorBars(e) ? rms.c_str() : "",
                  units.c_str());
    out += line;
  }
  if (!r.adequacy.empty() && r.adequacy != "white") {
    out += "residuals: " + r.adequacy + "\n";
  }
  for (const std::string& w : r.warnings) out += "warning: " + w + "\n";
  return out;
}

void WriteFitOutputs(const std::string& dir, const FitResult& result) {
  // Both texts first: a report that cannot be made leaves no fit.csv.
  const std::string csv = FitComparisonCsv(result);
  const std::string report = ReportJson(result);
  WriteFileAtomically(dir + "/fit.csv", csv);
  WriteFileAtomically(dir + "/report.json", report);
}

}  // namespace fit3dof
