// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Reading errors of the colored covariance (reading_errors.h): roll-locked
// lines and calibration terms, found in the residuals and counted whole.

#include "reading_errors.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>

#include "line_statistics.h"
#include "spectral_lines.h"
#include "symmetric_eigen.h"

namespace fit3dof {
namespace {

// Roll-locked lines whose regressors correlate more than this are one
// line seen at two aliased orders (RollHarmonics).
constexpr double kMaxTwinCorrelation = 0.5;
// Calibration terms tested: the channel's angle to the powers 2..3 (a
// bent and an S-shaped calibration curve), each counted when its
// projection exceeds 4.06 standard deviations (P(|Z| > 4.06) = 5e-5: the
// chance kFalseLineChance per series over the two powers).
constexpr int kCalibrationPowers[2] = {2, 3};
constexpr double kCalibrationZ = 4.06;

// The least lambda with a x = lambda b x (a symmetric, b positive
// definite), as Eigen's GeneralizedSelfAdjointEigenSolver finds it: the
// eigenvalues of L^-1 a L^-T, b = L L^T. Through SymmetricEigen, compiled
// once, rather than another instantiation of Eigen's solver here.
double LeastGeneralizedEigenvalue(const Eigen::MatrixXd& a,
                                  const Eigen::MatrixXd& b) {
  const Eigen::LLT<Eigen::MatrixXd> cholesky(b);
  Eigen::MatrixXd c = a.selfadjointView<Eigen::Lower>();
  cholesky.matrixL().solveInPlace<Eigen::OnTheLeft>(c);
  cholesky.matrixU().solveInPlace<Eigen::OnTheRight>(c);
  return SymmetricEigen(c).values()(0);
}

// The spin rate (Hz, signed) over samples [from, to] of the roll angle.
double SpinHz(const Eigen::VectorXd& t,
              const Eigen::VectorXd& roll,
              int from,
              int to) {
  return (roll(to) - roll(from)) / (2.0 * M_PI * (t(to) - t(from)));
}

// The bins [lo, hi] a band of frequencies [f_lo, f_hi] (Hz) shows at in a
// periodogram of n samples dt apart, aliases folded into 0..n/2.
std::pair<int, int> FoldedBand(double f_lo, double f_hi, int n, double dt) {
  const int half = n / 2;
  const double lo = f_lo * n * dt, hi = f_hi * n * dt;  // in bins
  const auto fold = [&](double bin) {
    const int m = static_cast<int>(std::lround(bin)) % n;
    return m <= half ? m : n - m;
  };
  // Each multiple of half the sampling rate folds the band back.
  const int turn_lo = static_cast<int>(lo / half);
  const int turn_hi = static_cast<int>(hi / half);
  const int a = fold(lo), c = fold(hi);
  if (turn_lo == turn_hi) return {std::min(a, c), std::max(a, c)};
  if (turn_hi > turn_lo + 1) return {0, half};
  // One fold: at an odd multiple the band reaches n/2, at an even one 0.
  if (turn_hi % 2 == 1) return {std::min(a, c), half};
  return {0, std::max(a, c)};
}

// The median power outside a band swept by a roll-locked line: its
// kBackgroundBins neighbours either side (BackgroundPower), or, for a band
// too wide for that, every bin outside it, or for one that covers nearly
// all, every bin (the line's own power then raises the bar).
double BandBackground(const std::vector<double>& power, int lo, int hi) {
  const double near = BackgroundPower(power, lo, hi);
  if (near > 0.0) return near;
  const int half = static_cast<int>(power.size()) - 1;
  std::vector<double> outside, all(power.begin() + 1, power.end());
  for (int j = 1; j <= half; ++j) {
    if (j < lo - 2 || j > hi + 2) outside.push_back(power[j]);
  }
  std::vector<double>& bins = outside.size() >= kBackgroundBins ? outside : all;
  if (bins.empty()) return 0.0;
  std::nth_element(bins.begin(), bins.begin() + bins.size() / 2, bins.end());
  return bins[bins.size() / 2];
}

// |sum_i r_i exp(-i h phi_i)|^2 for h = 1..kMaxRollOrder: the residual's
// power at each harmonic (order) of roll, on the periodogram's scale.
std::vector<double> OrderSpectrum(const Eigen::VectorXd& roll,
                                  const Eigen::VectorXd& r) {
  // In real arithmetic (std::complex's product checks for infinities,
  // __muldc3), and kChains samples at a time: each sample's powers of
  // exp(-i phi) are a chain of dependent products, and independent chains
  // side by side keep the multipliers busy.
  constexpr int kChains = 4;
  std::vector<double> re(kMaxRollOrder + 1, 0.0), im(kMaxRollOrder + 1, 0.0);
  const int n = static_cast<int>(r.size());
  for (int i0 = 0; i0 < n; i0 += kChains) {
    double c[kChains], s[kChains], zr[kChains], zi[kChains];
    for (int j = 0; j < kChains; ++j) {
      const bool in = i0 + j < n;
      c[j] = in ? std::cos(roll(i0 + j)) : 1.0;
      s[j] = in ? -std::sin(roll(i0 + j)) : 0.0;
      zr[j] = in ? r(i0 + j) : 0.0;
      zi[j] = 0.0;
    }
    for (int h = 1; h <= kMaxRollOrder; ++h) {
      double sum_r = 0.0, sum_i = 0.0;
      for (int j = 0; j < kChains; ++j) {
        const double next_r = zr[j] * c[j] - zi[j] * s[j];
        zi[j] = zr[j] * s[j] + zi[j] * c[j];
        zr[j] = next_r;
        sum_r += zr[j];
        sum_i += zi[j];
      }
      re[h] += sum_r;
      im[h] += sum_i;
    }
  }
  std::vector<double> power(kMaxRollOrder + 1, 0.0);
  for (int h = 1; h <= kMaxRollOrder; ++h) {
    power[h] = re[h] * re[h] + im[h] * im[h];
  }
  return power;
}

// A power no band's background (BandBackground) falls below: the median
// of m >= kBackgroundBins of the bins (or of all half of them) is at least
// the min(kBackgroundBins, half) / 2-th smallest of all. An order below
// the line factor times it needs no background.
double LeastBackground(const std::vector<double>& power) {
  std::vector<double> bins(power.begin() + 1, power.end());
  if (bins.empty()) return 0.0;
  const int rank =
      std::min<int>(kBackgroundBins, static_cast<int>(bins.size())) / 2;
  std::nth_element(bins.begin(), bins.begin() + rank, bins.end());
  return bins[rank];
}

// A reading error that is a function of what the instrument reads, as
// columns of one series: a roll-locked line (cos h phi, sin h phi), of
// random phase, or a calibration term (the channel's angle to a power),
// of unknown sign.
struct ReadingError {
  int series = 0;
  int roll_harmonic = 0;
  int calibration_power = 0;
  Eigen::MatrixXd u;
};

// Appends the harmonics of roll that stand out in r, the rest of series
// s, to `found` (at most kMostLines, strongest first): order h when its
// power exceeds the background of the band it sweeps by more than noise
// would with chance kFalseLineChance over the kMaxRollOrder orders tested.
void RollHarmonics(int s,
                   const Eigen::VectorXd& t,
                   const Eigen::VectorXd& roll,
                   const Eigen::VectorXd& r,
                   std::vector<ReadingError>* found) {
  const int n = static_cast<int>(r.size());
  const double dt = (t(n - 1) - t(0)) / (n - 1);
  const int eighth = std::max(1, n / 8);
  const double early = std::abs(SpinHz(t, roll, 0, eighth));
  const double late = std::abs(SpinHz(t, roll, n - 1 - eighth, n - 1));
  const double factor = LineFactor(kFalseLineChance / kMaxRollOrder);
  const std::vector<double> power =
      Periodogram(std::vector<double>(r.data(), r.data() + n));
  const std::vector<double> orders = OrderSpectrum(roll, r);
  const double least = factor * LeastBackground(power);
  std::vector<std::pair<double, int>> strong;  // (power / background, h)
  for (int h = 1; h <= kMaxRollOrder; ++h) {
    if (!(orders[h] > least)) continue;
    const auto [lo, hi] =
        FoldedBand(h * std::min(early, late), h * std::max(early, late), n, dt);
    // Within two bins of zero a harmonic of roll is a slow drift the
    // initial conditions and offsets absorb, not a line.
    if (lo < 2) continue;
    const double background = BandBackground(power, lo, hi);
    if (background > 0.0 && orders[h] > factor * background) {
      strong.push_back({orders[h] / background, h});
    }
  }
  std::sort(strong.rbegin(), strong.rend());
  // Sampled a few times per revolution, orders alias onto one another
  // (order h and h + m look alike when m revolutions fit a whole number of
  // samples, the spin's drift aside): of near twins only the strongest
  // is kept; fitting both would trade huge amplitudes between them.
  const size_t first = found->size();
  for (size_t i = 0; i < strong.size() && found->size() - first < kMostLines;
       ++i) {
    const int h = strong[i].second;
    Eigen::MatrixXd u = CosSin(h * roll);
    bool twin = false;
    for (size_t j = first; j < found->size(); ++j) {
      const Eigen::Matrix2d cross = u.transpose() * (*found)[j].u / (0.5 * n);
      twin = twin || Eigen::JacobiSVD<Eigen::Matrix2d>(cross).singularValues()(
                         0) > kMaxTwinCorrelation;
    }
    if (!twin) found->push_back({s, h, 0, std::move(u)});
  }
}

// The roll-locked lines of every series (RollHarmonics).
std::vector<ReadingError> RollErrors(
    const std::vector<ResidualSeries>& series,
    const std::vector<Eigen::VectorXd>& rests) {
  std::vector<ReadingError> found;
  for (size_t s = 0; s < series.size(); ++s) {
    const ResidualSeries& x = series[s];
    const int n = static_cast<int>(x.residual.size());
    if (n < 16 || x.roll.size() != n || x.times.size() != n ||
        !(x.times(n - 1) > x.times(0))) {
      continue;
    }
    RollHarmonics(static_cast<int>(s), x.times, x.roll, rests[s], &found);
  }
  return found;
}

// The variance of v^T r for r of the windowed autocovariance wc
// (WindowedAutocovariance).
double ColoredVariance(const Eigen::VectorXd& v,
                       const std::vector<double>& wc) {
  const int n = static_cast<int>(v.size());
  double var = wc[0] * v.squaredNorm();
  for (size_t lag = 1; lag < wc.size(); ++lag) {
    var += 2.0 * wc[lag] * v.head(n - lag).dot(v.tail(n - lag));
  }
  return var;
}

// The calibration terms of every series that carries its angle: power p of
// the angle when the residual's projection on it, as the fit leaves it,
// exceeds kCalibrationZ of its own standard deviation under the rest's
// autocorrelation in that series or in another of its segment. Both
// channels, because the fit couples them: a term left out of one would be
// fitted into the other's.
std::vector<ReadingError> CalibrationErrors(
    const std::vector<ResidualSeries>& series,
    const Eigen::MatrixXd& b,
    const std::vector<Eigen::VectorXd>& rests) {
  std::vector<ReadingError> candidates;
  std::vector<std::pair<int, int>> stands_out;  // (segment, power)
  for (size_t s = 0; s < series.size(); ++s) {
    const ResidualSeries& x = series[s];
    const int n = static_cast<int>(x.residual.size());
    if (n < 16 || x.angle.size() != n) continue;
    // Scaled to order one: the powers of radians are tiny.
    const double scale = x.angle.cwiseAbs().maxCoeff();
    if (!(scale > 0.0)) continue;
    const std::vector<double> wc = WindowedAutocovariance(
        rests[s], LagWindow(rests[s], Autocovariance(rests[s], 0)));
    for (int p = kCalibrationPowers[0]; p <= kCalibrationPowers[1]; ++p) {
      const Eigen::VectorXd u = (x.angle / scale).array().pow(p);
      const Eigen::VectorXd v =
          u - x.jacobian * (b * (x.jacobian.transpose() * u));
      const double var = ColoredVariance(v, wc);
      const double projection = v.dot(rests[s]);
      if (var > 0.0 &&
          projection * projection > kCalibrationZ * kCalibrationZ * var) {
        stands_out.push_back({x.segment, p});
      }
      candidates.push_back({static_cast<int>(s), 0, p, u});
    }
  }
  std::vector<ReadingError> found;
  for (ReadingError& c : candidates) {
    const std::pair<int, int> key{series[c.series].segment,
                                  c.calibration_power};
    if (std::find(stands_out.begin(), stands_out.end(), key) !=
        stands_out.end()) {
      found.push_back(std::move(c));
    }
  }
  return found;
}

// Reading errors of every series, fitted together and taken out of `rests`
// (one residual per series); returns their share of the bracket and
// appends each to its series' `lines`. Together, because the fit couples
// the channels: what it absorbs of an error in theta shows in psi's
// residual too (the channels are the two halves of one coning motion), and
// an error fitted to one channel alone would be taken for part of the
// echo. A line of random phase and amplitude a adds (a^2 / 2) Re(c c^H),
// c = J^T (cos + i sin); a term of unknown sign and size a, a^2 c c^T.
Eigen::MatrixXd JointBracket(const std::vector<ResidualSeries>& series,
                             const Eigen::MatrixXd& b,
                             std::vector<ReadingError> found,
                             std::vector<Eigen::VectorXd>* rests,
                             std::vector<std::vector<ResidualLine>>* lines) {
  const int k = static_cast<int>(b.rows());
  // Errors the fit could absorb whole leave nothing to measure them by:
  // they stay in the residuals' autocorrelation. Dropped one at a time,
  // the least kept first, as each changes what the others keep.
  for (;;) {
    const int m = static_cast<int>(found.size());
    if (m == 0) return Eigen::MatrixXd::Zero(k, k);
    std::vector<int> first(m + 1, 0);  // first column of each error
    for (int l = 0; l < m; ++l) first[l + 1] = first[l] + found[l].u.cols();
    const int cols = first[m];
    // G = B J^T U: the fit's response to each column; K_s = U_s - J_s G.
    Eigen::MatrixXd jtu(k, cols);
    for (int l = 0; l < m; ++l) {
      jtu.middleCols(first[l], found[l].u.cols()) =
          series[found[l].series].jacobian.transpose() * found[l].u;
    }
    const Eigen::MatrixXd g = b * jtu;
    std::vector<Eigen::MatrixXd> kept(series.size());
    Eigen::MatrixXd ktk = Eigen::MatrixXd::Zero(cols, cols);
    Eigen::VectorXd ktr = Eigen::VectorXd::Zero(cols);
    for (size_t s = 0; s < series.size(); ++s) {
      kept[s] = -series[s].jacobian * g;
      for (int l = 0; l < m; ++l) {
        if (found[l].series == static_cast<int>(s))
          kept[s].middleCols(first[l], found[l].u.cols()) += found[l].u;
      }
      ktk += kept[s].transpose() * kept[s];
      ktr += kept[s].transpose() * (*rests)[s];
    }
    // Kept share: the least of K^T K over U^T U, in any direction.
    std::vector<double> share(m);
    int worst = 0;
    for (int l = 0; l < m; ++l) {
      const int c = found[l].u.cols();
      const Eigen::MatrixXd utu = found[l].u.transpose() * found[l].u;
      share[l] =
          LeastGeneralizedEigenvalue(ktk.block(first[l], first[l], c, c), utu);
      if (share[l] < share[worst]) worst = l;
    }
    if (share[worst] < kMinKeptShare) {
      found.erase(found.begin() + worst);
      continue;
    }
    const Eigen::LDLT<Eigen::MatrixXd> solve(ktk);
    const Eigen::VectorXd alpha = solve.solve(ktr);
    const Eigen::MatrixXd inverse =
        solve.solve(Eigen::MatrixXd::Identity(cols, cols));
    for (size_t s = 0; s < series.size(); ++s) {
      (*rests)[s] -= kept[s] * alpha;
    }
    Eigen::MatrixXd bracket = Eigen::MatrixXd::Zero(k, k);
    for (int l = 0; l < m; ++l) {
      const ReadingError& f = found[l];
      const int c = f.u.cols();
      const Eigen::VectorXd& rest = (*rests)[f.series];
      const int n = static_cast<int>(rest.size());
      // The amplitude's share of the noise, var tr(block of (K^T K)^-1),
      // taken off.
      const double noise = rest.squaredNorm() / n *
                           inverse.block(first[l], first[l], c, c).trace();
      const double a2 =
          std::max(0.0, alpha.segment(first[l], c).squaredNorm() - noise);
      const Eigen::MatrixXd cj = jtu.middleCols(first[l], c);
      bracket += a2 / c * (cj * cj.transpose());
      ResidualLine line;
      const ResidualSeries& x = series[f.series];
      if (f.roll_harmonic > 0) {
        line.frequency_hz =
            f.roll_harmonic * std::abs(SpinHz(x.times, x.roll, 0, n - 1));
      }
      line.roll_harmonic = f.roll_harmonic;
      line.calibration_power = f.calibration_power;
      line.kept_share = share[l];
      // A calibration term's coefficient multiplies (angle / largest)^p:
      // it is the error at the largest angle.
      line.amplitude = std::sqrt(a2);
      (*lines)[f.series].push_back(line);
    }
    return bracket;
  }
}

}  // namespace

Eigen::MatrixXd ReadingErrorBracket(
    const std::vector<ResidualSeries>& series,
    const Eigen::MatrixXd& b,
    std::vector<Eigen::VectorXd>* rests,
    std::vector<std::vector<ResidualLine>>* lines) {
  // Reading errors that follow roll first, then calibration terms in what
  // they leave.
  Eigen::MatrixXd bracket =
      JointBracket(series, b, RollErrors(series, *rests), rests, lines);
  bracket += JointBracket(
      series, b, CalibrationErrors(series, b, *rests), rests, lines);
  return bracket;
}

}  // namespace fit3dof
