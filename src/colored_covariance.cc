// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The residual-correlation correction of the parameter covariance
// (colored_covariance.h).

#include "colored_covariance.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace fit3dof {
namespace {

constexpr int kReportedLags = 10;
constexpr int kQuietLags = 10;
constexpr int kLjungBoxLags = 20;
// 1% upper quantile of the standard normal: the Ljung-Box limit.
constexpr double kZ99 = 2.3263478740408408;

// Biased autocovariance c(k) = (1/N) sum_i r_i r_{i+k}.
double Autocovariance(const Eigen::VectorXd& r, int k) {
  const int n = static_cast<int>(r.size());
  return r.head(n - k).dot(r.tail(n - k)) / n;
}

// Chi-square quantile by Wilson and Hilferty's cube-root approximation
// (within 1% of the exact value for 20 degrees of freedom).
double ChiSquareQuantile(int dof, double z) {
  const double a = 2.0 / (9.0 * dof);
  return dof * std::pow(1.0 - a + z * std::sqrt(a), 3);
}

// The lag window (colored_covariance.h): the last lag whose
// autocorrelation lies outside Bartlett's 3-sigma band, looked for until
// kQuietLags lags in a row lie inside it (or N/2).
int LagWindow(const Eigen::VectorXd& r, double c0) {
  const int n = static_cast<int>(r.size());
  if (!(c0 > 0.0)) return 0;
  int last = 0;
  double sum_rho2 = 0.0;
  for (int k = 1; k <= n / 2 && k - last <= kQuietLags; ++k) {
    const double rho = Autocovariance(r, k) / c0;
    const double band = 3.0 * std::sqrt((1.0 + 2.0 * sum_rho2) / n);
    if (std::abs(rho) > band) last = k;
    sum_rho2 += rho * rho;
  }
  return last;
}

// Weight of lag k for window L: 1 up to L, falling linearly to 0 at 2L.
double LagWeight(int k, int window) {
  if (k <= window) return 1.0;
  return std::max(0.0, 1.0 - static_cast<double>(k - window) / (window + 1));
}

}  // namespace

SeriesCorrelation CorrelationOf(const Eigen::VectorXd& residual) {
  SeriesCorrelation s;
  const int n = static_cast<int>(residual.size());
  if (n < 2) return s;
  s.variance = Autocovariance(residual, 0);
  s.lag_window = LagWindow(residual, s.variance);
  const int lags = std::min(kLjungBoxLags, n / 2);
  double q = 0.0;
  for (int k = 1; k <= lags; ++k) {
    const double rho =
        s.variance > 0.0 ? Autocovariance(residual, k) / s.variance : 0.0;
    if (k <= kReportedLags) s.normalized.push_back(rho);
    q += rho * rho / (n - k);
  }
  s.ljung_box = n * (n + 2.0) * q;
  s.ljung_box_limit = lags > 0 ? ChiSquareQuantile(lags, kZ99) : 0.0;
  s.white = !(s.ljung_box > s.ljung_box_limit);
  return s;
}

Eigen::MatrixXd ColoredInformation(const std::vector<ResidualSeries>& series,
                                   std::vector<SeriesCorrelation>* stats) {
  const int k = series.empty() ? 0 : series[0].jacobian.cols();
  Eigen::MatrixXd bracket = Eigen::MatrixXd::Zero(k, k);
  for (const ResidualSeries& s : series) {
    const SeriesCorrelation corr = CorrelationOf(s.residual);
    if (stats != nullptr) stats->push_back(corr);
    const int n = static_cast<int>(s.residual.size());
    const int reach = std::min(n - 1, 2 * corr.lag_window);
    // Y = T J with T(i, j) = w(|i - j|) c(|i - j|): J^T T J costs N (2L+1) k
    // for Y and N k^2 for the product, not N^2 k^2.
    Eigen::MatrixXd y = corr.variance * s.jacobian;
    for (int lag = 1; lag <= reach; ++lag) {
      const double t =
          LagWeight(lag, corr.lag_window) * Autocovariance(s.residual, lag);
      if (t == 0.0) continue;
      y.topRows(n - lag) += t * s.jacobian.bottomRows(n - lag);
      y.bottomRows(n - lag) += t * s.jacobian.topRows(n - lag);
    }
    bracket.noalias() += s.jacobian.transpose() * y;
  }
  // Symmetric and positive semidefinite: a truncated, tapered sum of
  // sampled autocorrelations need not be.
  const Eigen::MatrixXd symmetric = 0.5 * (bracket + bracket.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(symmetric);
  const Eigen::VectorXd lambda = eigen.eigenvalues().cwiseMax(0.0);
  return eigen.eigenvectors() * lambda.asDiagonal() *
         eigen.eigenvectors().transpose();
}

Eigen::MatrixXd SandwichCovariance(const Eigen::MatrixXd& b,
                                   const Eigen::MatrixXd& bracket) {
  return b * bracket * b;
}

}  // namespace fit3dof
