// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A Case is everything one run needs, already validated: the model and its
// constants, the parameter table (value and free/frozen, the report's
// AACON and NCON), the data segments, the residual weights, noise, solver
// and simulation options. Loading a YAML config (config.h) or a NAMELIST
// deck produces a Case; nothing downstream reads YAML.

#ifndef FIT3DOF_CASE_H_
#define FIT3DOF_CASE_H_

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "fit3dof/body.h"
#include "fit3dof/motion_model.h"
#include "fit3dof/parameters.h"
#include "fit3dof/random_moment.h"
#include "fit3dof/wild_points.h"

namespace fit3dof {

// A tie as the fitter applies it: values[image] = factor * values[source].
struct ParameterTie {
  int image = 0;
  int source = 0;
  double factor = 1.0;
};

struct ParameterSetting {
  double value = 0.0;
  bool free = false;        // the report's NCON(i) = 1
  bool auto_start = false;  // free without a value (or value: auto): the
                            // fit estimates a starting value from the data
  // A parameter tied to another (config: `Cn_beta: {tied: Cm_alpha,
  // factor: -1}`): it is not free and always holds tie_factor times the
  // value of the parameter at position tied_to, which is neither tied nor
  // an initial condition. The symmetric relations of an axisymmetric body
  // in the asymmetric program (model_conversion.h) are such ties: the
  // asymmetric fit then costs no more parameters than the symmetric one.
  int tied_to = -1;
  double tie_factor = 1.0;

  bool tied() const { return tied_to >= 0; }
  // The setting of `tie`'s image.
  static ParameterSetting Tied(const ParameterTie& tie);
};

inline ParameterSetting ParameterSetting::Tied(const ParameterTie& tie) {
  ParameterSetting p;
  p.tied_to = tie.source;
  p.tie_factor = tie.factor;
  return p;
}

// values[image] = factor * values[source] for every tie. T: double or a
// ceres::Jet, whose derivatives then follow the source's.
template <typename T>
void ApplyTies(const std::vector<ParameterTie>& ties, T* values) {
  for (const ParameterTie& tie : ties) {
    values[tie.image] = tie.factor * values[tie.source];
  }
}

// Per-channel numbers: sigma weights, noise levels, biases (degrees).
struct ChannelValues {
  double phi = 0.0;
  double theta = 0.0;
  double psi = 0.0;

  // Channel `ch`: 0 phi, 1 theta, 2 psi, the order of a record's columns
  // and of SegmentFit::computed, for loops over the three.
  double& operator[](int ch);
  double operator[](int ch) const;
};

// The report's PART: which samples of a record are used.
struct DataSelection {
  int start = 1;          // NSTART, 1-based first sample
  double fraction = 1.0;  // SAMPLE, fraction of the record after start
  int every = 1;          // NDELTA, use every n-th sample
  // Optional time window (s), applied before start/fraction/every.
  double t_start = -1e300;
  double t_end = 1e300;
};

enum class InitialConditionMode {
  kFromData,  // INLCON = 0: estimated from the data
  kGiven,     // INLCON != 0: as written in the parameters
};

// One data block: its own record and its own six initial-condition
// parameters; the aerodynamic and tunnel parameters are shared.
struct Segment {
  std::string name;
  std::string data_file;  // resolved against the config's directory
  DataSelection selection;
  InitialConditionMode initial_conditions = InitialConditionMode::kFromData;
  OutlierPolicy outliers = OutlierPolicy::kWarn;  // data: {outliers: ...}
  // The segment's initial-condition parameters, in the model's order
  // (Layout(model).first_initial + j).
  std::array<ParameterSetting, 6> initial;
};

struct NoiseOptions {
  bool enabled = false;  // NSESWH = 1
  ChannelValues sigma;   // SPHI, STHTA, SPSI
  ChannelValues bias;    // AMPHI, AMTHTA, AMPSI
  std::uint64_t seed = 1;
};

// solver.method: how the normal equations are stepped.
enum class FitMethod {
  kLevenbergMarquardt,  // damped, with continuation and multi-start
  kGaussNewton,         // the 1978 program's undamped full step
  kFilterError,         // process noise modelled (filter_error.h)
};

// process_noise: the random angular acceleration per axis that the
// filter-error fit allows for (filter_error.h), entering the motion as
// simulate's random moments do (MotionModel::Filter).
struct ProcessNoiseModel {
  // Per axis (roll, pitch, yaw): the intensity, the square root of the
  // acceleration's spectral density in deg/s^1.5 (over a time dt the rate
  // wanders by intensity sqrt(dt) deg/s); 0 for an axis left out.
  std::array<double, 3> intensity{{0.0, 0.0, 0.0}};
  std::array<bool, 3> estimated{{false, false, false}};  // auto

  bool enabled() const {
    return estimated[0] || estimated[1] || estimated[2] || intensity[0] > 0.0 ||
           intensity[1] > 0.0 || intensity[2] > 0.0;
  }
};
bool operator==(const ProcessNoiseModel& a, const ProcessNoiseModel& b);

// "levenberg_marquardt" | "gauss_newton"; the config's spelling.
const char* FitMethodToString(FitMethod method);
// False (and *method untouched) for any other text.
bool StringToFitMethod(const std::string& text, FitMethod* method);

struct SolverOptions {
  int max_iterations = 50;  // NITER
  double tolerance = 1e-6;  // BOUND, on the change of the probable error
  double step = 0.001;      // DTMIN, s
  // Fit growing windows of the record (about two cycles first, doubling)
  // before the whole of it; see fit.h.
  bool continuation = true;
  // levenberg_marquardt, or gauss_newton: the 1978 program's undamped full
  // step over the whole record (no continuation, no multi-start).
  FitMethod method = FitMethod::kLevenbergMarquardt;
  // A fit whose probable error stays above this is not called converged
  // (residuals more than this many sigmas); 0 disables the check.
  double max_probable_error = 3.0;
  bool multi_start = true;  // restart from a spread of points when above it
  int starts = 8;
  // Error bars along known curved ridges from the profile of the sum of
  // squares (fit.h, CheckRidges), at a few refits each. Not a config key:
  // diagnose turns it off for the fits of its search, whose decisions do
  // not read those error bars, and profiles the fits it reports.
  bool profile_ridges = true;
  // The start is the solution of a nearby model (diagnose's refits with an
  // effect more or less): Levenberg-Marquardt trusts the Gauss-Newton step
  // from the first iteration (stage_solver.h). Not a config key.
  bool from_solution = false;
  // With from_solution: the start's own probable error, evaluated first,
  // above this and the start is far after all (a model without an effect
  // the record needs): the fit takes the growing windows (continuation.h)
  // all the same. 0: never. Not a config key.
  double far_start = 0.0;
  // Also stop when an iteration lowers n ln(RSS), the fit's part of the
  // Bayesian information criterion (n residuals, RSS their weighted sum of
  // squares), by less than this (0: the probable error's rule alone). Not
  // a config key: diagnose's search judges its fits by BIC and needs no
  // finer answer (RefitFromSolution).
  double bic_tolerance = 0.0;
  // Also stop once the probable error falls below this (0: never). Not a
  // config key: diagnose asks of some fits only whether they reach the
  // noise level (diagnose_round.cc, UnionMayReachTheNoise). The whole
  // record's run also stops once it is out of reach of it: at the pace of
  // its last iterations, even kept up, the remaining ones would leave it
  // far above (stage_solver.h, kOutOfReachMargin).
  double stop_below = 0.0;
  // Integrate at this coarser step (s; 0 or at most `step`: at `step`).
  // Not a config key: diagnose sets it from its nominal fit (CoarsestStep,
  // integration_step.h). A fit at it is kept only where its motion stays
  // within kStepChiSquare of the motion at `step`, every value then within
  // 0.1 of its standard error of the fit at `step`; otherwise it is fitted
  // again at a finer step, at `step` last (FitSamples).
  double search_step = 0.0;
};

struct SimulateOptions {
  double dt = 0.0;        // DTGEN, s
  double duration = 0.0;  // s; or give samples
  int samples = 0;        // number of samples including t = 0
  // Random moments driving the motion (random_moment.h); none by default.
  ProcessNoiseOptions process_noise;

  // Number of samples the options describe.
  int NumSamples() const;
};

struct Case {
  std::string name;
  std::string source;  // the file it came from, for messages
  ModelKind model = ModelKind::kSymmetric;
  Incidence incidence = Incidence::kVelocityRatio;
  Body body;
  Flow flow;
  // One entry per parameter of ParameterTable(model). The initial-condition
  // entries are the defaults that segments start from.
  std::vector<ParameterSetting> parameters;
  std::vector<Segment> segments;
  // Residual weights, deg (SIGPHI, SIGTHA, SIGPSI).
  ChannelValues sigma{1.0, 1.0, 1.0};
  // sigma: auto (all channels or some): the weights of those channels are
  // each segment's own noise levels, estimated at the solution by
  // relaxation (fit.h), started from the noise the data show without a
  // model; `sigma` is not used for them.
  std::array<bool, 3> sigma_auto{{false, false, false}};
  NoiseOptions noise;
  SolverOptions solver;
  ProcessNoiseModel process_noise;  // with solver.method: filter_error
  SimulateOptions simulate;

  ModelSpec Spec() const;
  // Whether any channel's sigma is `auto`.
  bool AnySigmaAuto() const;
  // Every parameter's value, tied ones as their tie makes them.
  std::vector<double> Values() const;
  std::vector<bool> FreeFlags() const;
  // Free, or tied to a free parameter: the terms a fit varies (the active
  // set of the model it fits, motion_model.h).
  std::vector<bool> VaryingFlags() const;
  // The ties among the parameters.
  std::vector<ParameterTie> Ties() const;
  // Sets each tied parameter's stored value from its source's (after the
  // sources' values changed, e.g. at a fit's solution).
  void SettleTies();
};

// Member-wise equality; a Case's `source` (where it was read from) is not
// compared. Numbers compare exactly: a written and re-read config must give
// back the same doubles.
bool operator==(const ParameterSetting& a, const ParameterSetting& b);
bool operator==(const ChannelValues& a, const ChannelValues& b);
bool operator==(const DataSelection& a, const DataSelection& b);
bool operator==(const Segment& a, const Segment& b);
bool operator==(const NoiseOptions& a, const NoiseOptions& b);
bool operator==(const SolverOptions& a, const SolverOptions& b);
bool operator==(const SimulateOptions& a, const SimulateOptions& b);
bool operator==(const Case& a, const Case& b);

}  // namespace fit3dof

#endif  // FIT3DOF_CASE_H_
