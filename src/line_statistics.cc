// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Residual-series statistics (line_statistics.h).

#include "line_statistics.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace fit3dof {
namespace {

constexpr int kQuietLags = 10;

// Weight of lag k for window L: 1 up to L, falling linearly to 0 at 2L.
double LagWeight(int k, int window) {
  if (k <= window) return 1.0;
  return std::max(0.0, 1.0 - static_cast<double>(k - window) / (window + 1));
}

}  // namespace

double Autocovariance(const Eigen::VectorXd& r, int k) {
  const int n = static_cast<int>(r.size());
  return r.head(n - k).dot(r.tail(n - k)) / n;
}

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

std::vector<double> WindowedAutocovariance(const Eigen::VectorXd& r,
                                           int window) {
  const int n = static_cast<int>(r.size());
  const int reach = std::min(n - 1, 2 * window);
  std::vector<double> wc(std::max(reach, 0) + 1);
  wc[0] = Autocovariance(r, 0);
  for (int lag = 1; lag <= reach; ++lag) {
    wc[lag] = LagWeight(lag, window) * Autocovariance(r, lag);
  }
  return wc;
}

double BackgroundPower(const std::vector<double>& power, int lo, int hi) {
  const int half = static_cast<int>(power.size()) - 1;
  std::vector<double> around;
  for (int j = lo - kBackgroundBins; j <= hi + kBackgroundBins; ++j) {
    if (j >= 1 && j <= half && (j < lo - 2 || j > hi + 2))
      around.push_back(power[j]);
  }
  if (around.size() < kBackgroundBins) return 0.0;
  std::nth_element(
      around.begin(), around.begin() + around.size() / 2, around.end());
  return around[around.size() / 2];
}

double LineFactor(double chance) {
  return std::log(1.0 / chance) / std::log(2.0);
}

Eigen::MatrixXd CosSin(const Eigen::VectorXd& phase) {
  Eigen::MatrixXd u(phase.size(), 2);
  for (int i = 0; i < phase.size(); ++i) {
    // glibc's sincos: one argument reduction for both.
    ::sincos(phase(i), &u(i, 1), &u(i, 0));
  }
  return u;
}

double Explained(const Eigen::MatrixXd& u, const Eigen::VectorXd& r) {
  const Eigen::Vector2d utr = u.transpose() * r;
  const Eigen::Matrix2d utu = u.transpose() * u;
  return utr.dot(utu.ldlt().solve(utr));
}

double ProbableErrorSpread(int points, int free_parameters) {
  const double dof =
      std::max(1.0, 3.0 * points - static_cast<double>(free_parameters));
  return kZ999 * std::sqrt(2.0 / dof);
}

}  // namespace fit3dof
