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
  const std::vector<double> power = Periodogram(x);
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

}  // namespace fit3dof
