// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Parameter covariance when the residuals are not white (Morelli and Klein,
// "Accuracy of aircraft parameter estimates from flight test data", 1995;
// SIDPAC's colores):
//
//   Cov = B [ sum_i sum_j J_i^T rho(i - j) J_j ] B,   B = (J^T J)^-1,
//
// with J the Jacobian of the weighted residuals and rho the residuals' own
// autocorrelation, estimated separately for every series (a channel of a
// segment: phi, theta, psi each have their own error). For white residuals
// only rho(0) remains and Cov = B * (each series' residual variance): the
// report's Eq. 27 with a variance per channel instead of one E^2.
//
// The lag window is chosen from the data, per series: L is the last lag at
// which the sample autocorrelation lies outside Bartlett's 3-sigma band for it,
// +-3 sqrt((1 + 2 sum_{j<k} rho_j^2) / N) (the band of an autocorrelation
// that has died out after lag k - 1), looked for until ten lags in a row
// lie inside (or N/2). Lags up to L count in full, lags L..2L with weights
// falling linearly to zero. Why: white residuals stop at once (L = 0: no
// spurious correction), an AR(1) error is kept for its whole memory (a
// Bartlett window, weights falling from lag 0, would lose about 10% of an
// AR(1) with coefficient 0.8 at the same L), and a periodic error, such as
// a roll-angle reading error, whose autocorrelation never decays, is kept
// until the band (which widens with every significant lag) covers it. The
// bracket is made positive semidefinite by dropping negative eigenvalues.
//
// Spectral lines (a reading error that follows roll, at the spin rate and
// its harmonics) need more: where such a line lies near the motion's own
// frequencies the fit absorbs much of it, so the residuals keep only a part
// and their autocorrelation understates what the error does to the
// estimates. Each line that stands above its neighbourhood of the residual
// periodogram (a 0.1% chance per series for noise) is fitted, frequency
// refined, as the fit would leave it: K = (I - H) [cos sin], H = J B J^T,
// r ~ K alpha. Then |alpha| estimates the error's own amplitude a (less the
// noise's share of it), the line with its echo near the motion's
// frequencies leaves the residual, and the line comes back whole: for a
// sinusoid of random phase, with c = J^T (cos + i sin), its exact share of
// the bracket is (a^2 / 2) Re(c c^H). A line with kept share (smallest
// eigenvalue of K^T K over n / 2) below kMinKeptShare is one the fit
// could absorb whole; nothing measures it, and it stays in the
// autocorrelation part.
//
// Reading errors, functions of what the instrument reads (a roll-locked
// line, a calibration curve), are found first and counted whole the same
// way (reading_errors.h); the search over time frequencies runs on what
// they leave.

#ifndef FIT3DOF_SRC_COLORED_COVARIANCE_H_
#define FIT3DOF_SRC_COLORED_COVARIANCE_H_

#include <Eigen/Core>
#include <vector>

namespace fit3dof {

// One series: Jacobian rows (one per sample, in time order, k columns),
// the weighted residuals, the sample times (s) and, when roll-locked lines
// are to be looked for, the roll angle (rad; else empty), and for
// calibration terms the channel's own angle (rad; else empty). Series of
// one segment share `segment`.
struct ResidualSeries {
  Eigen::MatrixXd jacobian;
  Eigen::VectorXd residual;
  Eigen::VectorXd times;
  Eigen::VectorXd roll;
  Eigen::VectorXd angle;
  int segment = 0;
  // The least lag window the bracket uses, whatever the residuals' own
  // (the filter-error fit's, filter_error.h).
  int min_lag_window = 0;
};

// A spectral line of a series' residual and what the fit absorbed of it.
struct ResidualLine {
  double frequency_hz = 0.0;
  double kept_share = 1.0;    // what the fit leaves of it, 0..1
  double amplitude = 0.0;     // the error's, estimated
  int roll_harmonic = 0;      // h for a line of phase h phi, else 0
  int calibration_power = 0;  // p for a calibration term, else 0
};

// Harmonics (orders) of the roll angle tested as roll-locked lines: a
// once-per-revolution reading error is order 1, a roll angle sensed in
// steps of 2 deg has lines at orders 180, 360, ...; 720 reaches steps of
// half a degree.
inline constexpr int kMaxRollOrder = 720;

// Lines the fit leaves less of than this are not taken out.
inline constexpr double kMinKeptShare = 0.05;

// What the estimate found in one series.
struct SeriesCorrelation {
  double variance = 0.0;            // rho(0), mean square residual
  int lag_window = 0;               // L (lags to 2L weighted)
  std::vector<double> normalized;   // rho(k) / rho(0), k = 1..10
  double ljung_box = 0.0;           // Q over lags 1..ljung_box_lags
  double ljung_box_limit = 0.0;     // its 1% critical value
  int ljung_box_lags = 0;           // 20, or half the samples if fewer
  bool white = true;                // Q below the limit
  std::vector<ResidualLine> lines;  // taken out and added back whole
};

// The autocorrelation statistics of one series of residuals.
SeriesCorrelation CorrelationOf(const Eigen::VectorXd& residual);

// The bracket sum_i sum_j J_i^T rho(i - j) J_j over every series (k x k),
// positive semidefinite, with the spectral lines added back whole; b is
// (J^T J)^-1 of all series together. `stats` (if given) receives each
// series' statistics (those of its whole residual) and lines.
Eigen::MatrixXd ColoredInformation(const std::vector<ResidualSeries>& series,
                                   const Eigen::MatrixXd& b,
                                   std::vector<SeriesCorrelation>* stats);

// Cov = B M B for B = (J^T J)^-1 (or its pseudo-inverse) and the bracket M.
Eigen::MatrixXd SandwichCovariance(const Eigen::MatrixXd& b,
                                   const Eigen::MatrixXd& bracket);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_COLORED_COVARIANCE_H_
