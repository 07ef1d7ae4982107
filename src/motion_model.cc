// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The motion model (motion_model.h): the active parameter set and the
// double instantiations of the templated integration.

#include "fit3dof/motion_model.h"

#include <cstdio>

#include "fit3dof/input_error.h"

namespace fit3dof {

void CheckIntegrationSteps(double steps,
                           double span,
                           double max_step,
                           const std::string& source) {
  if (steps <= kMaxIntegrationSteps) return;
  char text[256];
  std::snprintf(text,
                sizeof(text),
                ": integrating the motion would take %.3g RK4 steps per "
                "evaluation (%.6g s of record at solver.step = %.3g s); at "
                "most %.0e: check that the time column is in seconds and "
                "solver.step",
                steps,
                span,
                max_step,
                kMaxIntegrationSteps);
  throw InputError(source + text);
}

MotionModel::MotionModel(const ModelSpec& spec, const ActiveSet& active)
    : spec_(spec),
      active_(active),
      scale_(InternalScaleFactors(spec.model, spec.body, spec.flow)) {}

ActiveSet ActiveParameters(const std::vector<double>& values,
                           const std::vector<bool>& free) {
  ActiveSet active;
  for (size_t i = 0; i < values.size(); ++i) {
    active[i] = values[i] != 0.0 || (i < free.size() && free[i]);
  }
  return active;
}

template bool MotionModel::Evaluate<double>(
    const double*, const double*, int, double*, IntegrationFailure*) const;
template bool MotionModel::EvaluateStates<double>(
    const double*, const double*, int, double*, IntegrationFailure*) const;

}  // namespace fit3dof
