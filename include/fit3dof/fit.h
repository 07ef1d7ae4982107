// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The Chapman-Kirk fit of AEDC-TR-78-10 (Section 3.2) done with Ceres:
// every data segment is a residual block (segment_cost_function.h), the
// aerodynamic and tunnel parameters are shared between segments, each
// segment has its own initial conditions. Levenberg-Marquardt runs until the
// probable error changes by less than solver.tolerance between two
// iterations (the listing's BOUND) or solver.max_iterations (NITER) is
// reached; then
//
//   sum of residuals  S = sqrt(sum of squared weighted residuals)   Eq. 32
//   probable error    E = sqrt(S^2 / (3 N - N_free))               Eq. 26
//   RMS error         E sqrt(B_i), B = (J^T J)^-1                   Eq. 27
//
// with J the Jacobian of the weighted residuals, B from its singular values.
// Parameters that the data cannot separate (rank deficiency, or correlation
// above 0.99) are named in warnings together with the combination that is
// determined.
//
// Example Usage:
//
//   Case c = LoadConfig("run12.yaml");
//   FitResult result = Fit(c);
//   WriteFitOutputs("out/run12", result);

#ifndef FIT3DOF_FIT_H_
#define FIT3DOF_FIT_H_

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "fit3dof/case.h"
#include "fit3dof/provenance.h"
#include "fit3dof/time_history.h"
#include "fit3dof/wild_points.h"

namespace fit3dof {

struct ParameterEstimate {
  std::string name;     // report name; "segment.name" for a segment's own
                        // initial conditions when there are several segments
  std::string segment;  // empty for shared parameters
  int position = 0;     // in ParameterTable(model)
  double value = 0.0;
  double rms_error = 0.0;  // Eq. 27; NaN when frozen or not determined
  // The error bar to quote: with each channel's own noise level and
  // residual autocorrelation (colored residuals, Morelli and Klein 1995);
  // equal to rms_error for white residuals at the configured sigma. NaN
  // when frozen or not determined.
  double standard_error = 0.0;
  bool free = false;
  std::string units;
  // A tied parameter (case.h): the name of its source, and the factor.
  // Its value and errors are the source's times the factor (in size).
  std::string tied_to;
  double tie_factor = 1.0;
};

// A spectral line of a channel's error that the standard errors count
// whole (colored covariance): its frequency, the error's amplitude as
// estimated, and the share of it the fit left in the residual (0..1; the
// rest it absorbed into the estimates). A line locked to roll (phase
// h phi) gives its harmonic h and its mean frequency; a calibration term
// (the error as the channel's angle to the power p) gives p, no frequency,
// and as amplitude the error at the largest angle.
struct ErrorLine {
  double frequency_hz = 0.0;
  double amplitude_deg = 0.0;
  double kept_share = 1.0;
  int roll_harmonic = 0;      // h, or 0
  int calibration_power = 0;  // p, or 0
};

// One channel's residuals at the solution.
struct ResidualStatistics {
  double noise_sigma_deg = 0.0;         // the channel's noise level, estimated
  std::vector<double> autocorrelation;  // lags 1..10
  int lag_window = 0;  // lags the standard errors take into account
  // The Ljung-Box statistic Q over the first ljung_box_lags lags (20, or
  // half the samples if fewer) and its 1% critical value: white when Q
  // stays below it. Q weighs every lag, so residuals can fail it with a
  // lag-1 autocorrelation near zero (a line near a quarter of the
  // sampling rate).
  double ljung_box = 0.0;
  double ljung_box_limit = 0.0;
  int ljung_box_lags = 0;
  bool white = true;
  // Periodogram peaks above 4 ln N times the mean power (strongest first,
  // at most 3), then the largest one if it stands out of its own
  // neighbourhood only (the residual check's test).
  std::vector<double> spectral_lines_hz;
  std::vector<ErrorLine> error_lines;  // strongest first (at most 6)
};

struct SegmentFit {
  std::string name;
  TimeHistory data;              // the samples fitted (after selection, noise)
  std::vector<double> computed;  // phi, theta, psi per sample (deg)
  ChannelValues rms_residual_deg;
  ChannelValues sigma_deg;  // the residual weights used (sigma, or the
                            // estimated noise levels with sigma: auto)
  std::array<ResidualStatistics, 3> channels;  // phi, theta, psi
  std::array<double, 6> initial;               // the fitted initial conditions
  bool initial_from_data = false;
};

// A wild point found in a segment's data (wild_points.h).
struct Outlier {
  std::string segment;
  WildPoint point;
  bool dropped = false;    // the segment's policy is reject
  bool after_fit = false;  // found among the residuals, not in the raw data
};

// A process-noise intensity of the filter-error fit (filter_error.h):
// deg/s^1.5, the root of the random angular acceleration's spectral
// density.
struct ProcessNoiseEstimate {
  std::string axis;  // roll, pitch, yaw
  double intensity = 0.0;
  double standard_error = 0.0;  // NaN when given, not estimated
  bool estimated = false;
};

struct FitResult {
  std::string name;
  ModelKind model = ModelKind::kSymmetric;
  bool converged = false;
  int iterations = 0;       // of every attempt: stages, restarts, refits
  int points = 0;           // samples in all segments
  int free_parameters = 0;  // N_free
  double probable_error = 0.0;
  double sum_of_residuals = 0.0;
  ChannelValues rms_residual_deg;
  std::string termination;  // why the iteration stopped
  struct Stage {
    int points;      // samples in the stage's window
    int iterations;  // Levenberg-Marquardt iterations
  };
  std::vector<Stage> stages;  // continuation stages, the whole record last
  std::vector<std::string> pipeline;  // what ran: starting values,
                                      // continuation, multi-start
  int starts_tried = 0;               // multi-start (0: not needed)
  int starts_reached_best = 0;
  int failed_evaluations = 0;  // trial steps rejected because the motion
                               // blew up (theta near 90 deg, NaN)
  std::vector<ParameterEstimate> parameters;
  std::vector<std::string> correlation_names;  // free coordinates
  Eigen::MatrixXd correlation;                 // empty if not computable
  std::vector<std::string> warnings;
  // Whether the residuals look like measurement noise: "white", or how they
  // do not ("structured: theta (Ljung-Box Q 86.2 over 20 lags, its 1% limit
  // 37.6; autocorrelation 0.81 at lag 1) ..."). A fit
  // can converge (its iteration met the rule) and still not be adequate.
  std::string adequacy;
  // Every wild point found, in the order found; each is also a warning
  // (the first few) and a line of report.json's "outliers".
  std::vector<Outlier> outliers;
  std::vector<SegmentFit> segments;
  double seconds = 0.0;
  // The integration step the fit's motion took (s): the config's, or
  // solver.search_step where that served (then step_chi_square: how far
  // its motion was from the config's step's, StepChiSquare).
  double step = 0.0;
  double step_chi_square = 0.0;
  // Set by Fit (FitSamples reads no files and leaves it empty).
  Provenance provenance;
  // solver.method: filter_error only: the intensities per axis.
  std::vector<ProcessNoiseEstimate> process_noise;
};

// Fits the case's data. Wild points are screened for before the fit (in the
// raw samples) and after it (in the residuals); a segment whose policy is
// reject drops them and is fitted again. Throws InputError for bad input
// (missing data, too few points for the free parameters, nothing free, a motion
// that cannot be integrated from the starting values). A fit that does not
// converge returns normally with converged = false.
FitResult Fit(const Case& c);

// Fit without reading: the samples of each segment given (one record per
// segment of `c`, as ReadSegmentData returns them or a FitResult's
// segments hold them), no wild-point screen. Diagnose fits its candidates
// and its out-of-sample checks on the samples the first fit used. With
// c.solver.search_step (case.h), at that coarser step where the motion
// stays within kStepChiSquare of the motion at c.solver.step
// (integration_step.h), else at a finer one, at c.solver.step last;
// FitResult::step says which.
FitResult FitSamples(const Case& c, const std::vector<TimeHistory>& data);

// Error bars along the known curved ridges of the sum of squares: a
// bearing moment, where Cm_bearing is determined only along the ridge
// Cm_bearing x bearing_angle = const and its linear error bar (Eq. 27) sees
// only the ridge's width there. With c.solver.profile_ridges, Cm_bearing's
// error bars (RMS and standard) become its profile's
// (src/profile_error_bar.h: the fit repeated with Cm_bearing frozen on
// either side) when the angle's standard error exceeds 1/30 of it (the
// ridge bends by 10% over three errors). When the record does not
// determine the angle (zero within two standard errors, or no error), a
// warning names the ridge whether profiled or not. `fit` is the fit of
// case `c` to `data` (as FitSamples takes them). FitSamples calls it;
// diagnose, which fits without profiles while it searches, calls it on
// the fits it reports. A fit profiled already is left as it is.
void CheckRidges(const Case& c,
                 const std::vector<TimeHistory>& data,
                 FitResult* fit);

// Where CheckRidges finds the bearing moment on its ridge, the error bars
// of the stiffness the moment trades with below its angle (Cm_alpha and,
// asymmetric, Cn_beta; free, not profiled yet) widened to their profiles'
// where those are flatter than their linear error bars, and the ridge's
// warning saying so; returns the names widened. Where the record does not
// determine the angle, or lets it halve or double within two of its errors
// (its standard error over a quarter of it), the angle is swept first
// (src/profile_error_bar.h,
// SweepBearingAngle): those profiles refit from its probes too, and every
// free shared parameter's error bars widen to cover the values the ridge
// passes through within three errors (the angle's own included). FitSamples
// calls it with c.solver.profile_ridges; diagnose, whose decisions read the
// error bars of the models it reports, on its final model once it has decided.
std::vector<std::string> WidenTradedStiffness(
    const Case& c, const std::vector<TimeHistory>& data, FitResult* fit);

// The spin rate (Hz) of a segment's fitted motion, over the record.
double SpinHz(const SegmentFit& s);

// A segment's residual in channel `ch` (0 phi, 1 theta, 2 psi), deg per
// sample: computed minus measured.
std::vector<double> ChannelResidual(const SegmentFit& s, int ch);

// The estimate of the shared parameter (not a segment's own) named `name`,
// or null: in a fit's estimates, or in a list of them.
const ParameterEstimate* SharedEstimate(const FitResult& result,
                                        const std::string& name);
const ParameterEstimate* SharedEstimate(
    const std::vector<ParameterEstimate>& estimates, const std::string& name);

// The case with every free value at the fit's result and each segment's
// initial conditions given as fitted.
Case CaseAtSolution(const Case& c, const FitResult& result);

// The normal equations of the weighted residuals at the case's values (no
// solving): J^T J, J^T r and the residual sum of squares, with the free
// coordinates in the order of `names` (positions in ParameterTable, and
// the segment for initial conditions, -1 for shared ones).
struct Linearization {
  std::vector<std::string> names;
  std::vector<int> positions;
  std::vector<int> segments;
  Eigen::MatrixXd jtj;
  Eigen::VectorXd jtr;
  double ressum = 0.0;
  int points = 0;
};
// False when the motion cannot be integrated at the case's values. Reads
// the case's data (ReadSegmentData).
bool Linearize(const Case& c, Linearization* out);
// The same for samples already read: one record per segment of `c`, as
// ReadSegmentData returns them or a FitResult's segments hold them.
bool Linearize(const Case& c,
               const std::vector<TimeHistory>& data,
               Linearization* out);

// Each segment's samples as a fit uses them: read through its data
// selection (only the selected samples are kept), noise added (the seed
// advanced per segment) and screened for wild points (wild_points.h). The
// points found are appended to `outliers`; a segment whose policy is reject
// loses their samples. Throws InputError naming the config for an
// unreadable file or a selection of fewer than 2 samples.
std::vector<TimeHistory> ReadSegmentData(const Case& c,
                                         std::vector<Outlier>* outliers);

}  // namespace fit3dof

#endif  // FIT3DOF_FIT_H_
