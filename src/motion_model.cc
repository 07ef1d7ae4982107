// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/motion_model.h"

namespace fit3dof {

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
