// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Case's own methods (case.h): its model spec, parameter values and flags,
// and equality (the config writer's round trip is checked with it).

#include "fit3dof/case.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

namespace fit3dof {

const char* FitMethodToString(FitMethod method) {
  switch (method) {
    case FitMethod::kLevenbergMarquardt:
      return "levenberg_marquardt";
    case FitMethod::kGaussNewton:
      return "gauss_newton";
    case FitMethod::kFilterError:
      return "filter_error";
  }
  return "unknown";
}

bool StringToFitMethod(const std::string& text, FitMethod* method) {
  for (FitMethod m : {FitMethod::kLevenbergMarquardt,
                      FitMethod::kGaussNewton,
                      FitMethod::kFilterError}) {
    if (text == FitMethodToString(m)) {
      *method = m;
      return true;
    }
  }
  return false;
}

int SimulateOptions::NumSamples() const {
  if (samples > 0) return samples;
  if (dt <= 0.0) return 0;
  return static_cast<int>(std::floor(duration / dt + 1e-9)) + 1;
}

ModelSpec Case::Spec() const {
  ModelSpec spec;
  spec.model = model;
  spec.incidence = incidence;
  spec.body = body;
  spec.flow = flow;
  spec.max_step = solver.step;
  return spec;
}

std::vector<double> Case::Values() const {
  std::vector<double> values(parameters.size());
  for (size_t i = 0; i < parameters.size(); ++i)
    values[i] = parameters[i].value;
  ApplyTies(Ties(), values.data());
  return values;
}

bool Case::AnySigmaAuto() const {
  return std::any_of(
      sigma_auto.begin(), sigma_auto.end(), [](bool a) { return a; });
}

std::vector<bool> Case::FreeFlags() const {
  std::vector<bool> free(parameters.size());
  for (size_t i = 0; i < parameters.size(); ++i) free[i] = parameters[i].free;
  return free;
}

std::vector<bool> Case::VaryingFlags() const {
  std::vector<bool> varying = FreeFlags();
  for (const ParameterTie& tie : Ties()) {
    varying[tie.image] = parameters[tie.source].free;
  }
  return varying;
}

std::vector<ParameterTie> Case::Ties() const {
  std::vector<ParameterTie> ties;
  for (size_t i = 0; i < parameters.size(); ++i) {
    const ParameterSetting& p = parameters[i];
    if (!p.tied()) continue;
    CHECK(p.tied_to < static_cast<int>(parameters.size()) &&
          !parameters[p.tied_to].tied() && !p.free)
        << "parameter " << i << " tied to " << p.tied_to;
    ties.push_back({static_cast<int>(i), p.tied_to, p.tie_factor});
  }
  return ties;
}

void Case::SettleTies() {
  for (const ParameterTie& tie : Ties()) {
    parameters[tie.image].value = tie.factor * parameters[tie.source].value;
  }
}

namespace {

auto Tie(const Body& b) {
  return std::tie(b.area, b.diameter, b.Ix, b.Iy, b.Iz);
}
auto Tie(const Flow& f) { return std::tie(f.velocity, f.dynamic_pressure); }

}  // namespace

bool operator==(const ParameterSetting& a, const ParameterSetting& b) {
  return std::tie(a.value, a.free, a.auto_start, a.tied_to, a.tie_factor) ==
         std::tie(b.value, b.free, b.auto_start, b.tied_to, b.tie_factor);
}

double& ChannelValues::operator[](int ch) {
  CHECK(ch >= 0 && ch < 3) << "channel " << ch;
  return ch == 0 ? phi : ch == 1 ? theta : psi;
}

double ChannelValues::operator[](int ch) const {
  CHECK(ch >= 0 && ch < 3) << "channel " << ch;
  return ch == 0 ? phi : ch == 1 ? theta : psi;
}

bool operator==(const ChannelValues& a, const ChannelValues& b) {
  return std::tie(a.phi, a.theta, a.psi) == std::tie(b.phi, b.theta, b.psi);
}

bool operator==(const DataSelection& a, const DataSelection& b) {
  return std::tie(a.start, a.fraction, a.every, a.t_start, a.t_end) ==
         std::tie(b.start, b.fraction, b.every, b.t_start, b.t_end);
}

bool operator==(const Segment& a, const Segment& b) {
  return std::tie(a.name,
                  a.data_file,
                  a.selection,
                  a.initial_conditions,
                  a.outliers,
                  a.initial) == std::tie(b.name,
                                         b.data_file,
                                         b.selection,
                                         b.initial_conditions,
                                         b.outliers,
                                         b.initial);
}

bool operator==(const NoiseOptions& a, const NoiseOptions& b) {
  return std::tie(a.enabled, a.sigma, a.bias, a.seed) ==
         std::tie(b.enabled, b.sigma, b.bias, b.seed);
}

bool operator==(const SolverOptions& a, const SolverOptions& b) {
  return std::tie(a.max_iterations,
                  a.tolerance,
                  a.step,
                  a.continuation,
                  a.method,
                  a.max_probable_error,
                  a.multi_start,
                  a.starts,
                  a.profile_ridges,
                  a.from_solution,
                  a.far_start,
                  a.bic_tolerance,
                  a.stop_below,
                  a.search_step) == std::tie(b.max_iterations,
                                             b.tolerance,
                                             b.step,
                                             b.continuation,
                                             b.method,
                                             b.max_probable_error,
                                             b.multi_start,
                                             b.starts,
                                             b.profile_ridges,
                                             b.from_solution,
                                             b.far_start,
                                             b.bic_tolerance,
                                             b.stop_below,
                                             b.search_step);
}

bool operator==(const ProcessNoiseModel& a, const ProcessNoiseModel& b) {
  return std::tie(a.intensity, a.estimated) ==
         std::tie(b.intensity, b.estimated);
}

bool operator==(const SimulateOptions& a, const SimulateOptions& b) {
  return std::tie(a.dt, a.duration, a.samples, a.process_noise) ==
         std::tie(b.dt, b.duration, b.samples, b.process_noise);
}

// `source` (where the case was read from) is not part of what it is.
bool operator==(const Case& a, const Case& b) {
  return std::tie(a.name,
                  a.model,
                  a.incidence,
                  a.parameters,
                  a.segments,
                  a.sigma,
                  a.sigma_auto,
                  a.noise,
                  a.solver,
                  a.process_noise,
                  a.simulate) == std::tie(b.name,
                                          b.model,
                                          b.incidence,
                                          b.parameters,
                                          b.segments,
                                          b.sigma,
                                          b.sigma_auto,
                                          b.noise,
                                          b.solver,
                                          b.process_noise,
                                          b.simulate) &&
         Tie(a.body) == Tie(b.body) && Tie(a.flow) == Tie(b.flow);
}

}  // namespace fit3dof
