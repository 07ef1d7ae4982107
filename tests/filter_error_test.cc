// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The filter-error fit (solver: {method: filter_error}): without process
// noise it is output error; with random moments the model lacks it finds
// the truth within its error bars where output error does not, estimates
// the intensities, fits several segments jointly and reports it all.

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "fit3dof/batch.h"
#include "fit3dof/config.h"
#include "fit3dof/fit.h"
#include "fit3dof/fit_report.h"
#include "fit3dof/simulator.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "test_util.h"

namespace fit3dof {
namespace {

const ParameterEstimate& Find(const FitResult& r, const std::string& name) {
  for (const ParameterEstimate& e : r.parameters) {
    if (e.name == name) return e;
  }
  ADD_FAILURE() << "no parameter " << name;
  static ParameterEstimate none;
  return none;
}

// A sharp cone like Section 5.3's (q = 460 psf) at 100 samples per second,
// spinning at 300 deg/s with 6 deg of coning; the truth's coefficients.
constexpr char kCone[] = R"(name: cone
model: symmetric
incidence: velocity_ratio
body: {area: 0.3491, diameter: 0.6667, Ix: 0.0301, Iy: 0.2583}
flow: {velocity: 2900.0, dynamic_pressure: 460.0}
)";
constexpr double kCmAlpha = -0.23, kCmq = -5.5, kClp = -0.05;

// The truth's motion over `seconds` with random pitch and yaw moments of
// RMS `rms` (correlation time 0.05 s, seed `seed`), written to `path`.
void SimulateCone(double rms,
                  double seconds,
                  int seed,
                  const std::string& path) {
  const std::string text =
      std::string(kCone) +
      "parameters: {Cm_alpha: -0.23, Cm_q: -5.5, Cm_alpha_delta2: -1.13, "
      "Cl_p: -0.05, phidot0: 300, theta0: 6, psidot0: 40}\n"
      "initial_conditions: given\nsolver: {step: 0.002}\n"
      "simulate: {dt: 0.01, duration: " +
      std::to_string(seconds) +
      ", process_noise: {pitch: " + std::to_string(rms) +
      ", yaw: " + std::to_string(rms) +
      ", correlation_time: 0.05, seed: " + std::to_string(seed) + "}}\n";
  WriteTimeHistory(path, Simulate(ParseConfig(text, "motion.yaml", ".")));
}

// The fit of `data` (YAML for data: or segments:) from poor starting
// values, with 0.01 deg of noise added; filter error when `filter`.
Case ConeFit(const std::string& data, bool filter) {
  std::string text =
      std::string(kCone) +
      "parameters:\n"
      "  Cm_alpha: {value: -0.2, free: true}\n"
      "  Cm_q: {value: 0, free: true}\n"
      "  Cm_alpha_delta2: -1.13\n"
      "  Cl_p: {value: 0, free: true}\n"
      "  phi0: {free: true}\n  phidot0: {free: true}\n"
      "  theta0: {free: true}\n  thetadot0: {free: true}\n"
      "  psi0: {free: true}\n  psidot0: {free: true}\n"
      "initial_conditions: from_data\n" +
      data +
      "sigma: {phi: 0.01, theta: 0.01, psi: 0.01}\n"
      "noise: {sigma: {phi: 0.01, theta: 0.01, psi: 0.01}, seed: 3}\n";
  if (filter) {
    text +=
        "solver: {step: 0.002, tolerance: 1.0e-6, method: filter_error}\n"
        "process_noise: {roll: auto, pitch: auto, yaw: auto}\n";
  } else {
    text += "solver: {step: 0.002, tolerance: 1.0e-6}\n";
  }
  return ParseConfig(text, "fit.yaml", ".");
}

// How many standard errors the estimate lies from the truth.
double Off(const FitResult& r, const std::string& name, double truth) {
  const ParameterEstimate& e = Find(r, name);
  return std::abs(e.value - truth) / e.standard_error;
}

TEST(FilterError, WithoutProcessNoiseItIsOutputError) {
  const std::string dir = testing::ScratchDirectory("filter_error_plain");
  SimulateCone(0.0, testing::kSanitized ? 1.0 : 3.0, 1, dir + "/plain.csv");
  const std::string data = "data: {file: " + dir + "/plain.csv}\n";
  const FitResult oe = Fit(ConeFit(data, false));
  const FitResult fe = Fit(ConeFit(data, true));
  ASSERT_TRUE(oe.converged) << oe.termination;
  ASSERT_TRUE(fe.converged) << fe.termination;
  for (const char* name : {"Cm_alpha", "Cm_q", "Cl_p", "thetadot0"}) {
    const ParameterEstimate& a = Find(oe, name);
    const ParameterEstimate& b = Find(fe, name);
    EXPECT_LT(std::abs(a.value - b.value), 0.1 * a.standard_error) << name;
    EXPECT_NEAR(b.standard_error / a.standard_error, 1.0, 0.05) << name;
  }
  // No intensity found on any axis: reported as none.
  ASSERT_EQ(fe.process_noise.size(), 3u);
  for (const ProcessNoiseEstimate& p : fe.process_noise) {
    EXPECT_TRUE(p.estimated) << p.axis;
    EXPECT_EQ(p.intensity, 0.0) << p.axis;
  }
}

TEST(FilterError, FindsTheTruthWhereOutputErrorCannot) {
  const std::string dir = testing::ScratchDirectory("filter_error_noise");
  // The sanitized build runs the code paths on a shorter record; the
  // statistics are checked by the plain build.
  SimulateCone(3e-4, testing::kSanitized ? 1.5 : 8.0, 11, dir + "/noisy.csv");
  const std::string data = "data: {file: " + dir + "/noisy.csv}\n";
  const FitResult oe = Fit(ConeFit(data, false));
  const FitResult fe = Fit(ConeFit(data, true));
  ASSERT_TRUE(fe.converged) << fe.termination;
  ASSERT_EQ(fe.process_noise.size(), 3u);
  if (testing::kSanitized) return;
  EXPECT_LT(Off(fe, "Cm_alpha", kCmAlpha), 3.0);
  EXPECT_LT(Off(fe, "Cm_q", kCmq), 3.0);
  EXPECT_LT(Off(fe, "Cl_p", kClp), 3.0);
  // Output error's residuals are many times the noise and its roll damping
  // is far outside its error bars; the filter's innovations are near the
  // noise level.
  EXPECT_GT(oe.segments[0].rms_residual_deg.theta, 5 * 0.01);
  EXPECT_GT(Off(oe, "Cl_p", kClp), 5.0);
  EXPECT_LT(fe.segments[0].rms_residual_deg.theta, 1.5 * 0.01);
  // The random moments' intensity, sqrt(2 tau) RMS qSd/I in deg/s^1.5
  // (2.25), within 30%; none in roll.
  const double truth =
      std::sqrt(2 * 0.05) * 3e-4 * (460 * 0.3491 * 0.6667 / 0.2583) * 57.2958;
  EXPECT_EQ(fe.process_noise[0].axis, "roll");
  EXPECT_LT(fe.process_noise[0].intensity, 0.05 * truth);
  for (int axis : {1, 2}) {
    const ProcessNoiseEstimate& p = fe.process_noise[axis];
    EXPECT_NEAR(p.intensity / truth, 1.0, 0.3) << p.axis;
    EXPECT_GT(p.standard_error, 0.0) << p.axis;
    EXPECT_LT(p.standard_error, 0.2 * p.intensity) << p.axis;
  }
  // The report carries them; fit.csv's fitted angles are the filter's
  // one-step predictions, so its residuals are the innovations.
  const nlohmann::json report = nlohmann::json::parse(ReportJson(fe));
  EXPECT_NEAR(report["process_noise"]["pitch"]["intensity"].get<double>(),
              fe.process_noise[1].intensity,
              1e-12);
  EXPECT_EQ(report["process_noise"]["pitch"]["units"], "deg/s^1.5");
}

TEST(FilterError, FitsSegmentsJointly) {
  const std::string dir = testing::ScratchDirectory("filter_error_segments");
  const double seconds = testing::kSanitized ? 1.0 : 4.0;
  SimulateCone(3e-4, seconds, 21, dir + "/a.csv");
  SimulateCone(3e-4, seconds, 22, dir + "/b.csv");
  const FitResult r = Fit(
      ConeFit("segments:\n  - {name: a, data: {file: " + dir +
                  "/a.csv}}\n  - {name: b, data: {file: " + dir + "/b.csv}}\n",
              true));
  ASSERT_TRUE(r.converged) << r.termination;
  ASSERT_EQ(r.segments.size(), 2u);
  if (testing::kSanitized) return;
  EXPECT_LT(Off(r, "Cm_alpha", kCmAlpha), 3.0);
  EXPECT_LT(Off(r, "Cm_q", kCmq), 3.0);
  EXPECT_LT(Off(r, "Cl_p", kClp), 3.0);
  for (const SegmentFit& s : r.segments) {
    EXPECT_LT(s.rms_residual_deg.theta, 1.5 * 0.01) << s.name;
  }
}

TEST(FilterError, BatchSummariesCarryTheIntensities) {
  const std::string dir = testing::ScratchDirectory("filter_error_batch");
  SimulateCone(3e-4, testing::kSanitized ? 1.0 : 2.0, 31, dir + "/run.csv");
  testing::WriteText(dir + "/manifest.yaml",
                     "defaults:\n"
                     "  solver: {method: filter_error}\n"
                     "  process_noise: {roll: auto, pitch: auto, yaw: auto}\n"
                     "runs:\n  - {name: only, config: fit.yaml}\n");
  std::string fit = std::string(kCone) +
                    "parameters: {Cm_alpha: {value: -0.2, free: true}, "
                    "Cm_q: {value: 0, free: true}, Cm_alpha_delta2: -1.13, "
                    "phi0: {free: true}, phidot0: {free: true}, "
                    "theta0: {free: true}, thetadot0: {free: true}, "
                    "psi0: {free: true}, psidot0: {free: true}}\n"
                    "initial_conditions: from_data\n"
                    "data: {file: run.csv}\n"
                    "sigma: {phi: 0.01, theta: 0.01, psi: 0.01}\n"
                    "noise: {sigma: {phi: 0.01, theta: 0.01, psi: 0.01}, "
                    "seed: 3}\nsolver: {step: 0.002}\n";
  testing::WriteText(dir + "/fit.yaml", fit);
  BatchOptions options;
  options.out_dir = dir + "/out";
  options.jobs = 1;
  const BatchSummary summary = RunBatch(dir + "/manifest.yaml", options);
  ASSERT_EQ(summary.runs.size(), 1u);
  std::map<std::string, double> columns;
  for (const RunParameter& p : summary.runs[0].free) columns[p.name] = p.value;
  ASSERT_TRUE(columns.count("process_noise_pitch")) << "no intensity column";
  EXPECT_GT(columns["process_noise_pitch"], 0.0);
  // A resumed batch reads them back from report.json in the same order.
  options.resume = true;
  const BatchSummary again = RunBatch(dir + "/manifest.yaml", options);
  ASSERT_EQ(again.runs[0].free.size(), summary.runs[0].free.size());
  for (size_t i = 0; i < again.runs[0].free.size(); ++i) {
    EXPECT_EQ(again.runs[0].free[i].name, summary.runs[0].free[i].name);
  }
}

}  // namespace
}  // namespace fit3dof
