// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Error bars at a fit's solution (AEDC-TR-78-10, Section 3.2):
//
//   sum of residuals  S = sqrt(sum of squared weighted residuals)   Eq. 32
//   probable error    E = sqrt(S^2 / (3 N - N_free))               Eq. 26
//   RMS error         E sqrt(B_i), B = (J^T J)^-1                   Eq. 27
//
// Beside them the standard error, which stays honest when the residuals
// are not white noise (colored_covariance.h):
//
//   Cov = B [sum_i sum_j J_i^T rho(i - j) J_j] B,
//
// with rho each channel's (and segment's) own residual autocorrelation;
// for white residuals it is Eq. 27 with a variance per channel.
//
// B comes from the singular values of the weighted Jacobian (what
// ceres::Covariance's DENSE_SVD computes, from the Jacobian already
// evaluated) with the free coordinates scaled to unit Jacobian columns, so
// that its conditioning test measures correlation, not units. What the data
// cannot determine is named instead of given a number: a parameter without
// effect on the motion, a singular direction (with the combination that is
// determined), pairs correlated above 0.99 and groups of three or more nearly
// dependent parameters (the report's Eq. 43).

#ifndef FIT3DOF_SRC_UNCERTAINTY_H_
#define FIT3DOF_SRC_UNCERTAINTY_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "colored_covariance.h"
#include "fit_problem.h"

namespace fit3dof {

struct Uncertainty {
  double sum_of_residuals = 0.0;  // S, Eq. 32
  // E, Eq. 26. A parameter the data do not determine spends no degree of
  // freedom, so the others get the error bars of a fit with it frozen.
  double probable_error = 0.0;
  std::vector<double> rms;  // Eq. 27, global free order; NaN where not
                            // determined
  // The standard errors to quote: the covariance with each channel's own
  // residual variance and autocorrelation (colored_covariance.h), global
  // free order; NaN where not determined.
  std::vector<double> standard_error;
  // Each segment's phi, theta, psi residual statistics (segment-major).
  std::vector<SeriesCorrelation> series;
  Eigen::MatrixXd correlation;  // NaN rows and columns where not determined
  // The coordinates u = value / scale in which J^T J has unit diagonal
  // (assembly.h); the fitted motion is computed in them, as the solver did.
  std::vector<double> scale;
  std::vector<std::string> warnings;  // what the data cannot determine
};

// The error bars of `problem`'s free coordinates at `values` (global free
// order). `source` names the config if the motion cannot be integrated
// there (InputError).
Uncertainty EstimateUncertainty(const FitProblem& problem,
                                const std::vector<double>& values,
                                const std::string& source);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_UNCERTAINTY_H_
