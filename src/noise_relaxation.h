// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// sigma: auto. Maximum likelihood with an unknown noise level per channel
// and segment, by relaxation (as SIDPAC's oe and FVSysID do): at the
// solution, each auto channel's weight becomes that channel's RMS residual
// in that segment (the likelihood's estimate of its noise), the fit is
// solved again from where it is with the new weights, and so on until no
// weight changes by more than 1% (at most 10 rounds). Channels with a
// configured sigma keep it.
//
// The relaxation needs a start, and the fit before it needs weights that
// mean something: its rule for local minima (a probable error above
// solver.max_probable_error calls for restarts, multi_start.h) compares
// the residuals with sigma. A fixed 1 deg let a fit that lost the motion
// (2.8 deg RMS in theta) pass as at the noise level. So the auto channels
// start at the data's own noise level, measured without a model
// (DataNoiseDeg).

#ifndef FIT3DOF_SRC_NOISE_RELAXATION_H_
#define FIT3DOF_SRC_NOISE_RELAXATION_H_

#include <string>
#include <vector>

#include "fit3dof/case.h"
#include "fit_problem.h"

namespace fit3dof {

struct RelaxationOutcome {
  int rounds = 0;      // weight updates made
  int iterations = 0;  // Levenberg-Marquardt iterations of the refits
  bool settled = false;
  std::string summary;  // for the pipeline: the weights it settled on
};

// A model-free estimate of a channel's noise (deg) from its samples: the
// RMS of the d-th differences over sqrt(C(2d, d)), their gain for white
// noise, at the first of the lowest two orders of d = 2..8 that each keep
// 0.9 of the order before (the least over the orders where none do). A motion
// sampled more than six times per cycle shrinks with each order, white
// noise keeps its level, so the first order where it stops shrinking has
// the noise and the least spread (errors slower than the sampling, a
// calibration curve, count less; a wild point more).
// At least 1e-4 deg: a record without noise must not get a weight that
// the integration's own error exceeds. Times are taken as evenly spaced.
double DataNoiseDeg(const std::vector<double>& samples);

// Sets each auto channel's weight in every segment of `problem` to its
// DataNoiseDeg: the starting values of the relaxation.
void StartNoiseWeights(const Case& c, FitProblem* problem);

// Updates the auto channels' weights in `problem`'s segments and `values`
// (global free order) to the relaxed solution. Nothing to do (rounds = 0)
// when no channel is auto. Throws InputError if the motion cannot be
// integrated at the solution.
RelaxationOutcome RelaxNoiseWeights(const Case& c,
                                    FitProblem* problem,
                                    std::vector<double>* values);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_NOISE_RELAXATION_H_
