// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The residual-correlation correction on problems with a known answer: a
// linear model with AR(1) errors, whose estimator covariance is
// B X^T Sigma X B with Sigma the AR(1) covariance, and with white errors,
// where it must reduce to the residual variance times B.

#include "colored_covariance.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "gtest/gtest.h"
#include "symmetric_eigen.h"

namespace fit3dof {
namespace {

// Regressors of a damped-oscillation-like fit: a constant, a sinusoid at
// 1 Hz and a slow ramp, sampled at 100 Hz.
Eigen::MatrixXd Regressors(int n) {
  Eigen::MatrixXd x(n, 4);
  for (int i = 0; i < n; ++i) {
    const double t = 0.01 * i;
    x(i, 0) = 1.0;
    x(i, 1) = std::sin(2.0 * M_PI * t);
    x(i, 2) = std::cos(2.0 * M_PI * t) * std::exp(-t / (0.02 * n));
    x(i, 3) = t / (0.01 * n);
  }
  return x;
}

// AR(1) errors e_i = phi e_{i-1} + a_i, stationary, var(a) = 1.
Eigen::VectorXd Ar1(int n, double phi, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::VectorXd e(n);
  e(0) = normal(rng) / std::sqrt(1.0 - phi * phi);
  for (int i = 1; i < n; ++i) e(i) = phi * e(i - 1) + normal(rng);
  return e;
}

// B X^T Sigma X B for AR(1) errors with innovation variance 1.
Eigen::MatrixXd AnalyticCovariance(const Eigen::MatrixXd& x, double phi) {
  const int n = x.rows();
  const Eigen::MatrixXd b = (x.transpose() * x).inverse();
  const double c0 = 1.0 / (1.0 - phi * phi);
  Eigen::MatrixXd y = c0 * x;
  double c = c0;
  for (int lag = 1; lag < n && c > 1e-18 * c0; ++lag) {
    c *= phi;
    y.topRows(n - lag) += c * x.bottomRows(n - lag);
    y.bottomRows(n - lag) += c * x.topRows(n - lag);
  }
  return b * (x.transpose() * y) * b;
}

// The least-squares fit's residual series.
ResidualSeries FitLinear(const Eigen::MatrixXd& x, const Eigen::VectorXd& e) {
  const Eigen::VectorXd y = x * Eigen::Vector4d(1.0, 2.0, -0.5, 0.3) + e;
  const Eigen::VectorXd beta =
      (x.transpose() * x).ldlt().solve(x.transpose() * y);
  Eigen::VectorXd t(x.rows());
  for (int i = 0; i < x.rows(); ++i) t(i) = 0.01 * i;
  return {x, y - x * beta, t, {}, {}};
}

// The corrected covariance is an estimate from one record: over 10 records
// its mean is within 5% of the analytic covariance, each record within 20%.
TEST(ColoredCovariance, MatchesTheAnalyticCovarianceOfAnAr1Error) {
  const int n = 20000;
  const double phi = 0.8;
  const Eigen::MatrixXd x = Regressors(n);
  const Eigen::MatrixXd b = (x.transpose() * x).inverse();
  const Eigen::MatrixXd truth = AnalyticCovariance(x, phi);
  Eigen::Vector4d mean = Eigen::Vector4d::Zero();
  const int records = 10;
  for (int seed = 1; seed <= records; ++seed) {
    std::vector<SeriesCorrelation> stats;
    const Eigen::MatrixXd cov = SandwichCovariance(
        b, ColoredInformation({FitLinear(x, Ar1(n, phi, seed))}, b, &stats));
    for (int j = 0; j < 4; ++j) {
      const double ratio = cov(j, j) / truth(j, j);
      EXPECT_NEAR(ratio, 1.0, 0.2) << "seed " << seed << " parameter " << j;
      mean(j) += ratio / records;
    }
    // The uncorrected estimate (residual variance times B) is far off: the
    // long-run variance of this error is (1 + phi) / (1 - phi) = 9 times
    // its variance.
    EXPECT_LT(stats[0].variance * b(1, 1) / truth(1, 1), 0.5);
    EXPECT_FALSE(stats[0].white);
    EXPECT_NEAR(stats[0].normalized[0], phi, 0.02);
    EXPECT_GT(stats[0].lag_window, 8);
  }
  for (int j = 0; j < 4; ++j) {
    EXPECT_NEAR(mean(j), 1.0, 0.05) << "parameter " << j;
  }
}

TEST(ColoredCovariance, WhiteResidualsGiveTheirVarianceTimesB) {
  const int n = 5000;
  const Eigen::MatrixXd x = Regressors(n);
  const Eigen::MatrixXd b = (x.transpose() * x).inverse();
  int white = 0, no_lines = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    std::vector<SeriesCorrelation> stats;
    const Eigen::MatrixXd cov = SandwichCovariance(
        b, ColoredInformation({FitLinear(x, Ar1(n, 0.0, seed))}, b, &stats));
    white += stats[0].white;
    no_lines += stats[0].lines.empty();
    if (stats[0].lag_window == 0 && stats[0].lines.empty()) {
      EXPECT_NEAR(
          (cov - stats[0].variance * b).norm() / cov.norm(), 0.0, 1e-12);
    }
    for (int j = 0; j < 4; ++j) {
      EXPECT_NEAR(cov(j, j) / b(j, j), 1.0, 0.15) << "seed " << seed;
    }
  }
  EXPECT_GE(white, 18);  // the Ljung-Box test at 1%
  EXPECT_GE(no_lines, 19);
}

TEST(ColoredCovariance, SeriesAddUpAndTheResultIsPositiveSemidefinite) {
  const int n = 2000;
  const Eigen::MatrixXd x = Regressors(n);
  const ResidualSeries a = FitLinear(x, Ar1(n, 0.5, 7));
  const ResidualSeries c = FitLinear(x, Ar1(n, -0.3, 8));
  const Eigen::MatrixXd b = (x.transpose() * x).inverse();
  const Eigen::MatrixXd both = ColoredInformation({a, c}, b, nullptr);
  const Eigen::MatrixXd sum =
      ColoredInformation({a}, b, nullptr) + ColoredInformation({c}, b, nullptr);
  EXPECT_LT((both - sum).norm(), 1e-9 * both.norm());
  const SymmetricEigen eigen(both);
  EXPECT_GE(eigen.values().minCoeff(), 0.0);
}

// A random-phase sinusoidal error at 1.08 Hz beside a damped 1 Hz regressor
// (as a roll-following reading error beside the pitch motion): the fit
// absorbs much of it, the residual keeps little. Each record's corrected
// variance is an estimate; over 200 records the scatter of the estimates
// over the mean corrected standard error must be near 1 for every
// parameter, where the residual's autocorrelation alone is far below.
TEST(ColoredCovariance, LinesTheFitAbsorbsAreAddedBackWhole) {
  const int n = 800;
  const Eigen::MatrixXd x = Regressors(n);
  const Eigen::MatrixXd b = (x.transpose() * x).inverse();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * M_PI);
  std::normal_distribution<double> normal(0.0, 1.0);
  const int records = 200;
  Eigen::MatrixXd estimates(records, 4);
  Eigen::Vector4d mean_var = Eigen::Vector4d::Zero();
  Eigen::Vector4d mean_var_plain = Eigen::Vector4d::Zero();
  for (int rec = 0; rec < records; ++rec) {
    const double p = phase(rng);
    Eigen::VectorXd e(n);
    for (int i = 0; i < n; ++i) {
      e(i) = 3.0 * std::cos(2.0 * M_PI * 1.08 * 0.01 * i + p) + normal(rng);
    }
    const ResidualSeries s = FitLinear(x, e);
    estimates.row(rec) =
        (b * x.transpose() * (x * Eigen::Vector4d(1.0, 2.0, -0.5, 0.3) + e))
            .transpose();
    std::vector<SeriesCorrelation> stats;
    const Eigen::MatrixXd cov =
        SandwichCovariance(b, ColoredInformation({s}, b, &stats));
    ASSERT_FALSE(stats[0].lines.empty()) << "record " << rec;
    EXPECT_NEAR(stats[0].lines[0].frequency_hz, 1.08, 0.02);
    // Without the line: the plain lag-window bracket of the residual.
    ResidualSeries plain = s;
    plain.times.resize(0);
    const Eigen::MatrixXd cov_plain =
        SandwichCovariance(b, ColoredInformation({plain}, b, nullptr));
    mean_var += cov.diagonal() / records;
    mean_var_plain += cov_plain.diagonal() / records;
  }
  const Eigen::RowVector4d centre = estimates.colwise().mean();
  for (int j = 1; j < 3; ++j) {  // the two oscillation regressors
    const double scatter2 =
        (estimates.col(j).array() - centre(j)).square().sum() / (records - 1);
    const double ratio = std::sqrt(scatter2 / mean_var(j));
    EXPECT_GT(ratio, 0.8) << "parameter " << j;
    EXPECT_LT(ratio, 1.25) << "parameter " << j;
    EXPECT_GT(std::sqrt(scatter2 / mean_var_plain(j)), 1.5)
        << "parameter " << j;
  }
}

// The scatter of estimates of parameters 1 and 2 over records, against the
// mean variance reported with the reading-error terms and with the
// autocorrelation alone (no roll, angle or times), and in how many records
// a line `is_sought` was found.
struct Calibration {
  Eigen::Vector2d with, without;
  int found = 0;
};
template <typename MakeRecord, typename IsSought>
Calibration StudyRecords(const Eigen::MatrixXd& x,
                         int records,
                         const MakeRecord& make,
                         const IsSought& is_sought) {
  Calibration c;
  const Eigen::MatrixXd b = (x.transpose() * x).inverse();
  Eigen::MatrixXd estimates(records, 4);
  Eigen::Vector4d var = Eigen::Vector4d::Zero(), plain = var;
  for (int rec = 0; rec < records; ++rec) {
    Eigen::VectorXd e;
    ResidualSeries s = make(rec, &e);
    estimates.row(rec) =
        (b * x.transpose() * (x * Eigen::Vector4d(1.0, 2.0, -0.5, 0.3) + e))
            .transpose();
    std::vector<SeriesCorrelation> stats;
    var +=
        SandwichCovariance(b, ColoredInformation({s}, b, &stats)).diagonal() /
        records;
    c.found +=
        std::any_of(stats[0].lines.begin(), stats[0].lines.end(), is_sought);
    s.roll.resize(0);
    s.angle.resize(0);
    s.times.resize(0);
    plain +=
        SandwichCovariance(b, ColoredInformation({s}, b, nullptr)).diagonal() /
        records;
  }
  const Eigen::RowVector4d centre = estimates.colwise().mean();
  for (int j = 1; j < 3; ++j) {
    const double scatter2 =
        (estimates.col(j).array() - centre(j)).square().sum() / (records - 1);
    c.with(j - 1) = std::sqrt(scatter2 / var(j));
    c.without(j - 1) = std::sqrt(scatter2 / plain(j));
  }
  return c;
}

// A reading error locked to a decaying spin: its frequency sweeps from 1.2
// to 0.88 Hz across the 1 Hz regressor, so no single frequency catches it.
TEST(ColoredCovariance, RollLockedLinesFollowTheSpin) {
  const int n = 800;
  const Eigen::MatrixXd x = Regressors(n);
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * M_PI);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::VectorXd roll(n);
  for (int i = 0; i < n; ++i) {
    const double t = 0.01 * i;
    roll(i) = 2.0 * M_PI * (1.2 * t - 0.02 * t * t);
  }
  const Calibration c = StudyRecords(
      x,
      200,
      [&](int, Eigen::VectorXd* e) {
        const double p = phase(rng);
        e->resize(n);
        for (int i = 0; i < n; ++i)
          (*e)(i) = 3.0 * std::cos(roll(i) + p) + normal(rng);
        ResidualSeries s = FitLinear(x, *e);
        s.roll = roll;
        return s;
      },
      [](const ResidualLine& line) { return line.roll_harmonic == 1; });
  EXPECT_EQ(c.found, 200);
  std::printf("roll-locked: with %.2f %.2f, without %.2f %.2f\n",
              c.with(0),
              c.with(1),
              c.without(0),
              c.without(1));
  for (int j = 0; j < 2; ++j) {
    EXPECT_GT(c.with(j), 0.8) << "parameter " << j + 1;
    EXPECT_LT(c.with(j), 1.25) << "parameter " << j + 1;
    EXPECT_GT(c.without(j), 1.5) << "parameter " << j + 1;
  }
}

// A calibration error growing as the angle cubed, of random sign: the fit
// absorbs most of it into the oscillation's parameters (it decays three
// times as fast), and the bars must count the bias that leaves.
TEST(ColoredCovariance, CalibrationTermsAreCountedWhole) {
  const int n = 800;
  const Eigen::MatrixXd x = Regressors(n);
  const Eigen::VectorXd angle = 0.09 * x.col(2);  // rad, about 5 deg
  std::mt19937_64 rng(13);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Calibration c = StudyRecords(
      x,
      200,
      [&](int rec, Eigen::VectorXd* e) {
        const double sign = rec % 2 ? 1.0 : -1.0;
        e->resize(n);
        for (int i = 0; i < n; ++i)
          (*e)(i) = sign * 4.0 * std::pow(angle(i) / 0.09, 3) + normal(rng);
        ResidualSeries s = FitLinear(x, *e);
        s.angle = angle;
        return s;
      },
      [](const ResidualLine& line) { return line.calibration_power == 3; });
  EXPECT_GE(c.found, 190);
  for (int j = 0; j < 2; ++j) {
    EXPECT_GT(c.with(j), 0.8) << "parameter " << j + 1;
    EXPECT_LT(c.with(j), 1.25) << "parameter " << j + 1;
  }
  // The bias falls on the decaying oscillation (cos^3 is mostly cos); its
  // autocorrelation alone misses it.
  EXPECT_GT(c.without(1), 1.5);
  std::printf("calibration: with %.2f %.2f, without %.2f %.2f\n",
              c.with(0),
              c.with(1),
              c.without(0),
              c.without(1));
}

}  // namespace
}  // namespace fit3dof
