// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Spectral lines of a residual series (spectral_lines.h).

#include "spectral_lines.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <unsupported/Eigen/FFT>

namespace fit3dof {

namespace {

// |FFT(x - mean)|^2 at bins 1 .. bins - 1 (bin 0 is 0), x real or complex.
template <typename T>
std::vector<double> CentredPower(const std::vector<T>& x, int bins) {
  const int n = static_cast<int>(x.size());
  T mean = T();
  for (const T& v : x) mean += v / static_cast<double>(n);
  std::vector<T> centred(n);
  for (int i = 0; i < n; ++i) centred[i] = x[i] - mean;
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, centred);
  std::vector<double> power(bins, 0.0);
  for (int k = 1; k < bins; ++k) power[k] = std::norm(spectrum[k]);
  return power;
}

// The mean ordinate of a periodogram `power` (k = 1 .. n - 1; k = 0, the
// mean, unused) but the line's own at `peak_k`: that bin, the two next to
// it, and the same three about its mirror, n - peak_k (a line in one
// channel of theta + i psi shows at both +f and -f). A line's own power is
// no measure of the noise beside it, and the floor LocalLine sets at half
// the mean had been mostly the line's: on 38 samples a buzz of the pitch
// reading 4.8 times the noise, halfway between two bins, passed for noise
// in 1996 of 2000 records (now in about half; a line on a bin is found in
// every one, and noise alone as rarely as before).
double MeanBesideLine(const std::vector<double>& power, int peak_k) {
  const int n = static_cast<int>(power.size());
  double sum = 0.0;
  int bins = 0;
  for (int k = 1; k < n; ++k) {
    const int from_peak = std::abs(k - peak_k);
    const int from_mirror = std::abs(k - (n - peak_k));
    if (std::min({from_peak, n - from_peak, from_mirror, n - from_mirror}) <=
        1) {
      continue;
    }
    sum += power[k];
    ++bins;
  }
  return bins > 0 ? sum / bins : 0.0;
}

}  // namespace

// The neighbourhood is up to n / 16 bins on each side, at least 4, the two
// next to the line left out (a line between two bins spreads into them).
// The global test (peak over the mean of all bins) must let colored noise
// pass, whose spectrum rises threefold toward low frequencies at a lag-1
// autocorrelation of 0.5; a line standing out of its own neighbourhood is
// structure whatever the color around it (Coulomb friction left a line 20
// times its surroundings that a Magnus moment and a nonlinear damping did
// not remove, below the global limit of 4 ln N = 27 on 800 samples).
double LocalLine(const std::vector<double>& power, int peak_k, double* ratio) {
  const int n = static_cast<int>(power.size());
  const int half = std::max(4, n / 16);
  double sum = 0.0;
  int bins = 0;
  for (int d = 2; d <= half + 1; ++d) {
    for (int k : {peak_k - d, peak_k + d}) {
      const int wrapped = ((k % n) + n) % n;  // two-sided: k < 0 is -f
      if (wrapped == 0) continue;
      sum += power[wrapped];
      ++bins;
    }
  }
  // The fit takes the noise out of the bins its parameters reach (the
  // modes' frequencies, the lowest ones), and a neighbourhood of such
  // bins is no measure of the noise: on a 47-sample coning run the true
  // model's own residual had a peak 5.3 times the mean of all bins, 28
  // times that of neighbours the fit had emptied. The neighbourhood's mean
  // is taken as at least half the mean of the bins beside the line.
  const double local = std::max(bins > 0 ? sum / bins : 0.0,
                                0.5 * MeanBesideLine(power, peak_k));
  *ratio = local > 0.0 ? power[peak_k] / local : 0.0;
  // An exponential ordinate over the mean of `bins` others exceeds x with
  // chance (1 + x / bins)^-bins; over n bins, 1e-3 in all.
  return bins * (std::pow(n / 1e-3, 1.0 / bins) - 1.0);
}

namespace {

// The lines of a real series' periodogram `power` (bins 0 .. n / 2 of n
// samples every `dt` seconds) above `factor` ln(n) times its mean
// (SpectralLines).
std::vector<SpectralLine> LinesAboveMean(const std::vector<double>& power,
                                         int n,
                                         double dt,
                                         double factor,
                                         int most) {
  const int half = n / 2;
  double total = 0.0;
  for (int k = 1; k <= half; ++k) total += power[k];
  const double mean_power = total / half;
  if (!(mean_power > 0.0)) return {};
  const double limit = factor * std::log(static_cast<double>(n)) * mean_power;
  std::vector<SpectralLine> lines;
  for (int k = 1; k <= half; ++k) {
    const bool peak =
        power[k] >= power[k - 1] && (k == half || power[k] >= power[k + 1]);
    if (peak && power[k] > limit) {
      lines.push_back({k / (n * dt), power[k] / mean_power});
    }
  }
  std::sort(lines.begin(),
            lines.end(),
            [](const SpectralLine& a, const SpectralLine& b) {
              return a.power_ratio > b.power_ratio;
            });
  if (static_cast<int>(lines.size()) > most) lines.resize(most);
  return lines;
}

// LocalSpectralLine on a real series' periodogram `power` (bins 0 .. n / 2
// of n samples every `dt` seconds): the two-sided periodogram LocalLine
// reads is its mirror image, ordinate n - k being k's.
bool LocalLineOf(const std::vector<double>& power,
                 int n,
                 double dt,
                 SpectralLine* line) {
  std::vector<double> two_sided(n);
  for (int k = 0; k < n; ++k) two_sided[k] = power[std::min(k, n - k)];
  int peak_k = 1;
  for (int k = 2; k <= n / 2; ++k) {
    if (power[k] > power[peak_k]) peak_k = k;
  }
  double ratio = 0.0;
  const double limit = LocalLine(two_sided, peak_k, &ratio);
  if (!(ratio > limit)) return false;
  *line = {peak_k / (n * dt), ratio};
  return true;
}

}  // namespace

std::vector<double> Periodogram(const std::vector<double>& x) {
  return CentredPower(x, static_cast<int>(x.size()) / 2 + 1);
}

std::vector<double> Periodogram(const std::vector<std::complex<double>>& z) {
  return CentredPower(z, static_cast<int>(z.size()));
}

std::vector<SpectralLine> SpectralLines(const std::vector<double>& x,
                                        double dt,
                                        double factor,
                                        int most) {
  const int n = static_cast<int>(x.size());
  if (n < 16 || !(dt > 0.0)) return {};
  return LinesAboveMean(Periodogram(x), n, dt, factor, most);
}

bool LocalSpectralLine(const std::vector<double>& x,
                       double dt,
                       SpectralLine* line) {
  const int n = static_cast<int>(x.size());
  if (n < 16 || !(dt > 0.0)) return false;
  return LocalLineOf(Periodogram(x), n, dt, line);
}

std::vector<SpectralLine> ResidualLines(const std::vector<double>& x,
                                        double dt) {
  const int n = static_cast<int>(x.size());
  if (n < 16 || !(dt > 0.0)) return {};
  // One periodogram for both tests.
  const std::vector<double> power = Periodogram(x);
  std::vector<SpectralLine> lines =
      LinesAboveMean(power, n, dt, kLineFactor, kMostLinesNamed);
  SpectralLine local;
  if (!LocalLineOf(power, n, dt, &local)) return lines;
  for (const SpectralLine& line : lines) {
    if (line.frequency_hz == local.frequency_hz) return lines;  // one bin
  }
  lines.push_back(local);
  return lines;
}

}  // namespace fit3dof
