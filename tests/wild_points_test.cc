// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Wild points: clean records (noise-free, noisy, coarse, fast) give none;
// spikes, absurd values and samples beyond the model's reach are found and
// named; a fit names them by default and drops them when asked, reaching
// the same coefficients as a fit of the clean record.

#include "fit3dof/wild_points.h"

#include <cmath>
#include <string>

#include "fit3dof/config.h"
#include "fit3dof/fit.h"
#include "fit3dof/fit_report.h"
#include "fit3dof/input_error.h"
#include "fit3dof/noise.h"
#include "fit3dof/time_history.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

TimeHistory Record(const std::string& name) {
  return ReadTimeHistory(testing::SourcePath("configs/report/data/" + name));
}

TimeHistory Noisy(TimeHistory data, double sigma, std::uint64_t seed) {
  NoiseOptions noise;
  noise.enabled = true;
  noise.sigma = {sigma, sigma, sigma};
  noise.seed = seed;
  AddNoise(noise, &data);
  return data;
}

const char* kRecords[] = {
    "table6_clean.csv", "section5_1_clean.csv", "asymmetric_magnus_clean.csv"};

// The report's motions, noise-free and with 0.001 to 0.1 deg of noise over
// 20 seeds each: not one sample is called wild. The table 6 record has
// about 8 samples per pitch cycle and a fast roll.
TEST(WildPoints, CleanRecordsHaveNone) {
  for (const char* name : kRecords) {
    const TimeHistory clean = Record(name);
    EXPECT_TRUE(ScreenData(clean).empty()) << name;
    for (double sigma : {0.001, 0.01, 0.1}) {
      for (int seed = 1; seed <= testing::Repetitions(20); ++seed) {
        // Noise puts no channel on a grid.
        for (int ch = 0; ch < 3; ++ch) {
          EXPECT_EQ(ReadingStepDeg(Noisy(clean, sigma, seed), ch), 0.0)
              << name << " channel " << ch;
        }
        const std::vector<WildPoint> found =
            ScreenData(Noisy(clean, sigma, seed));
        EXPECT_TRUE(found.empty()) << name << " sigma " << sigma << " seed "
                                   << seed << ": " << found[0].Describe();
      }
    }
  }
}

// Colored measurement errors, as the report says real tunnel data have:
// first-order autoregressive noise (correlation 0.9 and 0.99 from sample to
// sample) plus a random-walk drift. The errors are smooth, not wild.
TEST(WildPoints, ColoredErrorsAreNotWild) {
  for (const char* name : kRecords) {
    const TimeHistory clean = Record(name);
    for (double rho : {0.9, 0.99}) {
      for (int seed = 1; seed <= testing::Repetitions(10); ++seed) {
        GaussianSource gauss(seed);
        TimeHistory data = clean;
        std::vector<double>* channels[] = {&data.phi, &data.theta, &data.psi};
        for (std::vector<double>* x : channels) {
          double colored = 0.0, drift = 0.0;
          for (double& v : *x) {
            colored =
                rho * colored + std::sqrt(1 - rho * rho) * 0.02 * gauss.Next();
            drift += 0.002 * gauss.Next();
            v += colored + drift + 0.005 * gauss.Next();
          }
        }
        const std::vector<WildPoint> found = ScreenData(data);
        EXPECT_TRUE(found.empty()) << name << " rho " << rho << " seed " << seed
                                   << ": " << found[0].Describe();
      }
    }
  }
}

// The computed angles a fit would give for `clean` (phi, theta, psi per
// sample).
std::vector<double> Computed(const TimeHistory& clean) {
  std::vector<double> computed;
  for (int i = 0; i < clean.size(); ++i) {
    computed.insert(computed.end(),
                    {clean.phi[i], clean.theta[i], clean.psi[i]});
  }
  return computed;
}

// Readings on a grid: roll in counts of about 2 deg, 1.05 times a whole
// fraction of its turn per sample (as 2-deg counts at 1.9 deg a sample),
// 0.01 deg of
// noise added after (tools/diagnose_suite's quantized roll); pitch from a
// converter with a 0.02-deg least bit, its 0.01 deg of noise before the
// rounding. Against the motion the roll's rounding traces a slow sawtooth
// that jumps by a count where it wraps, 49 robust sigmas of the sawtooth
// off the cubic through its neighbours (draw 88's quantized runs had 10
// and 8 such samples called wild). Not wild, in the data or in the
// residuals; spikes of ten counts in roll, of a hundred in pitch (2 deg:
// the motion's own curvature between Table 6's samples is what a pitch
// spike is judged by) still are.
TEST(WildPoints, QuantizedReadingsAreNotWild) {
  for (const char* name : kRecords) {
    const TimeHistory clean = Record(name);
    // About 2 deg, 1.05 times a whole fraction of the turn per sample.
    const double turn = std::abs(clean.phi[1] - clean.phi[0]);
    const double count = 1.05 * turn / std::max(1.0, std::floor(turn / 2.0));
    for (int seed = 1; seed <= testing::Repetitions(10); ++seed) {
      GaussianSource gauss(seed);
      TimeHistory data = clean;
      const double zero = 0.037 * seed * count;
      for (int i = 0; i < data.size(); ++i) {
        data.phi[i] = count * std::round((data.phi[i] - zero) / count) + zero +
                      0.01 * gauss.Next();
        data.theta[i] =
            0.02 * std::round((data.theta[i] + 0.01 * gauss.Next()) / 0.02);
      }
      // The grid's step is what diagnose holds the channel's noise above.
      EXPECT_NEAR(ReadingStepDeg(data, 1), 0.02, 1e-6) << name;
      std::vector<WildPoint> found = ScreenData(data);
      EXPECT_TRUE(found.empty())
          << name << " seed " << seed << ": " << found[0].Describe();
      found = ScreenResiduals(data, Computed(clean), {});
      EXPECT_TRUE(found.empty())
          << name << " seed " << seed << ": " << found[0].Describe();
      data.phi[data.size() / 2] += 10.0 * count;
      data.theta[data.size() / 3] += 2.0;
      found = ScreenData(data);
      ASSERT_EQ(found.size(), 2u) << name << " seed " << seed;
      EXPECT_EQ(found[0].sample, data.size() / 3);
      EXPECT_EQ(found[1].sample, data.size() / 2);
    }
  }
}

// Readings that are no motion at all do not trip the grid test: a
// channel held constant, one moving by 1e-300 deg a sample (finer than
// any sensor's count), one on a coarse grid at 1e300 deg, one alternating
// between two values. None is called wild, and nothing overflows (the
// sanitized build checks).
TEST(WildPoints, OddGridsAreNotWild) {
  TimeHistory data;
  for (int i = 0; i < 64; ++i) {
    data.Append(0.1 * i, 1e-300 * i, 5.0, i % 2 == 0 ? 0.25 : -0.25);
  }
  EXPECT_TRUE(ScreenData(data).empty()) << ScreenData(data)[0].Describe();
  std::vector<double> computed;
  for (int i = 0; i < data.size(); ++i) {
    computed.insert(computed.end(), {data.phi[i], data.theta[i], data.psi[i]});
  }
  EXPECT_TRUE(ScreenResiduals(data, computed, {}).empty());
  TimeHistory huge;
  for (int i = 0; i < 64; ++i) huge.Append(0.1 * i, 1e300 * (i % 7), 1.0, 0.0);
  ScreenData(huge);  // whatever it finds, it finds without overflow
}

// Every second sample of the record (half the sampling rate): still none.
TEST(WildPoints, CoarseSamplingHasNone) {
  const TimeHistory clean = Record("table6_clean.csv");
  TimeHistory coarse;
  for (int i = 0; i < clean.size(); i += 2) {
    coarse.Append(clean.t[i], clean.phi[i], clean.theta[i], clean.psi[i]);
  }
  for (int seed = 1; seed <= testing::Repetitions(20); ++seed) {
    EXPECT_TRUE(ScreenData(Noisy(coarse, 0.01, seed)).empty()) << seed;
  }
}

TEST(WildPoints, NamesASpikeAndAnAbsurdValue) {
  TimeHistory data = Noisy(Record("table6_clean.csv"), 0.01, 7);
  data.theta[300] += 40.0;
  data.phi[512] = 1e308;
  const std::vector<WildPoint> found = ScreenData(data);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].sample, 300);
  EXPECT_EQ(found[0].channel, 1);
  EXPECT_EQ(found[0].t, data.t[300]);
  EXPECT_EQ(found[0].value, data.theta[300]);
  EXPECT_NEAR(found[0].deviation, 40.0, 0.5);
  EXPECT_GT(found[0].sigmas, 1000.0);
  EXPECT_EQ(found[1].sample, 512);
  EXPECT_EQ(found[1].channel, 0);
  EXPECT_EQ(found[1].value, 1e308);
  const std::string line = found[0].Describe();
  EXPECT_NE(line.find("theta = "), std::string::npos) << line;
  EXPECT_NE(line.find("t = 18 s"), std::string::npos) << line;
}

TEST(WildPoints, FindsSpikesAtTheEdgesAndSideBySide) {
  TimeHistory data = Noisy(Record("section5_1_clean.csv"), 0.01, 3);
  data.psi[0] -= 5.0;
  data.psi[data.size() - 1] += 5.0;
  data.phi[100] += 3.0;
  data.phi[101] -= 2.0;
  data.phi[102] += 4.0;
  const std::vector<WildPoint> found = ScreenData(data);
  ASSERT_EQ(found.size(), 5u);
  EXPECT_EQ(found[0].sample, 0);
  EXPECT_EQ(found[1].sample, 100);
  EXPECT_EQ(found[2].sample, 101);
  EXPECT_EQ(found[3].sample, 102);
  EXPECT_EQ(found[4].sample, data.size() - 1);
}

TEST(WildPoints, ThetaBeyondNinetyDegreesIsOutOfReach) {
  TimeHistory data = Record("table6_clean.csv");
  data.theta[50] = 90.0;
  data.theta[51] = -135.0;
  const std::vector<WildPoint> found = ScreenData(data);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].test, WildPointTest::kReach);
  EXPECT_EQ(found[1].test, WildPointTest::kReach);
  EXPECT_TRUE(std::isinf(found[0].sigmas));
}

// A 0.3-deg spike is small against the table 6 motion's curvature between
// samples but 30 sigmas of the noise: the residuals show it.
TEST(WildPoints, ResidualsShowWhatTheDataHide) {
  const TimeHistory clean = Record("table6_clean.csv");
  std::vector<double> computed;
  for (int i = 0; i < clean.size(); ++i) {
    computed.insert(computed.end(),
                    {clean.phi[i], clean.theta[i], clean.psi[i]});
  }
  TimeHistory data = Noisy(clean, 0.01, 11);
  EXPECT_TRUE(ScreenResiduals(data, computed, {}).empty());
  data.theta[400] += 0.3;
  const std::vector<WildPoint> found = ScreenResiduals(data, computed, {});
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].sample, 400);
  EXPECT_EQ(found[0].test, WildPointTest::kResidual);
  // A known wild point is not named again.
  EXPECT_TRUE(ScreenResiduals(data, computed, {400}).empty());
}

TEST(WildPoints, DropSamplesKeepsTheRest) {
  const TimeHistory data = Record("table6_clean.csv");
  const TimeHistory kept = DropSamples(data, {3, 1, 3});
  ASSERT_EQ(kept.size(), data.size() - 2);
  EXPECT_EQ(kept.t[1], data.t[2]);
  EXPECT_EQ(kept.t[2], data.t[4]);
}

// The Table 6 fit at 0.01 deg noise with a 40-deg spike in theta: by default
// it is named (warnings, report.json) and kept; with outliers: reject it is
// dropped and the fit matches the fit of the clean record.
class WildPointFit : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::ScratchDirectory("wild_point_fit");
    TimeHistory data = Noisy(Record("table6_clean.csv"), 0.01, 5);
    clean_ = dir_ + "/clean.csv";
    WriteTimeHistory(clean_, data);
    data.theta[300] += 40.0;
    spiked_ = dir_ + "/spiked.csv";
    WriteTimeHistory(spiked_, data);
  }

  FitResult FitFile(const std::string& file, const std::string& policy) {
    Case c =
        LoadConfig(testing::SourcePath("configs/report/table6_sigma0.01.yaml"));
    c.noise.enabled = false;
    c.segments[0].data_file = file;
    ParseOutlierPolicy(policy, &c.segments[0].outliers);
    // A fit that keeps a wild point cannot converge and tries every
    // restart; the sanitized build tries two (the same path, a quarter of
    // the time).
    if (testing::kSanitized) c.solver.starts = 2;
    return Fit(c);
  }

  std::string dir_, clean_, spiked_;
};

TEST_F(WildPointFit, DefaultNamesAndKeeps) {
  const FitResult r = FitFile(spiked_, "warn");
  ASSERT_GE(r.outliers.size(), 1u);
  EXPECT_EQ(r.outliers[0].point.sample, 300);
  EXPECT_FALSE(r.outliers[0].dropped);
  EXPECT_EQ(r.points, 800);
  bool named = false;
  for (const std::string& w : r.warnings) {
    named |= w.find("wild point: theta = ") != std::string::npos &&
             w.find("t = 18 s") != std::string::npos &&
             w.find("kept") != std::string::npos;
  }
  EXPECT_TRUE(named);
  EXPECT_GT(r.probable_error, 3.0);
  EXPECT_NE(r.termination.find("1 wild point, kept"), std::string::npos)
      << r.termination;
  const nlohmann::json report = nlohmann::json::parse(ReportJson(r));
  ASSERT_GE(report["outliers"].size(), 1u);
  EXPECT_EQ(report["outliers"][0]["channel"], "theta");
  EXPECT_EQ(report["outliers"][0]["t"], 18.0);
  EXPECT_EQ(report["outliers"][0]["action"], "kept");
}

TEST_F(WildPointFit, RejectDropsAndMatchesTheCleanFit) {
  const FitResult clean = FitFile(clean_, "warn");
  EXPECT_TRUE(clean.outliers.empty());
  const FitResult r = FitFile(spiked_, "reject");
  ASSERT_EQ(r.outliers.size(), 1u);
  EXPECT_TRUE(r.outliers[0].dropped);
  EXPECT_EQ(r.points, 799);
  EXPECT_TRUE(r.converged) << r.termination;
  EXPECT_NEAR(r.probable_error, clean.probable_error, 0.01);
  for (size_t j = 0; j < r.parameters.size(); ++j) {
    const ParameterEstimate& e = r.parameters[j];
    if (!e.free) continue;
    EXPECT_NEAR(
        e.value, clean.parameters[j].value, 0.2 * clean.parameters[j].rms_error)
        << e.name;
  }
}

// 1e308 in roll: roll is compared modulo 360 deg, so the fit itself is
// not thrown, but the value is still beyond any motion and is named.
TEST_F(WildPointFit, AnAbsurdValueIsNamed) {
  TimeHistory data = ReadTimeHistory(clean_);
  data.phi[200] = 1e308;
  data.psi[201] = -2e9;
  const std::string file = dir_ + "/absurd.csv";
  WriteTimeHistory(file, data);
  const FitResult kept = FitFile(file, "warn");
  ASSERT_EQ(kept.outliers.size(), 2u);
  EXPECT_EQ(kept.outliers[0].point.value, 1e308);
  EXPECT_EQ(kept.outliers[0].point.test, WildPointTest::kReach);
  EXPECT_EQ(kept.outliers[1].point.value, -2e9);
  const FitResult r = FitFile(file, "reject");
  EXPECT_TRUE(r.converged) << r.termination;
  EXPECT_EQ(r.points, 798);
}

// Roll wrapped into (-180, 180], as some telemetry records it, is a
// continuous motion, not a wild point at every turn.
TEST(WildPoints, WrappedRollIsNotWild) {
  TimeHistory data = Noisy(Record("table6_clean.csv"), 0.01, 2);
  for (double& phi : data.phi) phi -= 360.0 * std::round(phi / 360.0);
  EXPECT_TRUE(ScreenData(data).empty());
  data.phi[321] += 30.0;
  const std::vector<WildPoint> found = ScreenData(data);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].sample, 321);
}

TEST(WildPoints, ConfigSaysWhatToDo) {
  const std::string dir = testing::ScratchDirectory("wild_point_config");
  const std::string base =
      "name: x\nmodel: symmetric\nbody: {area: 0.39, diameter: 0.7, Ix: "
      "0.04, Iy: 0.24}\nflow: {velocity: 4774, dynamic_pressure: 150}\n"
      "parameters: {Cm_alpha: {value: -0.2, free: true}}\n";
  testing::WriteText(dir + "/a.yaml",
                     base + "data: {file: d.csv, outliers: reject}\n");
  const Case c = LoadConfig(dir + "/a.yaml");
  EXPECT_EQ(c.segments[0].outliers, OutlierPolicy::kReject);
  const Case again = ParseConfig(CaseToYaml(c), dir + "/b.yaml", dir);
  EXPECT_EQ(again.segments[0].outliers, OutlierPolicy::kReject);
  testing::WriteText(dir + "/c.yaml",
                     base + "data: {file: d.csv, outliers: drop}\n");
  try {
    LoadConfig(dir + "/c.yaml");
    ADD_FAILURE() << "accepted outliers: drop";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("c.yaml:6"), std::string::npos) << message;
    EXPECT_NE(message.find("data.outliers"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace fit3dof
