// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Are the residuals measurement noise? (CheckResiduals, diagnose.h): the
// probable error, each channel's lag-1 autocorrelation and the periodogram
// of theta + i psi.

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "fit3dof/diagnose.h"
#include "line_statistics.h"
#include "spectral_lines.h"

namespace fit3dof {
namespace {

// The spread of E^2 when sigma is the noise the data show without a model
// (sigma: auto, DiagnoseOptions::noise_held): `spread`, what noise alone
// gives (ProbableErrorSpread), with the estimate's own added.
// DataNoiseDeg's mean square of the d-th differences of white noise over n
// samples has relative variance about (2 / n) sum_k rho_k^2 = (2 / n)
// C(4d, 2d) / C(2d, d)^2, at most 7.3 / n for its orders up to 8: on a
// 47-sample run E may reach 1.51 by chance (1.14 on 800), where a
// configured sigma allows 1.12 (1.05). `points`: the samples the estimate
// pooled (all segments', Diagnose).
double HeldSpread(double spread, int points) {
  constexpr double kDataNoiseVariance = 7.3;  // 2 C(32, 16) / C(16, 8)^2
  return std::hypot(
      spread, kZ999 * std::sqrt(kDataNoiseVariance / std::max(1, points)));
}

}  // namespace

ChannelValues ResidualLag1(const FitResult& fit) {
  ChannelValues lag;
  for (int ch = 0; ch < 3; ++ch) {
    double num = 0.0, den = 0.0;
    for (const SegmentFit& s : fit.segments) {
      const std::vector<double> r = ChannelResidual(s, ch);
      double mean = 0.0;
      for (int i = 0; i < s.data.size(); ++i) mean += r[i] / s.data.size();
      for (int i = 0; i + 1 < s.data.size(); ++i)
        num += (r[i] - mean) * (r[i + 1] - mean);
      for (int i = 0; i < s.data.size(); ++i)
        den += (r[i] - mean) * (r[i] - mean);
    }
    lag[ch] = den > 0.0 ? num / den : 0.0;
  }
  return lag;
}

ResidualCheck CheckResiduals(const FitResult& fit,
                             const DiagnoseOptions& options) {
  ResidualCheck check;
  check.probable_error = fit.probable_error;
  check.rms_deg = fit.rms_residual_deg;
  check.lag1 = ResidualLag1(fit);
  const ChannelValues& lag = check.lag1;
  // Periodogram of theta + i psi residuals over the first segment.
  double spectral_limit = 1e300;
  double line_limit = 1e300;
  if (!fit.segments.empty() && fit.segments[0].data.size() >= 16) {
    const SegmentFit& s = fit.segments[0];
    const int n = s.data.size();
    std::vector<std::complex<double>> z(n);
    for (int i = 0; i < n; ++i) {
      z[i] = {s.computed[3 * i + 1] - s.data.theta[i],
              s.computed[3 * i + 2] - s.data.psi[i]};
    }
    const std::vector<double> power = Periodogram(z);
    double total = 0.0, peak = 0.0;
    int peak_k = 0;
    for (int k = 1; k < n; ++k) {  // the mean (k = 0) is not a line
      total += power[k];
      if (power[k] > peak) {
        peak = power[k];
        peak_k = k;
      }
    }
    check.peak_ratio = total > 0.0 ? peak / (total / (n - 1)) : 0.0;
    line_limit = LocalLine(power, peak_k, &check.line_ratio);
    const double duration = s.data.t.back() - s.data.t.front();
    const int signed_k = peak_k <= n / 2 ? peak_k : peak_k - n;
    check.peak_frequency_hz = signed_k * (n - 1) / (n * duration);
    spectral_limit = options.spectral_factor * std::log(static_cast<double>(n));
  }
  // The limits never below what noise itself reaches with chance 1e-3 on
  // a record this short: E^2 is chi-square over its degrees of freedom
  // (sd sqrt(2 / dof)), a lag-1 autocorrelation of noise has sd
  // 1 / sqrt(n). On 47 samples E = 1.12 or a lag-1 autocorrelation of 0.4
  // is one noise record in twenty.
  const double spread = ProbableErrorSpread(fit.points, fit.free_parameters);
  const double noise_limit = std::max(
      options.noise_limit,
      std::sqrt(1.0 + (options.noise_held ? HeldSpread(spread, fit.points)
                                          : spread)));
  const double whiteness_limit =
      std::max(options.whiteness_limit,
               kZ999 / std::sqrt(std::max(1.0, 1.0 * fit.points)));
  // One-sided: a missing effect is smooth at the sampling (10 or more
  // points per cycle of the motion, a slow roll) and raises the lag-1
  // autocorrelation. A fit lowers that of noise instead (the directions it
  // removes are smooth): on two 47-sample runs with 19 free parameters the
  // true model's theta residual had -0.36, beyond the limit of 0.32.
  const double worst = std::max({lag[0], lag[1], lag[2]});
  check.noise_limit = noise_limit;
  check.whiteness_limit = whiteness_limit;
  check.white = worst < whiteness_limit && check.peak_ratio < spectral_limit &&
                check.line_ratio < line_limit;
  check.at_noise_level = fit.probable_error < noise_limit && check.white;
  check.independent = !ResidualsDepend(fit);
  check.below_sigma = fit.probable_error * fit.probable_error < 1.0 - spread;
  return check;
}

}  // namespace fit3dof
