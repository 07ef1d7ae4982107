// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A fit's motion at another integration step. The config's step (DTMIN)
// is often far finer than the record needs: at a step of 2 ms on a 3-s run
// of 10 samples per cycle, 8 ms moves every fitted value by less than 0.01
// of its error. diagnose fits a few hundred models of one record; it
// integrates them at the coarsest step the record allows
// (SolverOptions::search_step, case.h) and FitSamples keeps such a fit
// only where its motion at its solution stays within kStepChiSquare of
// the motion at the config's step, fitting it again at a finer step
// otherwise (at the config's own, last).
//
// Why the sum of squares bounds the values: a model error e (the two
// motions' difference, weighted as the residuals) moves the least-squares
// solution by dp = -(J'J)^-1 J'e, and dp' (J'J) dp = |P e|^2 <= |e|^2, P
// the projection on J's columns. With J'J the inverse of the covariance
// (weighted residuals), each value moves by at most sqrt(|e|^2) of its
// standard error: 0.1 at kStepChiSquare.
//
// Example Usage:
//
//   const FitResult nominal = Fit(c);
//   Case searched = c;
//   searched.solver.search_step =
//       CoarsestStep(c, data, nominal, kStepChiSquare / 16);
//   const FitResult fit = FitSamples(searched, data);  // fit.step: its own

#ifndef FIT3DOF_INTEGRATION_STEP_H_
#define FIT3DOF_INTEGRATION_STEP_H_

#include <vector>

#include "fit3dof/case.h"
#include "fit3dof/fit.h"
#include "fit3dof/time_history.h"

namespace fit3dof {

// The most a fit at a search step may differ from the config's step: the
// weighted sum of squares of the two motions' difference at its solution.
inline constexpr double kStepChiSquare = 0.01;

// The weighted sum of squares (the weights those of `fit`'s residuals) of
// the difference between the motion of `fit`'s solution integrated at
// `step` and at c.solver.step, over every sample of `data` (the samples
// `fit`, a fit of `c`, was fitted to). Infinity where either motion cannot
// be integrated.
double StepChiSquare(const Case& c,
                     const std::vector<TimeHistory>& data,
                     const FitResult& fit,
                     double step);

// The coarsest of c.solver.step times 2, 4, ... 32 whose motion at `fit`'s
// solution stays within `chi_square` of the motion at c.solver.step
// (StepChiSquare), no coarser than the record's widest sample interval
// (one substep per sample); c.solver.step itself when none does.
double CoarsestStep(const Case& c,
                    const std::vector<TimeHistory>& data,
                    const FitResult& fit,
                    double chi_square);

}  // namespace fit3dof

#endif  // FIT3DOF_INTEGRATION_STEP_H_
