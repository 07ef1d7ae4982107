// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// sigma: auto. Maximum likelihood with an unknown noise level per channel
// and segment, by relaxation (as SIDPAC's oe and FVSysID do): at the
// solution, each auto channel's weight becomes that channel's RMS residual
// in that segment (the likelihood's estimate of its noise), the fit is
// solved again from where it is with the new weights, and so on until no
// weight changes by more than 1% (at most 10 rounds). Channels with a
// configured sigma keep it.

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

// Updates the auto channels' weights in `problem`'s segments and `values`
// (global free order) to the relaxed solution. Nothing to do (rounds = 0)
// when no channel is auto. Throws InputError if the motion cannot be
// integrated at the solution.
RelaxationOutcome RelaxNoiseWeights(const Case& c,
                                    FitProblem* problem,
                                    std::vector<double>* values);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_NOISE_RELAXATION_H_
