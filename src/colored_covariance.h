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

#ifndef FIT3DOF_SRC_COLORED_COVARIANCE_H_
#define FIT3DOF_SRC_COLORED_COVARIANCE_H_

#include <Eigen/Core>
#include <vector>

namespace fit3dof {

// One series: Jacobian rows (one per sample, in time order, k columns) and
// the weighted residuals.
struct ResidualSeries {
  Eigen::MatrixXd jacobian;
  Eigen::VectorXd residual;
};

// What the estimate found in one series.
struct SeriesCorrelation {
  double variance = 0.0;           // rho(0), mean square residual
  int lag_window = 0;              // L (lags to 2L weighted)
  std::vector<double> normalized;  // rho(k) / rho(0), k = 1..10
  double ljung_box = 0.0;          // Q over lags 1..20
  double ljung_box_limit = 0.0;    // its 1% critical value
  bool white = true;               // Q below the limit
};

// The autocorrelation statistics of one series of residuals.
SeriesCorrelation CorrelationOf(const Eigen::VectorXd& residual);

// The bracket sum_i sum_j J_i^T rho(i - j) J_j over every series (k x k),
// positive semidefinite; `stats` (if given) receives each series'
// statistics.
Eigen::MatrixXd ColoredInformation(const std::vector<ResidualSeries>& series,
                                   std::vector<SeriesCorrelation>* stats);

// Cov = B M B for B = (J^T J)^-1 (or its pseudo-inverse) and the bracket M.
Eigen::MatrixXd SandwichCovariance(const Eigen::MatrixXd& b,
                                   const Eigen::MatrixXd& bracket);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_COLORED_COVARIANCE_H_
