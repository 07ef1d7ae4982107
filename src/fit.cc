// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Fit as an orchestrator (fit.h): read and screen the data once
// (fit_problem.h), starting values, the continuation pipeline
// (continuation.h) with restarts when it ends far above the noise
// (multi_start.h), error bars at the solution (uncertainty.h), then the
// post-fit wild-point screen and refit.

#include "fit3dof/fit.h"

#include <glog/logging.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "assembly.h"
#include "continuation.h"
#include "filter_error.h"
#include "fit3dof/angles.h"
#include "fit3dof/input_error.h"
#include "fit3dof/integration_step.h"
#include "fit3dof/interrupt.h"
#include "fit3dof/parameters.h"
#include "fit3dof/start_values.h"
#include "fit3dof/wild_points.h"
#include "fit_problem.h"
#include "format.h"
#include "line_statistics.h"
#include "multi_start.h"
#include "noise_relaxation.h"
#include "profile_error_bar.h"
#include "spectral_lines.h"
#include "uncertainty.h"

namespace fit3dof {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// Bad input that no solver could fix: nothing free, fewer residuals than
// free parameters.
void CheckSize(const Case& c, const FitProblem& p) {
  const int k = p.free.size();
  if (k == 0) {
    throw InputError(c.source +
                     ": parameters: every parameter is frozen; mark at least "
                     "one with free: true");
  }
  if (3 * p.points - k <= 0) {
    throw InputError(
        c.source + ": too few points: " + std::to_string(p.points) +
        " samples give " + std::to_string(3 * p.points) + " residuals for " +
        std::to_string(k) + " free parameters");
  }
}

// Starting values from the data for the free parameters given none
// (start_values.h), into problem->values; each named in `pipeline`.
void AutoStart(const Case& c,
               FitProblem* problem,
               std::vector<std::string>* pipeline) {
  const FreeLayout& free = problem->free;
  std::vector<bool> auto_start(c.parameters.size(), false);
  bool any_auto = false;
  for (int g = 0; g < free.size(); ++g) {
    if (free.segment[g] < 0 && c.parameters[free.position[g]].auto_start) {
      auto_start[free.position[g]] = true;
      any_auto = true;
    }
  }
  if (!any_auto) return;
  std::vector<double> full = c.Values();
  for (const std::string& line :
       EstimateStartValues(c, problem->segments[0].data, auto_start, &full)) {
    pipeline->push_back("starting value: " + line);
    VLOG(1) << c.name << ": starting value " << line;
  }
  for (int g = 0; g < free.size(); ++g) {
    if (free.segment[g] < 0 && auto_start[free.position[g]]) {
      problem->values[g] = full[free.position[g]];
    }
  }
}

// The pipeline from the starting values and, when it ends far above the
// noise level, the restarts; `values` gets the best solution. Fills the
// result's iteration counts, stages, multi-start figures and pipeline.
PipelineOutcome Solve(const Case& c,
                      const FitProblem& problem,
                      std::vector<double>* values,
                      FitResult* result) {
  const double limit = c.solver.max_probable_error;
  const bool plain =
      c.solver.method == FitMethod::kGaussNewton || !c.solver.continuation;
  const bool robust = !plain && c.solver.multi_start && c.solver.starts > 0;
  *values = problem.values;
  PipelineOutcome outcome = RunPipeline(c, problem, values);
  if (StopRequested()) throw Interrupted();
  if (!outcome.integrable) {
    const std::string message =
        "the motion cannot be integrated from the starting values (" +
        outcome.failure + ")";
    if (!robust || limit <= 0.0) {
      throw InputError(c.source + ": " + message + "; check the parameters");
    }
    // The robust pipeline restarts from the data instead.
    result->pipeline.push_back(message + ": restarting from the data");
    outcome.probable_error = std::numeric_limits<double>::infinity();
    *values = problem.values;
  }
  if (limit > 0.0 && outcome.probable_error > limit && robust) {
    const MultiStartOutcome m = RunMultiStart(c, problem, outcome);
    result->iterations += m.iterations;
    if (m.improved) {
      result->iterations += outcome.iterations;
      outcome = m.best;
      outcome.iterations = 0;  // counted among the restarts' already
      *values = m.values;
    } else if (!outcome.integrable) {
      throw InputError(c.source +
                       ": the motion cannot be integrated from the starting "
                       "values nor from any restart (" +
                       outcome.failure +
                       "); check the body and flow constants");
    }
    result->starts_tried = m.tried;
    result->starts_reached_best = m.reached;
    result->pipeline.push_back("multi-start: probable error " +
                               FormatNumber("%.3g", outcome.probable_error) +
                               " after " + std::to_string(m.tried) +
                               " starts, " + std::to_string(m.reached) +
                               " reached the best minimum");
  }
  if (robust && outcome.integrable) {
    const MultiStartOutcome b =
        RunBearingRestarts(c, problem, *values, outcome);
    result->iterations += b.iterations;
    if (b.tried > 0) {
      result->pipeline.push_back(
          "bearing_angle beyond the record's angles: restarted from " +
          std::to_string(b.tried - 1) + " angles within them" +
          (b.improved ? ", probable error " +
                            FormatNumber("%.3g", outcome.probable_error) +
                            " -> " + FormatNumber("%.3g", b.best.probable_error)
                      : ", none did better"));
    }
    if (b.improved) {
      result->iterations += outcome.iterations;
      outcome = b.best;
      outcome.iterations = 0;  // counted among the restarts' already
      *values = b.values;
    }
  }
  if (StopRequested()) throw Interrupted();
  result->iterations += outcome.iterations;
  result->failed_evaluations += outcome.failed_evaluations;
  result->stages = outcome.stages;
  if (result->stages.size() > 1) {
    result->pipeline.push_back(
        "continuation: " + std::to_string(result->stages.size()) +
        " stages up to the whole record");
  }
  return outcome;
}

// Converged by the solver's rule. A fit that ends above the noise level
// (probable error over solver.max_probable_error) may sit in a local
// minimum: it is called converged only when the restarts confirm its
// minimum (two or more starts reached it); residuals that are merely not
// white noise are the adequacy's business (JudgeAdequacy), not this.
void Judge(const Case& c, const PipelineOutcome& outcome, FitResult* result) {
  const double limit = c.solver.max_probable_error;
  result->converged = outcome.converged;
  result->termination = outcome.termination;
  const bool above = limit > 0.0 && outcome.probable_error > limit;
  const bool confirmed =
      result->starts_tried > 0 && result->starts_reached_best >= 2;
  // With sigma: auto the fit so far weighed the residuals by the noise the
  // data show without a model (StartNoiseWeights).
  const std::string sigma =
      c.AnySigmaAuto() ? "the data's model-free noise level" : "sigma";
  if (above && !confirmed) {
    result->converged = false;
    result->termination =
        "the fit did not reach the noise level: probable error " +
        FormatNumber("%.3g", outcome.probable_error) + " > " +
        FormatNumber("%g", limit) + " (a local minimum, a missing effect, or " +
        sigma + " smaller than the noise)";
  } else if (above) {
    result->termination +=
        "; the fit did not reach the noise level (probable error " +
        FormatNumber("%.3g", outcome.probable_error) + " > " +
        FormatNumber("%g", limit) + ") at the minimum " +
        std::to_string(result->starts_reached_best) + " of " +
        std::to_string(result->starts_tried) +
        " starts reached: not a local minimum; the residuals exceed " + sigma +
        " (see adequacy)";
  }
  if (!result->converged) {
    LOG(WARNING) << c.name << ": " << result->termination;
  }
}

// A tied parameter's estimate from its source's: the value is already the
// tie's, the errors scale with the factor.
void TieEstimate(const ParameterTie& tie,
                 std::vector<ParameterEstimate>* estimates) {
  auto at = [&](int position) -> ParameterEstimate* {
    for (ParameterEstimate& e : *estimates) {
      if (e.position == position && e.segment.empty()) return &e;
    }
    return nullptr;
  };
  ParameterEstimate* image = at(tie.image);
  const ParameterEstimate* source = at(tie.source);
  if (image == nullptr || source == nullptr) return;
  image->tied_to = source->name;
  image->tie_factor = tie.factor;
  image->rms_error = std::abs(tie.factor) * source->rms_error;
  image->standard_error = std::abs(tie.factor) * source->standard_error;
}

// An estimate for every parameter of the model in use; with several
// segments their own initial conditions follow in FitSegments.
std::vector<ParameterEstimate> Estimates(const Case& c,
                                         const FitProblem& problem,
                                         const std::vector<double>& values,
                                         const Uncertainty& u) {
  const FreeLayout& free = problem.free;
  const auto& table = ParameterTable(c.model);
  std::vector<double> final_values = c.Values();
  for (int g = 0; g < free.size(); ++g) {
    if (free.segment[g] < 0) final_values[free.position[g]] = values[g];
  }
  ApplyTies(free.ties, final_values.data());
  const bool several = problem.segments.size() > 1;
  std::vector<ParameterEstimate> estimates;
  for (int i = 0; i < NumParameters(c.model); ++i) {
    if (table[i].scaling == Scaling::kUnused) continue;
    if (IsInitialCondition(c.model, i) && several) continue;
    ParameterEstimate e;
    e.name = table[i].name;
    e.position = i;
    e.units = table[i].units;
    e.value = IsInitialCondition(c.model, i) ? problem.segments[0].base[i]
                                             : final_values[i];
    e.rms_error = kNaN;
    e.standard_error = kNaN;
    for (int g = 0; g < free.size(); ++g) {
      if (free.position[g] == i && free.segment[g] <= 0) {
        e.free = true;
        e.value = values[g];
        e.rms_error = u.rms[g];
        e.standard_error = u.standard_error[g];
      }
    }
    estimates.push_back(e);
  }
  for (const ParameterTie& tie : free.ties) TieEstimate(tie, &estimates);
  return estimates;
}

// Each segment's fitted initial conditions, computed motion and residual
// levels; with several segments their own initial conditions as estimates.
void FitSegments(const Case& c,
                 const FitProblem& problem,
                 const std::vector<double>& values,
                 const Uncertainty& u,
                 FitResult* result) {
  const FreeLayout& free = problem.free;
  const std::vector<double>& rms = u.rms;
  const Assembly assembly =
      Assemble(problem.segments, free, problem.model, values, u.scale);
  const int first = Layout(c.model).first_initial;
  double sum2[3] = {0, 0, 0};
  for (size_t s = 0; s < problem.segments.size(); ++s) {
    const PreparedSegment& p = problem.segments[s];
    const std::vector<double> full = SegmentFullValues(assembly, s);
    SegmentFit fit;
    fit.name = p.name;
    fit.data = p.data;
    fit.initial_from_data = p.from_data;
    fit.sigma_deg = p.sigma;
    assembly.costs[s]->ComputeAngles(full, &fit.computed, nullptr);
    for (int j = 0; j < 6; ++j) fit.initial[j] = full[first + j];
    double seg2[3] = {0, 0, 0};
    const double* measured[3] = {
        p.data.phi.data(), p.data.theta.data(), p.data.psi.data()};
    for (int i = 0; i < p.data.size(); ++i) {
      for (int ch = 0; ch < 3; ++ch) {
        const double d = fit.computed[3 * i + ch] - measured[ch][i];
        seg2[ch] += d * d;
        sum2[ch] += d * d;
      }
    }
    const double n = p.data.size();
    fit.rms_residual_deg = {
        std::sqrt(seg2[0] / n), std::sqrt(seg2[1] / n), std::sqrt(seg2[2] / n)};
    for (int ch = 0; ch < 3; ++ch) {
      const SeriesCorrelation& series = u.series[3 * s + ch];
      ResidualStatistics& stats = fit.channels[ch];
      // The maximum-likelihood noise level of the channel: its RMS
      // residual.
      stats.noise_sigma_deg = std::sqrt(seg2[ch] / n);
      stats.autocorrelation = series.normalized;
      stats.lag_window = series.lag_window;
      stats.ljung_box = series.ljung_box;
      stats.ljung_box_limit = series.ljung_box_limit;
      stats.ljung_box_lags = series.ljung_box_lags;
      stats.white = series.white;
      const double weight = p.sigma[ch];
      for (const ResidualLine& line : series.lines) {
        stats.error_lines.push_back({line.frequency_hz,
                                     line.amplitude * weight,
                                     line.kept_share,
                                     line.roll_harmonic,
                                     line.calibration_power});
      }
      const std::vector<double> residual = ChannelResidual(fit, ch);
      const double dt =
          (p.data.t.back() - p.data.t.front()) / std::max(1, p.data.size() - 1);
      for (const SpectralLine& line : ResidualLines(residual, dt)) {
        stats.spectral_lines_hz.push_back(line.frequency_hz);
      }
    }
    for (int g = 0; g < free.size() && problem.segments.size() > 1; ++g) {
      if (free.segment[g] != static_cast<int>(s)) continue;
      ParameterEstimate e;
      e.name = problem.names[g];
      e.segment = p.name;
      e.position = free.position[g];
      e.units = ParameterTable(c.model)[free.position[g]].units;
      e.value = values[g];
      e.rms_error = rms[g];
      e.standard_error = u.standard_error[g];
      e.free = true;
      result->parameters.push_back(e);
    }
    result->segments.push_back(std::move(fit));
  }
  const double n = problem.points;
  result->rms_residual_deg = {
      std::sqrt(sum2[0] / n), std::sqrt(sum2[1] / n), std::sqrt(sum2[2] / n)};
}

// A spectral line's frequency, named after the spin rate when it is one of
// its first harmonics (within 3%).
std::string LineName(double hz, double spin_hz) {
  std::string name = FormatNumber("%.3g", hz) + " Hz";
  for (int h = 1; h <= 3 && spin_hz > 0.0; ++h) {
    if (std::abs(hz - h * spin_hz) <= 0.03 * h * spin_hz) {
      return name +
             (h == 1 ? " = spin" : " = " + std::to_string(h) + " x spin");
    }
  }
  return name;
}

// How one segment's channel is not white, and the test that says so:
// "theta (Ljung-Box Q 86.2 over 20 lags, its 1% limit 37.6;
// autocorrelation 0.00 at lag 1, -0.62 at lag 3; spectral lines at 1.72 Hz
// = spin)". Q weighs every lag: quoting lag 1 alone, a pitch calibration
// error on a 3-s run read "not white noise (lag-1 autocorrelation 0.00 in
// theta)", its residual near a quarter of the sampling rate.
std::string Structure(const SegmentFit& s, int ch, bool several) {
  const ResidualStatistics& stats = s.channels[ch];
  const std::vector<double>& rho = stats.autocorrelation;
  std::string text = ChannelName(ch);
  if (several) text += " ('" + s.name + "')";
  text += " (Ljung-Box Q " + FormatNumber("%.3g", stats.ljung_box) + " over " +
          std::to_string(stats.ljung_box_lags) + " lags, its 1% limit " +
          FormatNumber("%.3g", stats.ljung_box_limit);
  if (!rho.empty()) {
    text += "; autocorrelation " + FormatNumber("%.2f", rho[0]) + " at lag 1";
    const auto strongest =
        std::max_element(rho.begin(), rho.end(), [](double a, double b) {
          return std::abs(a) < std::abs(b);
        });
    if (strongest != rho.begin()) {
      text += ", " + FormatNumber("%.2f", *strongest) + " at lag " +
              std::to_string(strongest - rho.begin() + 1);
    }
  }
  if (!stats.spectral_lines_hz.empty()) {
    text += "; spectral lines at ";
    for (size_t i = 0; i < stats.spectral_lines_hz.size(); ++i) {
      text += (i ? ", " : "") + LineName(stats.spectral_lines_hz[i], SpinHz(s));
    }
  }
  return text + ")";
}

// White residuals further from sigma than noise goes with chance 1e-3
// (the probable error, Eq. 26, is chi-square over its degrees of freedom):
// a sigma that is not the noise, which the RMS errors (Eq. 27, scaled by
// the probable error) allow for and the standard errors do not. Said
// because diagnose reads the size of the residuals in sigma: too small a
// sigma looks like a missing effect there, too large a one hides one.
void WarnOfSigma(const Case& c, FitResult* result) {
  if (c.AnySigmaAuto()) return;
  const double e2 = result->probable_error * result->probable_error;
  if (std::abs(e2 - 1.0) <=
      ProbableErrorSpread(result->points, result->free_parameters)) {
    return;
  }
  const ChannelValues& rms = result->rms_residual_deg;
  result->warnings.push_back(
      "the residuals are white but " +
      FormatNumber("%.3g", result->probable_error) + " times sigma (rms phi " +
      FormatNumber("%.3g", rms.phi) + ", theta " +
      FormatNumber("%.3g", rms.theta) + ", psi " +
      FormatNumber("%.3g", rms.psi) + " deg): " +
      (e2 > 1.0 ? "the noise is larger than configured, or an effect leaves "
                  "no structure"
                : "sigma is larger than the noise") +
      "; the RMS errors allow for it, and fit3dof diagnose reads residuals "
      "in sigma");
}

// An angle known to within 1 / kCurvedRidge of itself bends Cm_bearing's
// ridge by less than 10% over three errors (CheckRidges).
constexpr double kCurvedRidge = 30.0;
// The start of the warning on a bearing moment's ridge (CheckRidges).
constexpr char kBearingRidge[] = "bearing_angle = ";
// The pipeline's entry once a parameter's error bar is the profile's,
// after its name.
constexpr char kProfileEntry[] = "'s error bar from its profile";
// The pipeline's entry once the sweep along the bearing angle has widened
// a parameter's error bar (WidenAlongTheAngle), after its name.
constexpr char kSweepEntry[] = "'s error bar along the bearing angle";
// The stiffness a bearing moment trades with (bearing_moment.h: below its
// angle it is one, M_y = Cm_bearing alpha, M_z = -Cm_bearing beta), whose
// error bars its ridge widens too (CheckRidges).
constexpr const char* kTradedStiffness[] = {"Cm_alpha", "Cn_beta"};

// Whether `result`'s error bar of `name` is its profile's already.
bool Profiled(const FitResult& result, const std::string& name) {
  const std::string entry = name + kProfileEntry;
  return std::any_of(
      result.pipeline.begin(),
      result.pipeline.end(),
      [&](const std::string& p) { return p.rfind(entry, 0) == 0; });
}

// The warning on a bearing moment whose angle the record does not
// determine; `error_bar` says what Cm_bearing's error bar is.
std::string BearingRidgeWarning(const ParameterEstimate& moment,
                                const ParameterEstimate& angle,
                                const std::string& error_bar) {
  // The fade depends on the angle's square (bearing_moment.h): its sign
  // means nothing, the saturated moment has Cm_bearing's.
  const double size = std::abs(angle.value);
  return kBearingRidge + FormatNumber("%.3g", size) +
         (std::isnan(angle.standard_error)
              ? " deg (no error bar)"
              : " +- " + FormatNumber("%.2g", angle.standard_error) + " deg") +
         " is not determined by the record: Cm_bearing (" +
         FormatNumber("%.3g", moment.value) +
         ") is determined only with it, along a ridge where the saturated "
         "moment's coefficient, Cm_bearing x bearing_angle (" +
         FormatNumber("%.3g", moment.value * size * kDegree) +
         "), stays nearly fixed, and " + error_bar +
         "; freeze bearing_angle at a value the bearing's calibration gives, "
         "or quote the saturated moment";
}

// Both error bars of `e` times `scale`, and the pipeline's entry saying
// so: its name, `entry` (after the name), the `refits` it took and the
// factor.
void ScaleErrorBars(double scale,
                    const char* entry,
                    int refits,
                    ParameterEstimate* e,
                    FitResult* result) {
  e->rms_error *= scale;
  e->standard_error *= scale;
  result->pipeline.push_back(e->name + entry + ": " + std::to_string(refits) +
                             " refits, x" + FormatNumber("%.3g", scale));
}

// A parameter's error bars widened to its profile's (`profile`); the
// description for the warning.
std::string WidenToProfile(const ProfileErrorBar& profile,
                           ParameterEstimate* e,
                           FitResult* result) {
  const double linear = e->standard_error;
  ScaleErrorBars(profile.rms_error / profile.linear,
                 kProfileEntry,
                 profile.refits,
                 e,
                 result);
  return "its error bar is the profile's (" +
         FormatNumber("%.2g", e->standard_error) + ", refitted with " +
         e->name + " frozen out to +-" +
         FormatNumber("%.2g", profile.farthest) +
         (profile.bounded
              ? ""
              : ", where the sum of squares rose by less than E^2") +
         "), not the solution's curvature's (" + FormatNumber("%.2g", linear) +
         ")";
}

// Whether the residuals look like noise (FitResult::adequacy); a warning
// when they do not.
void JudgeAdequacy(const Case& c, FitResult* result) {
  std::string structured;
  for (const SegmentFit& s : result->segments) {
    for (int ch = 0; ch < 3; ++ch) {
      if (s.channels[ch].white) continue;
      structured += (structured.empty() ? "" : ", ") +
                    Structure(s, ch, result->segments.size() > 1);
    }
  }
  if (structured.empty()) {
    result->adequacy = "white";
    WarnOfSigma(c, result);
    return;
  }
  result->adequacy = "structured: " + structured;
  result->warnings.push_back(
      "the residuals are not white noise (" + structured +
      "): the standard errors allow for it; fit3dof diagnose " + c.source +
      " looks for a missing effect");
}

// Whether `fit` holds a free bearing moment on its curved ridge, where
// Cm_bearing's linear error bar cannot be trusted (CheckRidges);
// *undetermined: whether the record does not determine its angle.
bool OnBearingRidge(const FitResult& fit, bool* undetermined) {
  const ParameterEstimate* moment = SharedEstimate(fit, "Cm_bearing");
  const ParameterEstimate* angle = SharedEstimate(fit, "bearing_angle");
  if (moment == nullptr || angle == nullptr || !moment->free || !angle->free) {
    return false;
  }
  // An angle within two of its errors of zero is not determined: on a
  // pair of runs the bearing moment's angle fitted 2.2 +- 1.6 deg (truth 1)
  // and Cm_bearing -0.0020 +- 0.00025 (truth -0.0033) along the ridge.
  *undetermined = !(2.0 * angle->standard_error < std::abs(angle->value));
  // A determined angle still bends the ridge: saturated, Cm_bearing goes
  // as 1 / bearing_angle, and 3 errors of an angle known to r of itself
  // move it 1 / (1 - 3 r) times as far as the linear error bar says. Past
  // r = 1/30 (10%) the profile is taken; an 800-sample run's angle of 1.31
  // +- 0.12 deg (truth 1) put Cm_bearing 4.6 linear errors off.
  return *undetermined ||
         !(kCurvedRidge * angle->standard_error < std::abs(angle->value));
}

// The error bars of the stiffness a bearing moment on its ridge trades
// with (kTradedStiffness), free and not profiled yet, widened to their
// profiles' (WidenTradedStiffness); their names are added to *names. On a
// 3-s run with the moment saturating at 2 deg (Cm_bearing -0.0082), fitted
// at 0.71 +- 0.97 deg, Cm_alpha was -0.20131 +- 0.00028 against a truth of
// -0.20020 (4 errors): frozen there, the refit's sum of squares rose by 2.3
// E^2 (1.5 errors), the angle going to 2.35 deg; frozen 6.4 linear errors
// out, by 3.3 E^2. Its profile error bar is 0.0016. Returns, for the
// ridge's warning, what it widened ("; Cm_alpha's is its profile's too
// (...)"). Its refits start from the solution and from the nearest of
// `branches` (ProfileAcross).
std::string ProfileTradedStiffness(const Case& c,
                                   const std::vector<TimeHistory>& data,
                                   const std::vector<FitResult>& branches,
                                   FitResult* result,
                                   std::vector<std::string>* names) {
  std::string widened;
  for (const char* name : kTradedStiffness) {
    const ParameterEstimate* e = SharedEstimate(*result, name);
    ProfileErrorBar profile;
    if (e == nullptr || !e->free || Profiled(*result, name) ||
        !ProfileAcross(c, data, *result, name, branches, &profile) ||
        !(profile.rms_error > profile.linear)) {
      continue;
    }
    const double linear = e->standard_error;
    ParameterEstimate* widen =
        &result->parameters[e - result->parameters.data()];
    WidenToProfile(profile, widen, result);
    names->push_back(name);
    widened += "; " + std::string(name) + "'s is its profile's too (" +
               FormatNumber("%.2g", widen->standard_error) + ", not " +
               FormatNumber("%.2g", linear) + ")";
  }
  return widened;
}

// The sweep along the angle of `result` (SweepBearingAngle), up to the
// record's largest angle; false when there is none.
bool SweepTheAngle(const Case& c,
                   const std::vector<TimeHistory>& data,
                   const FitResult& result,
                   AngleSweep* sweep) {
  double largest = 0.0;
  for (const TimeHistory& d : data) {
    largest = std::max(largest, LargestTotalAngle(d));
  }
  return SweepBearingAngle(c, data, result, largest, sweep) &&
         sweep->highest > 0.0;
}

// Whether `fit`'s bearing angle (free: OnBearingRidge) is known to less
// than a factor of two within two of its errors (its standard error over a
// quarter of it, or none), as every angle the record does not determine
// is. The ridge's branches then part
// within the record's reach: on draw 173's pair of 3-s runs with a moment
// saturating at half a degree (Cm_bearing -0.00524), fitted at 2.83 +- 1.11
// deg and -0.00179 +- 0.00098 (its profile from the solution), Cm_bearing
// frozen farther out refitted the angle upward (9.4 deg at the truth's
// value, chi-square 7.3 up) where the branch below, the angle near 0.5 deg,
// fits the truth 5.0 up: the truth had been 3.5 errors off.
bool AngleLoose(const FitResult& fit) {
  const ParameterEstimate* angle = SharedEstimate(fit, "bearing_angle");
  return angle != nullptr &&
         !(4.0 * angle->standard_error < std::abs(angle->value));
}

// The error bars of every free shared parameter widened to cover the
// values the ridge passes through within three errors (`sweep`); their
// names are added to *names (once). Returns, for the ridge's warning,
// what it widened.
std::string WidenAlongTheAngle(const AngleSweep& sweep,
                               FitResult* result,
                               std::vector<std::string>* names) {
  std::string widened;
  for (size_t i = 0; i < result->parameters.size(); ++i) {
    ParameterEstimate& e = result->parameters[i];
    if (!(sweep.widths[i] > e.rms_error)) continue;
    ScaleErrorBars(
        sweep.widths[i] / e.rms_error, kSweepEntry, sweep.refits, &e, result);
    if (std::find(names->begin(), names->end(), e.name) == names->end()) {
      names->push_back(e.name);
    }
    widened += (widened.empty() ? "" : ", ") + e.name + " +- " +
               FormatNumber("%.2g", e.standard_error);
  }
  if (widened.empty()) return "";
  return "; with the angle frozen from " + FormatNumber("%.3g", sweep.lowest) +
         " to " + FormatNumber("%.3g", sweep.highest) +
         " deg the sum of squares stays within 9 E^2, and the error bars "
         "cover the values the ridge passes through there: " +
         widened;
}

}  // namespace

void CheckRidges(const Case& c,
                 const std::vector<TimeHistory>& data,
                 FitResult* result) {
  bool undetermined = false;
  if (!OnBearingRidge(*result, &undetermined)) return;
  const ParameterEstimate* moment = SharedEstimate(*result, "Cm_bearing");
  const ParameterEstimate* angle = SharedEstimate(*result, "bearing_angle");
  if (Profiled(*result, "Cm_bearing")) return;
  std::string error_bar =
      std::isnan(moment->standard_error)
          ? "it has no error bar of its own"
          : "its error bar from the solution's curvature (" +
                FormatNumber("%.2g", moment->standard_error) +
                ") is too short there";
  ProfileErrorBar profile;
  if (c.solver.profile_ridges &&
      ProfileOf(c, data, *result, "Cm_bearing", &profile)) {
    error_bar =
        WidenToProfile(profile,
                       &result->parameters[moment - result->parameters.data()],
                       result);
  }
  auto& warnings = result->warnings;
  warnings.erase(std::remove_if(warnings.begin(),
                                warnings.end(),
                                [](const std::string& w) {
                                  return w.rfind(kBearingRidge, 0) == 0;
                                }),
                 warnings.end());
  if (undetermined) {
    warnings.push_back(BearingRidgeWarning(*moment, *angle, error_bar));
  }
}

std::vector<std::string> WidenTradedStiffness(
    const Case& c, const std::vector<TimeHistory>& data, FitResult* fit) {
  bool undetermined = false;
  if (!OnBearingRidge(*fit, &undetermined)) return {};
  // Where the record lets the angle halve or double within two errors
  // (AngleLoose; one it does not determine too), the ridge has branches a
  // refit from the solution does not reach: swept first, so that the
  // profiles start from its probes too.
  AngleSweep sweep;
  const bool swept = AngleLoose(*fit) && SweepTheAngle(c, data, *fit, &sweep);
  const ParameterEstimate angle = *SharedEstimate(*fit, "bearing_angle");
  std::vector<std::string> widened;
  std::string text =
      ProfileTradedStiffness(c, data, sweep.probes, fit, &widened);
  if (swept) text += WidenAlongTheAngle(sweep, fit, &widened);
  if (text.empty()) return widened;
  // A determined angle has no ridge warning (CheckRidges) to carry what
  // its sweep widened: one of its own says so.
  if (swept && !undetermined) {
    fit->warnings.push_back(
        kBearingRidge + FormatNumber("%.3g", std::abs(angle.value)) + " +- " +
        FormatNumber("%.2g", angle.standard_error) +
        " deg may halve or double within two of its errors: Cm_bearing "
        "trades with it along a ridge whose branches a refit from the "
        "solution does not reach" +
        text);
    return widened;
  }
  for (std::string& w : fit->warnings) {
    if (w.rfind(kBearingRidge, 0) != 0) continue;
    // Before the advice at the warning's end (BearingRidgeWarning).
    const size_t advice = w.rfind("; freeze bearing_angle");
    w.insert(advice == std::string::npos ? w.size() : advice, text);
  }
  return widened;
}

namespace {

// A bearing moment's fade depends on its angle's square (bearing_moment.h),
// so a fit may end at either sign of the angle with one model. It is
// reported as its magnitude, so that fits of one model agree in sign:
// a diagnosis weighs several models' values together for its error bars,
// and a tool comparing against a saturation angle reads a negative one as
// far off (draw 37's Table 6 record: -0.917 +- 0.22 deg, truth 1). Flipped
// before the error bars are estimated, which then see the Jacobian's column
// flipped with it.
void AngleAsMagnitude(const FitProblem& problem, std::vector<double>* values) {
  const auto it =
      std::find(problem.names.begin(), problem.names.end(), "bearing_angle");
  if (it == problem.names.end()) return;
  double& angle = (*values)[it - problem.names.begin()];
  angle = std::abs(angle);
}

// FitSamples at c.solver.search_step, kept where its motion stays within
// kStepChiSquare of the motion at c.solver.step (integration_step.h).
// Where it does not, at the finer step where the distance, shrinking as
// the step's 8th power, is expected within a 16th of it, and so on; at
// c.solver.step last, as if no search step were given. On draw 149's pair
// of 3-s runs with a bearing moment, 16 of 282 fits (bearing moments
// switching over a hundredth of a degree) were 0.04-1.0 apart at 8 ms.
FitResult FitAtSearchStep(const Case& c, const std::vector<TimeHistory>& data) {
  Case at = c;
  at.solver.search_step = 0.0;
  double step = c.solver.search_step;
  double seconds = 0.0;  // of the fits not kept
  int iterations = 0;
  while (step > c.solver.step) {
    at.solver.step = step;
    // A motion the coarser step cannot integrate from the start (a stiff
    // moment) is the finer steps' to judge.
    double apart = std::numeric_limits<double>::infinity();
    try {
      FitResult fit = FitSamples(at, data);
      apart = StepChiSquare(c, data, fit, step);
      if (apart <= kStepChiSquare) {
        fit.step_chi_square = apart;
        fit.seconds += seconds;
        fit.iterations += iterations;
        return fit;
      }
      seconds += fit.seconds;
      iterations += fit.iterations;
    } catch (const InputError&) {
    }
    VLOG(1) << c.name << ": at the step of " << step << " s the motion is "
            << apart << " apart; fitted again at a finer one";
    do {
      step /= 2.0;
      apart /= 256.0;
    } while (step > c.solver.step && apart > kStepChiSquare / 16.0);
  }
  at.solver.step = c.solver.step;
  FitResult fit = FitSamples(at, data);
  fit.seconds += seconds;
  fit.iterations += iterations;
  return fit;
}

}  // namespace

FitResult FitSamples(const Case& c, const std::vector<TimeHistory>& data) {
  if (c.solver.search_step > c.solver.step &&
      c.solver.method != FitMethod::kFilterError) {
    return FitAtSearchStep(c, data);
  }
  const auto start_time = std::chrono::steady_clock::now();
  FitProblem problem = PrepareProblem(c, data);
  CheckSize(c, problem);
  StartNoiseWeights(c, &problem);
  FitResult result;
  result.name = c.name;
  result.model = c.model;
  result.step = c.solver.step;
  result.points = problem.points;
  result.free_parameters = problem.free.size();
  AutoStart(c, &problem, &result.pipeline);
  if (VLOG_IS_ON(1)) {
    std::ostringstream start;
    for (int g = 0; g < problem.free.size(); ++g) {
      start << " " << problem.names[g] << "=" << problem.values[g];
    }
    VLOG(1) << c.name << ": starting values" << start.str();
  }
  std::vector<double> values;
  if (c.solver.method == FitMethod::kFilterError) {
    // The segments keep the final filter's weights: the error bars below
    // are the held-gain filter's.
    Judge(c, SolveFilterError(c, &problem, &values, &result), &result);
  } else {
    Judge(c, Solve(c, problem, &values, &result), &result);
    const RelaxationOutcome relaxed = RelaxNoiseWeights(c, &problem, &values);
    if (relaxed.rounds > 0) {
      result.iterations += relaxed.iterations;
      result.pipeline.push_back(relaxed.summary);
    }
  }
  AngleAsMagnitude(problem, &values);
  const Uncertainty u = EstimateUncertainty(problem, values, c.source);
  result.sum_of_residuals = u.sum_of_residuals;
  result.probable_error = u.probable_error;
  result.warnings = u.warnings;
  result.correlation_names = problem.names;
  result.correlation = u.correlation;
  result.parameters = Estimates(c, problem, values, u);
  CheckRidges(c, data, &result);
  if (c.solver.profile_ridges) WidenTradedStiffness(c, data, &result);
  FitSegments(c, problem, values, u, &result);
  JudgeAdequacy(c, &result);
  result.seconds = std::chrono::duration<double>(
                       std::chrono::steady_clock::now() - start_time)
                       .count();
  return result;
}

namespace {

// Rounds of post-fit screening and refitting for rejecting segments.
constexpr int kWildPointRounds = 3;
// Wild points named one by one in the warnings; the rest only in the
// report's outliers.
constexpr int kWildPointWarnings = 10;

// "the data hold 2 wild points (first: ...); data: {outliers: reject}
// drops them", for a fit that failed with wild points in its data.
std::string WildPointSummary(const std::vector<Outlier>& outliers) {
  return "the data hold " + std::to_string(outliers.size()) + " wild point" +
         (outliers.size() == 1 ? "" : "s") +
         " (first: " + outliers[0].point.Describe() +
         "); data: {outliers: reject} drops them";
}

void ReportWildPoints(const Case& c,
                      const std::vector<Outlier>& outliers,
                      FitResult* result) {
  result->outliers = outliers;
  int dropped = 0;
  for (size_t j = 0; j < outliers.size(); ++j) {
    const Outlier& o = outliers[j];
    dropped += o.dropped;
    if (static_cast<int>(j) >= kWildPointWarnings) continue;
    result->warnings.push_back(
        "wild point" +
        (c.segments.size() > 1 ? " in segment '" + o.segment + "'" : "") +
        ": " + o.point.Describe() +
        (o.dropped ? "; dropped"
                   : "; kept (data: {outliers: reject} drops it)"));
  }
  if (static_cast<int>(outliers.size()) > kWildPointWarnings) {
    result->warnings.push_back(
        std::to_string(outliers.size() - kWildPointWarnings) +
        " more wild points (all in report.json's outliers)");
  }
  const int kept = static_cast<int>(outliers.size()) - dropped;
  const double limit = c.solver.max_probable_error;
  const bool above = limit > 0.0 && result->probable_error > limit;
  if (kept > 0 && (!result->converged || above)) {
    // Point at the data as well as at the model.
    result->termination += "; the data hold " + std::to_string(kept) +
                           " wild point" + (kept == 1 ? "" : "s") +
                           ", kept (see the warnings; data: {outliers: "
                           "reject} drops them)";
  }
  if (dropped > 0) {
    result->pipeline.push_back("wild points: " + std::to_string(dropped) +
                               " dropped (their samples left out of the "
                               "fit)");
  }
}

}  // namespace

std::vector<double> ChannelResidual(const SegmentFit& s, int ch) {
  const std::vector<double>& measured = s.data.channel(ch);
  std::vector<double> residual(measured.size());
  for (size_t i = 0; i < measured.size(); ++i) {
    residual[i] = s.computed[3 * i + ch] - measured[i];
  }
  return residual;
}

double SpinHz(const SegmentFit& s) {
  const int n = s.data.size();
  if (n < 2) return 0.0;
  const double duration = s.data.t.back() - s.data.t.front();
  if (!(duration > 0.0)) return 0.0;
  return std::abs(s.computed[3 * (n - 1)] - s.computed[0]) / 360.0 / duration;
}

const ParameterEstimate* SharedEstimate(
    const std::vector<ParameterEstimate>& estimates, const std::string& name) {
  for (const ParameterEstimate& e : estimates) {
    if (e.segment.empty() && e.name == name) return &e;
  }
  return nullptr;
}

const ParameterEstimate* SharedEstimate(const FitResult& result,
                                        const std::string& name) {
  return SharedEstimate(result.parameters, name);
}

Case CaseAtSolution(const Case& c, const FitResult& r) {
  // Positions index the program's own table (parameters.h).
  CHECK(r.model == c.model) << "a solution of the other program";
  Case at = c;
  for (const ParameterEstimate& e : r.parameters) {
    if (e.segment.empty() && !IsInitialCondition(c.model, e.position)) {
      at.parameters[e.position].value = e.value;
      at.parameters[e.position].auto_start = false;
    }
  }
  at.SettleTies();
  for (size_t s = 0; s < at.segments.size() && s < r.segments.size(); ++s) {
    at.segments[s].initial_conditions = InitialConditionMode::kGiven;
    for (int j = 0; j < 6; ++j) {
      at.segments[s].initial[j].value = r.segments[s].initial[j];
      at.segments[s].initial[j].auto_start = false;
    }
  }
  return at;
}

bool Linearize(const Case& c, Linearization* out) {
  std::vector<Outlier> outliers;
  return Linearize(c, ReadSegmentData(c, &outliers), out);
}

bool Linearize(const Case& c,
               const std::vector<TimeHistory>& data,
               Linearization* out) {
  const FitProblem p = PrepareProblem(c, data);
  Assembly a = Assemble(p.segments,
                        p.free,
                        p.model,
                        p.values,
                        std::vector<double>(p.free.size(), 1.0));
  out->names = p.names;
  out->positions = p.free.position;
  out->segments = p.free.segment;
  out->points = p.points;
  return Information(a, &out->jtj, &out->ressum, &out->jtr);
}

FitResult Fit(const Case& c) {
  if (c.segments.empty()) {
    throw InputError(c.source +
                     ": data: missing (a fit needs data: or segments:)");
  }
  std::vector<Outlier> outliers;
  std::vector<TimeHistory> data = ReadSegmentData(c, &outliers);
  FitResult result;
  try {
    result = FitSamples(c, data);
  } catch (const InputError& e) {
    if (outliers.empty()) throw;
    throw InputError(std::string(e.what()) + "; " + WildPointSummary(outliers));
  }
  // After the fit: residuals the fit cannot reach. A rejecting segment
  // drops them and the fit runs again from where it stopped (a wild point
  // that hid others can only show once it is gone; three rounds at most).
  // The residuals of a fit that did not reach the noise level are no
  // reference: the misfit, not the data, would be named.
  for (int round = 0; round < kWildPointRounds && result.converged; ++round) {
    bool refit = false;
    for (size_t s = 0; s < c.segments.size(); ++s) {
      const bool reject = c.segments[s].outliers == OutlierPolicy::kReject;
      std::vector<int> known;
      for (const Outlier& o : outliers) {
        if (o.segment == c.segments[s].name && !o.dropped) {
          known.push_back(o.point.sample);
        }
      }
      const SegmentFit& fit = result.segments[s];
      std::vector<int> drop;
      for (const WildPoint& w :
           ScreenResiduals(fit.data, fit.computed, known)) {
        outliers.push_back({c.segments[s].name, w, reject, true});
        if (reject) drop.push_back(w.sample);
      }
      if (!drop.empty()) {
        data[s] = DropSamples(fit.data, drop);
        refit = true;
      }
    }
    if (!refit) break;
    const double seconds = result.seconds;
    const int iterations = result.iterations;
    result = FitSamples(CaseAtSolution(c, result), data);
    result.seconds += seconds;
    result.iterations += iterations;
  }
  ReportWildPoints(c, outliers, &result);
  result.provenance = ProvenanceOf(c);
  return result;
}

}  // namespace fit3dof
