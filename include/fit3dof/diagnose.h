// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The discrepancy workflow (`fit3dof diagnose`): fit the model as
// configured, decide whether the residuals are measurement noise, and if
// not find the missing effect, add it, refit, and repeat (the report's
// Section 5.3 done systematically).
//
// Noise or model? The residuals are at the noise level when the probable
// error (Eq. 26, residuals in units of the configured sigma) is below
// `noise_limit` (1.1), no channel's residual has a lag-1 autocorrelation
// above `whiteness_limit` (0.3), and the periodogram of theta + i psi has
// no line above `spectral_limit` (4 ln N) times its mean: measurement noise
// is white with a flat spectrum, a missing effect leaves slow, structured
// residuals with lines near the motion's frequencies.
//
// Which effect? Every catalog effect not yet in the model is scored at the
// current solution by a score (Lagrange-multiplier) test: with g = J_c^T r
// the gradient of the cost along the candidate's parameters (at zero) and
// S_c = I_cc - I_cf I_ff^-1 I_fc the candidate's information after the
// parameters already free have taken what they can (the Schur complement,
// which handles correlation with them, e.g. Cm_alpha, t1, t3 of Eq. 43),
//   LM = g^T S_c^+ g / E^2
// is the predicted drop of the weighted residual sum of squares in units of
// the residual variance. The score is a local (linear) prediction and
// underrates large effects (a product of inertia that moves roll by degrees
// ranked fourth in a test), so the best `refit` (5) candidates are refitted
// in full;
// the one with the lowest Bayesian information criterion,
//   BIC = n ln(RSS / n) + k ln(n)   (n residuals, k free parameters),
// is added if it lowers BIC by more than `min_bic_drop` (10: very strong
// evidence). The loop stops at the noise level or when no candidate is
// significant.

#ifndef FIT3DOF_DIAGNOSE_H_
#define FIT3DOF_DIAGNOSE_H_

#include <string>
#include <vector>

#include "fit3dof/case.h"
#include "fit3dof/fit.h"

namespace fit3dof {

struct Effect {
  std::string id;
  std::string description;
  std::vector<std::string> symmetric;   // parameters in the symmetric model
  std::vector<std::string> asymmetric;  // and in the asymmetric one
  bool to_asymmetric = false;           // needs the asymmetric program
};

const std::vector<Effect>& EffectCatalog();

struct DiagnoseOptions {
  double noise_limit = 1.1;
  double whiteness_limit = 0.3;
  double spectral_factor = 4.0;  // spectral_limit = factor * ln(N)
  int refit = 5;
  double min_bic_drop = 10.0;
  int max_steps = 5;
  std::vector<std::string> effects;  // restrict the catalog (empty: all)
};

struct ResidualCheck {
  double probable_error = 0.0;
  ChannelValues rms_deg;
  ChannelValues lag1;  // autocorrelation at lag 1
  // Periodogram of the complex residual theta + i psi (first segment): the
  // largest power over the mean power, and where it sits. White noise
  // gives about ln(N); a missing effect a sharp line near the motion's
  // frequencies.
  double peak_ratio = 0.0;
  double peak_frequency_hz = 0.0;
  bool at_noise_level = false;
};

struct CandidateScore {
  std::string effect;
  double score = 0.0;  // LM statistic
  int dof = 0;         // directions not already spanned
};

struct DiagnosisStep {
  std::string effect;
  std::string description;
  std::vector<ParameterEstimate> parameters;
  double score = 0.0;
  double bic_drop = 0.0;
  std::vector<CandidateScore> ranking;
  ResidualCheck after;
};

struct Diagnosis {
  ResidualCheck initial;
  ResidualCheck final;
  std::vector<DiagnosisStep> steps;
  std::string verdict;
  Case final_case;
  std::vector<FitResult> fits;  // the fit before the first step, then one
                                // per step
};

ResidualCheck CheckResiduals(const FitResult& fit,
                             const DiagnoseOptions& options);

// Throws InputError for bad input (as Fit does).
Diagnosis Diagnose(const Case& c, const DiagnoseOptions& options);

std::string DiagnosisJson(const Diagnosis& d, const Case& noise_reference);
// `sigma`: the stated noise level, quoted beside the residuals.
std::string FormatDiagnosis(const Diagnosis& d, const ChannelValues& sigma);

}  // namespace fit3dof

#endif  // FIT3DOF_DIAGNOSE_H_
