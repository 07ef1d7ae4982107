// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The residual-correlation correction of the parameter covariance
// (colored_covariance.h).

#include "colored_covariance.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "line_statistics.h"
#include "reading_errors.h"
#include "spectral_lines.h"
#include "symmetric_eigen.h"

namespace fit3dof {
namespace {

constexpr int kReportedLags = 10;
constexpr int kLjungBoxLags = 20;
// 1% upper quantile of the standard normal: the Ljung-Box limit.
constexpr double kZ99 = 2.3263478740408408;
// The grid that refines each line's frequency within one bin either side.
constexpr int kRefineSteps = 20;

// Chi-square quantile by Wilson and Hilferty's cube-root approximation
// (within 1% of the exact value for 20 degrees of freedom).
double ChiSquareQuantile(int dof, double z) {
  const double a = 2.0 / (9.0 * dof);
  return dof * std::pow(1.0 - a + z * std::sqrt(a), 3);
}

// Frequencies (Hz) of the periodogram peaks that stand above their
// background (BackgroundPower; kFalseLineChance over the half spectrum).
// Against a local median a coloured continuum (an AR(1) error) shows no
// lines; against the mean its low-frequency bins would.
std::vector<double> LineFrequencies(const std::vector<double>& power,
                                    int n,
                                    double dt) {
  const int half = n / 2;
  const double factor = LineFactor(kFalseLineChance / half);
  std::vector<std::pair<double, int>> peaks;
  for (int k = 1; k < half; ++k) {
    if (power[k] < power[k - 1] || power[k] < power[k + 1]) continue;
    const double background = BackgroundPower(power, k, k);
    if (background > 0.0 && power[k] > factor * background)
      peaks.push_back({power[k], k});
  }
  std::sort(peaks.rbegin(), peaks.rend());
  std::vector<double> frequencies;
  for (size_t p = 0; p < peaks.size() && p < kMostLines; ++p) {
    frequencies.push_back(peaks[p].second / (n * dt));
  }
  return frequencies;
}

Eigen::MatrixXd CosSinAt(const Eigen::VectorXd& t, double frequency_hz) {
  return CosSin(2.0 * M_PI * frequency_hz * t);
}

// The pair u as the fit leaves it, (I - J B J^T) u; jtu (if given)
// receives J^T u.
Eigen::MatrixXd Kept(const Eigen::MatrixXd& jacobian,
                     const Eigen::MatrixXd& b,
                     const Eigen::MatrixXd& u,
                     Eigen::MatrixXd* jtu = nullptr) {
  const Eigen::MatrixXd ju = jacobian.transpose() * u;
  if (jtu != nullptr) *jtu = ju;
  return u - jacobian * (b * ju);
}

// Explained(Kept(jacobian, b, u), r) without forming the n x 2 kept
// pair: with C = J^T u, K^T r = u^T r - C^T (B J^T r) and K^T K =
// u^T u - 2 C^T B C + C^T (B J^T J B) C. RefineFrequency evaluates it
// for a score of frequencies of one series.
class KeptExplained {
 public:
  KeptExplained(const Eigen::MatrixXd& jacobian,
                const Eigen::MatrixXd& b,
                const Eigen::VectorXd& r)
      : jacobian_(jacobian),
        b_(b),
        r_(r),
        bjtr_(b * (jacobian.transpose() * r)),
        bgb_(b * (jacobian.transpose() * jacobian) * b) {}

  double operator()(const Eigen::MatrixXd& u) const {
    // Two dot products per column of J: a GEMM's packing costs more here.
    const Eigen::MatrixXd c = jacobian_.transpose().lazyProduct(u);
    const Eigen::Vector2d ktr = u.transpose() * r_ - c.transpose() * bjtr_;
    const Eigen::Matrix2d ktk = u.transpose() * u -
                                2.0 * c.transpose() * b_ * c +
                                c.transpose() * bgb_ * c;
    return ktr.dot(ktk.ldlt().solve(ktr));
  }

 private:
  const Eigen::MatrixXd& jacobian_;
  const Eigen::MatrixXd& b_;
  const Eigen::VectorXd& r_;
  const Eigen::VectorXd bjtr_;
  const Eigen::MatrixXd bgb_;
};

// Rotates each row of the pair u (cos, sin of a phase) by the phase of
// the same row of d: the pair at the sum of the phases, without trig.
void Rotate(const Eigen::MatrixXd& d, Eigen::MatrixXd* u) {
  for (int i = 0; i < u->rows(); ++i) {
    const double c = (*u)(i, 0), s = (*u)(i, 1);
    (*u)(i, 0) = c * d(i, 0) - s * d(i, 1);
    (*u)(i, 1) = s * d(i, 0) + c * d(i, 1);
  }
}

// The frequency near `guess` (within one bin, 1 / span, on a grid of
// 1 / kRefineSteps of a bin) at which a sinusoid, as the fit leaves it,
// explains most of r: every kCoarse-th grid point first, then the grid
// around the best of them. The sinusoids of a pass are one rotation
// apart, so each pass costs two evaluations of the trig functions.
double RefineFrequency(const Eigen::MatrixXd& jacobian,
                       const Eigen::MatrixXd& b,
                       const Eigen::VectorXd& r,
                       const Eigen::VectorXd& t,
                       double guess) {
  constexpr int kCoarse = 4;
  const double bin = 1.0 / (t(t.size() - 1) - t(0));
  const auto frequency = [&](int s) { return guess + bin * s / kRefineSteps; };
  const KeptExplained explained(jacobian, b, r);
  int best = 0;
  double best_power = -1.0;
  // Grid points from..to (within +-kRefineSteps), every step-th.
  const auto pass = [&](int from, int to, int step) {
    from = std::max(from, -kRefineSteps);
    to = std::min(to, kRefineSteps);
    const Eigen::MatrixXd turn = CosSinAt(t, frequency(step) - guess);
    Eigen::MatrixXd u = CosSinAt(t, frequency(from));
    for (int s = from; s <= to; s += step) {
      if (s > from) Rotate(turn, &u);
      if (!(frequency(s) > 0.0)) continue;
      const double power = explained(u);
      if (power > best_power) {
        best_power = power;
        best = s;
      }
    }
  };
  pass(-kRefineSteps, kRefineSteps, kCoarse);
  pass(best - kCoarse + 1, best + kCoarse - 1, 1);
  return frequency(best);
}

// A line found in a series: what is reported, and J^T u for its bracket.
struct FoundLine {
  ResidualLine line;
  Eigen::MatrixXd jtu;
};

// Fits the pair u, as the fit leaves it, to r and takes it out of r (with
// the echo the fit's absorption spread near the motion's frequencies).
// False for a pair the fit could absorb whole (kept share below
// kMinKeptShare): nothing measures it, and it stays in the residual's
// autocorrelation.
bool TakeOut(const Eigen::MatrixXd& jacobian,
             const Eigen::MatrixXd& b,
             const Eigen::MatrixXd& u,
             Eigen::VectorXd* r,
             FoundLine* f) {
  const int n = static_cast<int>(r->size());
  const Eigen::MatrixXd kept = Kept(jacobian, b, u, &f->jtu);
  const Eigen::Matrix2d ktk = kept.transpose() * kept;
  f->line.kept_share =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(ktk).eigenvalues()(0) /
      (0.5 * n);
  if (f->line.kept_share < kMinKeptShare) return false;
  const Eigen::Vector2d alpha = ktk.ldlt().solve(kept.transpose() * *r);
  *r -= kept * alpha;
  f->line.amplitude = alpha.norm();
  return true;
}

// Takes each significant line of fixed frequency out of `r` and returns
// their share of the bracket, (a^2 / 2) Re(c c^H)
// (colored_covariance.h). Fitted as the fit leaves it, a line's amplitude
// is the error's own, and what the fit's absorption of it spilled onto
// other frequencies goes with it instead of showing up as a line of its
// own.
Eigen::MatrixXd LineBracket(const ResidualSeries& series,
                            const Eigen::MatrixXd& b,
                            Eigen::VectorXd* r,
                            std::vector<ResidualLine>* lines) {
  const Eigen::MatrixXd& jacobian = series.jacobian;
  const Eigen::VectorXd& t = series.times;
  const int n = static_cast<int>(r->size());
  const int k = static_cast<int>(jacobian.cols());
  Eigen::MatrixXd bracket = Eigen::MatrixXd::Zero(k, k);
  if (n < 16 || t.size() != n || !(t(n - 1) > t(0))) return bracket;
  const double dt = (t(n - 1) - t(0)) / (n - 1);
  std::vector<FoundLine> found;
  const std::vector<double> power =
      Periodogram(std::vector<double>(r->data(), r->data() + n));
  for (double frequency : LineFrequencies(power, n, dt)) {
    FoundLine f;
    f.line.frequency_hz = RefineFrequency(jacobian, b, *r, t, frequency);
    if (TakeOut(jacobian, b, CosSinAt(t, f.line.frequency_hz), r, &f))
      found.push_back(std::move(f));
  }
  // The amplitudes' share of the background noise: E|alpha|^2 = a^2 +
  // var tr((K^T K)^-1), K = (I - H) u, taken off each.
  const double background = r->squaredNorm() / n;
  for (FoundLine& f : found) {
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
  const std::vector<double> wc =
      WindowedAutocovariance(residual, corr.lag_window);
  // Y = T J with T(i, j) = w(|i - j|) c(|i - j|): J^T T J costs N (2L+1) k
  // for Y and N k^2 for the product, not N^2 k^2.
  Eigen::MatrixXd y = corr.variance * jacobian;
  for (size_t lag = 1; lag < wc.size(); ++lag) {
    const double t = wc[lag];
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
  s.ljung_box_lags = lags;
  s.ljung_box_limit = lags > 0 ? ChiSquareQuantile(lags, kZ99) : 0.0;
  s.white = !(s.ljung_box > s.ljung_box_limit);
  return s;
}

Eigen::MatrixXd ColoredInformation(const std::vector<ResidualSeries>& series,
                                   const Eigen::MatrixXd& b,
                                   std::vector<SeriesCorrelation>* stats) {
  std::vector<Eigen::VectorXd> rests;
  for (const ResidualSeries& s : series) rests.push_back(s.residual);
  std::vector<std::vector<ResidualLine>> lines(series.size());
  Eigen::MatrixXd bracket = ReadingErrorBracket(series, b, &rests, &lines);
  for (size_t i = 0; i < series.size(); ++i) {
    const ResidualSeries& s = series[i];
    SeriesCorrelation corr = CorrelationOf(s.residual);
    corr.lines = std::move(lines[i]);
    Eigen::VectorXd& rest = rests[i];
    bracket += LineBracket(s, b, &rest, &corr.lines);
    // Without lines the rest is the whole residual, whose statistics are
    // at hand.
    SeriesCorrelation of_rest = corr.lines.empty() ? corr : CorrelationOf(rest);
    of_rest.lag_window = std::max(of_rest.lag_window, s.min_lag_window);
    bracket += LagBracket(s.jacobian, rest, of_rest);
    if (stats != nullptr) stats->push_back(std::move(corr));
  }
  // Symmetric and positive semidefinite: a truncated, tapered sum of
  // sampled autocorrelations need not be.
  const Eigen::MatrixXd symmetric = 0.5 * (bracket + bracket.transpose());
  const SymmetricEigen eigen(symmetric);
  const Eigen::VectorXd lambda = eigen.values().cwiseMax(0.0);
  return eigen.vectors() * lambda.asDiagonal() * eigen.vectors().transpose();
}

Eigen::MatrixXd SandwichCovariance(const Eigen::MatrixXd& b,
                                   const Eigen::MatrixXd& bracket) {
  return b * bracket * b;
}

}  // namespace fit3dof
