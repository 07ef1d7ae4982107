// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The residual-correlation correction of the parameter covariance
// (colored_covariance.h).

#include "colored_covariance.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "spectral_lines.h"

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

// Lines looked for per series, the bins either side whose median power is
// a line's background, the chance of a false line per series, and the grid
// that refines each line's frequency within one bin either side.
constexpr int kMostLines = 6;
constexpr int kBackgroundBins = 32;
constexpr double kFalseLineChance = 1e-4;
constexpr int kRefineSteps = 20;

// Frequencies (Hz) of the periodogram peaks of r that stand above their
// neighbourhood: power over the median of the kBackgroundBins bins either
// side (two next to the peak left out, where a line leaks). Against a local
// median a coloured continuum (an AR(1) error) shows no lines; against the
// mean its low-frequency bins would. A bin of noise has exponentially
// distributed power, whose median is ln 2 times its mean, so a peak counts
// when power > ln(bins / kFalseLineChance) / ln 2 times the median.
std::vector<double> LineFrequencies(const Eigen::VectorXd& r, double dt) {
  const int n = static_cast<int>(r.size());
  const std::vector<double> power =
      Periodogram(std::vector<double>(r.data(), r.data() + n));
  const int half = n / 2;
  const double factor = std::log(half / kFalseLineChance) / std::log(2.0);
  std::vector<std::pair<double, int>> peaks;
  for (int k = 1; k < half; ++k) {
    if (power[k] < power[k - 1] || power[k] < power[k + 1]) continue;
    std::vector<double> around;
    for (int j = k - kBackgroundBins; j <= k + kBackgroundBins; ++j) {
      if (j >= 1 && j <= half && std::abs(j - k) > 2)
        around.push_back(power[j]);
    }
    if (around.size() < kBackgroundBins) continue;
    std::nth_element(
        around.begin(), around.begin() + around.size() / 2, around.end());
    const double median = around[around.size() / 2];
    if (power[k] > factor * median) peaks.push_back({power[k], k});
  }
  std::sort(peaks.rbegin(), peaks.rend());
  std::vector<double> frequencies;
  for (size_t p = 0; p < peaks.size() && p < kMostLines; ++p) {
    frequencies.push_back(peaks[p].second / (n * dt));
  }
  return frequencies;
}

// Cosine and sine at f (Hz) at the times t (n x 2).
Eigen::MatrixXd CosSin(const Eigen::VectorXd& t, double frequency_hz) {
  const double w = 2.0 * M_PI * frequency_hz;
  Eigen::MatrixXd u(t.size(), 2);
  for (int i = 0; i < t.size(); ++i) {
    u(i, 0) = std::cos(w * t(i));
    u(i, 1) = std::sin(w * t(i));
  }
  return u;
}

// [cos sin] at f as the fit leaves it, (I - J B J^T) [cos sin]; jtu (if
// given) receives J^T [cos sin].
Eigen::MatrixXd Kept(const Eigen::MatrixXd& jacobian,
                     const Eigen::MatrixXd& b,
                     const Eigen::VectorXd& t,
                     double frequency_hz,
                     Eigen::MatrixXd* jtu = nullptr) {
  const Eigen::MatrixXd u = CosSin(t, frequency_hz);
  const Eigen::MatrixXd ju = jacobian.transpose() * u;
  if (jtu != nullptr) *jtu = ju;
  return u - jacobian * (b * ju);
}

// The part of r that a kept sinusoid pair explains.
double Explained(const Eigen::MatrixXd& kept, const Eigen::VectorXd& r) {
  const Eigen::Vector2d ktr = kept.transpose() * r;
  const Eigen::Matrix2d ktk = kept.transpose() * kept;
  return ktr.dot(ktk.ldlt().solve(ktr));
}

// The frequency near `guess` (within one bin, 1 / span) at which a
// sinusoid, as the fit leaves it, explains most of r.
double RefineFrequency(const Eigen::MatrixXd& jacobian,
                       const Eigen::MatrixXd& b,
                       const Eigen::VectorXd& r,
                       const Eigen::VectorXd& t,
                       double guess) {
  const double bin = 1.0 / (t(t.size() - 1) - t(0));
  double best = guess, best_power = -1.0;
  for (int s = -kRefineSteps; s <= kRefineSteps; ++s) {
    const double f = guess + bin * s / kRefineSteps;
    if (!(f > 0.0)) continue;
    const double power = Explained(Kept(jacobian, b, t, f), r);
    if (power > best_power) {
      best_power = power;
      best = f;
    }
  }
  return best;
}

// Takes each significant line out of `r` and returns its share of the
// bracket, (a^2 / 2) Re(c c^H) (colored_covariance.h). A line is fitted to
// the residual as the fit leaves it, (I - H) [cos sin] with H = J B J^T:
// its amplitude is then the error's own, and what the fit's absorption of
// it spilled onto other frequencies (near the motion's) goes with it
// instead of showing up as a line of its own.
Eigen::MatrixXd LineBracket(const Eigen::MatrixXd& jacobian,
                            const Eigen::VectorXd& t,
                            const Eigen::MatrixXd& b,
                            Eigen::VectorXd* r,
                            std::vector<ResidualLine>* lines) {
  const int n = static_cast<int>(r->size());
  const int k = static_cast<int>(jacobian.cols());
  Eigen::MatrixXd bracket = Eigen::MatrixXd::Zero(k, k);
  if (n < 16 || t.size() != n || !(t(n - 1) > t(0))) return bracket;
  const double dt = (t(n - 1) - t(0)) / (n - 1);
  struct Found {
    ResidualLine line;
    Eigen::MatrixXd jtu;  // J^T [cos sin]
  };
  std::vector<Found> found;
  for (double frequency : LineFrequencies(*r, dt)) {
    Found f;
    f.line.frequency_hz = RefineFrequency(jacobian, b, *r, t, frequency);
    const Eigen::MatrixXd kept =
        Kept(jacobian, b, t, f.line.frequency_hz, &f.jtu);
    const Eigen::Matrix2d ktk = kept.transpose() * kept;
    f.line.kept_share =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(ktk).eigenvalues()(0) /
        (0.5 * n);
    // A line the fit could absorb whole leaves nothing to measure it by:
    // it stays in the residual's autocorrelation.
    if (f.line.kept_share < kMinKeptShare) continue;
    const Eigen::Vector2d alpha = ktk.ldlt().solve(kept.transpose() * *r);
    *r -= kept * alpha;
    f.line.residual_amplitude =
        std::sqrt(2.0 * (kept * alpha).squaredNorm() / n);
    f.line.amplitude = alpha.norm();
    found.push_back(f);
  }
  // The amplitudes' share of the background noise: E|alpha|^2 = a^2 +
  // var tr((K^T K)^-1), K = (I - H) [cos sin], taken off each.
  const double background = r->squaredNorm() / n;
  for (Found& f : found) {
    const double noise = background * 2.0 / (f.line.kept_share * 0.5 * n);
    const double a2 =
        std::max(0.0, f.line.amplitude * f.line.amplitude - noise);
    f.line.amplitude = std::sqrt(a2);
    // Re(c c^H) with c = J^T (cos + i sin).
    bracket += 0.5 * a2 *
               (f.jtu.col(0) * f.jtu.col(0).transpose() +
                f.jtu.col(1) * f.jtu.col(1).transpose());
    lines->push_back(f.line);
  }
  return bracket;
}

// The lag-window bracket sum_i sum_j J_i^T w c(i - j) J_j of one series,
// whose statistics are corr.
Eigen::MatrixXd LagBracket(const Eigen::MatrixXd& jacobian,
                           const Eigen::VectorXd& residual,
                           const SeriesCorrelation& corr) {
  const int n = static_cast<int>(residual.size());
  const int reach = std::min(n - 1, 2 * corr.lag_window);
  // Y = T J with T(i, j) = w(|i - j|) c(|i - j|): J^T T J costs N (2L+1) k
  // for Y and N k^2 for the product, not N^2 k^2.
  Eigen::MatrixXd y = corr.variance * jacobian;
  for (int lag = 1; lag <= reach; ++lag) {
    const double t =
        LagWeight(lag, corr.lag_window) * Autocovariance(residual, lag);
    if (t == 0.0) continue;
    y.topRows(n - lag) += t * jacobian.bottomRows(n - lag);
    y.bottomRows(n - lag) += t * jacobian.topRows(n - lag);
  }
  return jacobian.transpose() * y;
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
                                   const Eigen::MatrixXd& b,
                                   std::vector<SeriesCorrelation>* stats) {
  const int k = series.empty() ? 0 : series[0].jacobian.cols();
  Eigen::MatrixXd bracket = Eigen::MatrixXd::Zero(k, k);
  for (const ResidualSeries& s : series) {
    SeriesCorrelation corr = CorrelationOf(s.residual);
    Eigen::VectorXd rest = s.residual;
    bracket += LineBracket(s.jacobian, s.times, b, &rest, &corr.lines);
    // Without lines the rest is the whole residual, whose statistics are
    // at hand.
    bracket += LagBracket(
        s.jacobian, rest, corr.lines.empty() ? corr : CorrelationOf(rest));
    if (stats != nullptr) stats->push_back(std::move(corr));
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
