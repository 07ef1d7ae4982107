// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The filter-error fit (solver: {method: filter_error} with a
// process_noise block). Output error integrates the motion open loop over
// the whole record, so a random moment the model lacks (flow
// unsteadiness, turbulence, bearing pressure: the report's Section 6)
// accumulates into phase errors that bias the coefficients and make the
// error bars meaningless. Here an extended Kalman filter
// (MotionModel::Filter) corrects the state at every sample; the residuals
// are its innovations, whitened by their covariances; and the
// process-noise intensities (and the noise levels of sigma: auto
// channels) are estimated with the coefficients by maximum likelihood.
//
// The relaxation of Maine and Iliff's MMLE3 and Jategaonkar's FVSysID
// (ml_fem), one round:
//   1. the intensities of the `auto` axes and the sigmas of the auto
//      channels minimize the deviance D = sum_i e_i^T S_i^-1 e_i +
//      log det S_i (twice the negative log likelihood) with the
//      coefficients held: Brent's method in their logarithms, one
//      coordinate after the other;
//   2. the filter at those gives the gains K_i and covariances S_i;
//   3. Levenberg-Marquardt (SolveStage) on the coefficients and initial
//      conditions with K_i and S_i held: residuals L_i^-1 e_i, S_i = L_i
//      L_i^T, their derivatives those of the held-gain filter
//      (MotionModel::EvaluateFiltered with Jets);
// until D changes by less than kDevianceTolerance. The error bars are the
// Gauss-Newton information of the held-gain innovations, as the
// filter-error method's: the output-error uncertainty code on the final
// filter's residuals. An intensity's error comes from D's curvature in its
// logarithm.
//
// Why a filter and not the smoothing equivalent (weak-constraint multiple
// shooting, windows with their own states tied by continuity residuals):
// that was built first and measured (2026-11-22). Windows long enough to
// keep the coefficients identifiable let the random moment act unchecked
// within each window, and the intensities came out 3-7x the truth with
// Cm_q's scatter 5x its error; windows of a few samples diverged from the
// usual starts. The filter corrects at every sample and its likelihood
// sets the intensity with no window to choose.

#ifndef FIT3DOF_SRC_FILTER_ERROR_H_
#define FIT3DOF_SRC_FILTER_ERROR_H_

#include <vector>

#include "continuation.h"
#include "fit3dof/case.h"
#include "fit3dof/fit.h"
#include "fit_problem.h"

namespace fit3dof {

// Fits `problem` (starting from problem->values) by the filter-error
// method; `values` gets the solution (global free order). The segments
// keep the final filter's innovation weights and, for auto channels, the
// estimated sigmas, so that the uncertainty computed from `problem`
// afterwards is the filter's. Fills result->process_noise and adds the
// rounds to result's iterations and pipeline.
PipelineOutcome SolveFilterError(const Case& c,
                                 FitProblem* problem,
                                 std::vector<double>* values,
                                 FitResult* result);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_FILTER_ERROR_H_
