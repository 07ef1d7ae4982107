// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Lines in the spectrum of a residual series: the frequencies whose
// periodogram power stands above `factor` ln(N) times the mean power (white
// noise reaches that only by chance: its largest of N/2 powers is about
// ln(N) times the mean). A reading error that follows roll shows lines at
// the spin rate and its harmonics, a missing aerodynamic term near the
// motion's own frequencies.

#ifndef FIT3DOF_SRC_SPECTRAL_LINES_H_
#define FIT3DOF_SRC_SPECTRAL_LINES_H_

#include <complex>
#include <vector>

namespace fit3dof {

struct SpectralLine {
  double frequency_hz = 0.0;
  double power_ratio = 0.0;  // over the mean power (LocalSpectralLine: its
                             // neighbourhood's)
};

// The periodogram of x: |FFT(x - mean)|^2 at bins 0..N/2 (bin k is
// k / (N dt) Hz); bin 0 is 0, the mean being removed.
std::vector<double> Periodogram(const std::vector<double>& x);

// The two-sided periodogram of a complex series z (theta + i psi: a
// whirl's sense is the sign of its frequency): |FFT(z - mean)|^2 at bins
// 0..N-1, bin k above N/2 being the negative frequency (k - N) / (N dt)
// Hz; bin 0 is 0.
std::vector<double> Periodogram(const std::vector<std::complex<double>>& z);

// SpectralLines' defaults: lines above 4 ln(N) times the mean power, the
// strongest three.
inline constexpr double kLineFactor = 4.0;
inline constexpr int kMostLinesNamed = 3;

// The strongest lines (at most `most`, strongest first) of `x` sampled
// every `dt` seconds; none for fewer than 16 samples.
std::vector<SpectralLine> SpectralLines(const std::vector<double>& x,
                                        double dt,
                                        double factor = kLineFactor,
                                        int most = kMostLinesNamed);

// The test of one line against its own neighbourhood, which colored noise
// (a spectrum rising smoothly toward low frequencies) passes where the
// global test against the mean of all bins may not. `power` is a
// two-sided periodogram (k = 1 .. n - 1; k = 0, the mean, unused), the
// line's largest ordinate at `peak_k`: its ratio to the mean of its
// neighbours (the two next to it left out; at least half the mean of every
// ordinate but the line's own, that bin, the two next to it and the same
// three about its mirror n - peak_k, where a line of a real series shows
// too) into *ratio; returns the ratio that noise with a smooth spectrum
// exceeds with chance 1e-3 over the n bins.
double LocalLine(const std::vector<double>& power, int peak_k, double* ratio);

// The largest ordinate of the real series `x` (sampled every `dt` seconds,
// at least 16 samples) in *line when it stands out of its own
// neighbourhood (LocalLine on x's two-sided periodogram, the residual
// check's test); false when it does not.
bool LocalSpectralLine(const std::vector<double>& x,
                       double dt,
                       SpectralLine* line);

// The lines of a residual series `x`: SpectralLines' (strongest first),
// then the largest ordinate when it stands out of its own neighbourhood
// and is not among them (LocalSpectralLine). A strong line of a short
// record is much of the mean SpectralLines measures it against: draw
// 165's tunnel buzz of the pitch reading (38 samples), which the residual
// check called structure, had been described as no line at all.
std::vector<SpectralLine> ResidualLines(const std::vector<double>& x,
                                        double dt);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_SPECTRAL_LINES_H_
