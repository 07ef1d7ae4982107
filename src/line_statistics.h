// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Statistics of residual series shared by the colored covariance and its
// reading-error terms: autocovariances and the lag window, and the test of
// a line against the periodogram around it.

#ifndef FIT3DOF_SRC_LINE_STATISTICS_H_
#define FIT3DOF_SRC_LINE_STATISTICS_H_

#include <Eigen/Core>
#include <vector>

namespace fit3dof {

// Lines looked for per series, the bins either side whose median power is
// a line's background, and the chance of a false line per series.
inline constexpr int kMostLines = 6;
inline constexpr int kBackgroundBins = 32;
inline constexpr double kFalseLineChance = 1e-4;

// The upper 0.1% point of the standard normal: the chance the residual
// checks allow noise (residual_check.cc, residual_description.cc, fit.cc).
inline constexpr double kZ999 = 3.0902323061678132;

// How far pure noise takes the probable error squared (Eq. 26, chi-square
// over its degrees of freedom, sd sqrt(2 / dof)) from 1 either way with
// chance 1e-3: kZ999 sqrt(2 / dof), dof = 3 points - free (at least 1).
double ProbableErrorSpread(int points, int free_parameters);

// Biased autocovariance c(k) = (1/N) sum_i r_i r_{i+k}.
double Autocovariance(const Eigen::VectorXd& r, int k);

// The lag window (colored_covariance.h): the last lag whose
// autocorrelation lies outside Bartlett's 3-sigma band, looked for until
// ten lags in a row lie inside it (or N/2); c0 = c(0).
int LagWindow(const Eigen::VectorXd& r, double c0);

// w(k) c(k) for k = 0..min(N - 1, 2L): the autocovariance of r as the
// colored covariance counts it for lag window L, the weight w 1 up to L
// and falling linearly to 0 at 2L.
std::vector<double> WindowedAutocovariance(const Eigen::VectorXd& r,
                                           int window);

// The median power of the kBackgroundBins bins either side of bins
// [lo, hi], two next to the band left out (where a line leaks); 0 when
// too few bins remain.
double BackgroundPower(const std::vector<double>& power, int lo, int hi);

// How far above its background a bin of noise rises with the given chance:
// a bin's power is exponentially distributed, its median ln 2 times its
// mean, so P(power > c median) = exp(-c ln 2).
double LineFactor(double chance);

// Cosine and sine of the phases (n x 2).
Eigen::MatrixXd CosSin(const Eigen::VectorXd& phase);

// The part of r that a pair of columns u (n x 2) explains,
// r^T u (u^T u)^-1 u^T r.
double Explained(const Eigen::MatrixXd& u, const Eigen::VectorXd& r);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_LINE_STATISTICS_H_
