// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// What a fit leaves behind (format: docs/formats.md):
//   DIR/report.json  the coefficients, their RMS errors (Eq. 27), the
//                    probable error (Eq. 26), the sum of residuals (Eq. 32),
//                    correlations and warnings;
//   DIR/fit.csv      the report's DATA FIT COMPARISON: t, phi, phi_fit,
//                    theta, theta_fit, psi, psi_fit (and segment);
// and a readable table for the terminal. Files are written atomically.

#ifndef FIT3DOF_FIT_REPORT_H_
#define FIT3DOF_FIT_REPORT_H_

#include <string>

#include "fit3dof/fit.h"

namespace fit3dof {

std::string ReportJson(const FitResult& result);
std::string FitComparisonCsv(const FitResult& result);
std::string FormatFitTable(const FitResult& result);

// Writes report.json and fit.csv into `dir` (created if missing).
void WriteFitOutputs(const std::string& dir, const FitResult& result);

}  // namespace fit3dof

#endif  // FIT3DOF_FIT_REPORT_H_
