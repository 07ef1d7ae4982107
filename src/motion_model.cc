// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The motion model (motion_model.h): the active parameter set and the
// double instantiations of the templated integration.

#include "fit3dof/motion_model.h"

#include <cstdio>

#include "fit3dof/input_error.h"

namespace fit3dof {
namespace {

// A coefficient of q S d: a moment that follows the dynamic pressure.
bool IsMomentCoefficient(Scaling scaling) {
  switch (scaling) {
    case Scaling::kPitchStatic:
    case Scaling::kPitchRate:
    case Scaling::kYawStatic:
    case Scaling::kYawRate:
    case Scaling::kRollStatic:
    case Scaling::kRollRate:
      return true;
    default:
      return false;
  }
}

}  // namespace

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
      scale_(InternalScaleFactors(spec.model, spec.body, spec.flow)) {
  symmetric_.ratio = spec_.body.Ix / spec_.body.Iy;
  symmetric_.incidence = spec_.incidence;
  asymmetric_.Ix = spec_.body.Ix;
  asymmetric_.Iy = spec_.body.Iy;
  asymmetric_.Iz = spec_.body.Iz;
  asymmetric_.incidence = spec_.incidence;
  layout_ = Layout(spec_.model);
  if (spec_.model == ModelKind::kSymmetric) {
    state_index_ = {kSymPhi, kSymTheta, kSymPsi};
    for (const KinematicRow& row : kSymmetricKinematics) {
      kinematic_rate_[row.angle] = row.rate;
    }
  } else {
    state_index_ = {kAsymPhi, kAsymTheta, kAsymPsi};
  }
  const int ri = layout_.roll_interaction;
  roll_interaction_ =
      active_[ri] || active_[ri + 1] || active_[ri + 2] || active_[ri + 3];
  const int r2 = layout_.roll_harmonic2;
  roll_harmonic2_ =
      active_[r2] || active_[r2 + 1] || active_[r2 + 2] || active_[r2 + 3];
  calibration_ =
      active_[layout_.calibration] || active_[layout_.calibration + 1];
  calibration_square_ = active_[layout_.calibration_square] ||
                        active_[layout_.calibration_square + 1];
  drift_ = active_[layout_.drift] || active_[layout_.drift + 1];
  lag_ = active_[layout_.lag] || active_[layout_.lag + 1];
  gain_ = active_[layout_.gain];
  if (active_[layout_.q_drift]) {
    const auto& table = ParameterTable(spec_.model);
    for (int i = 0; i < static_cast<int>(table.size()); ++i) {
      if (active_[i] && IsMomentCoefficient(table[i].scaling)) {
        drifting_.push_back(i);
      }
    }
  }
  // A moment coefficient as an angular acceleration, as scaling.cc turns
  // Cl_0, Cm and Cn (q S d / I of the axis; one I in the symmetric model).
  const double qsd =
      spec_.flow.dynamic_pressure * spec_.body.area * spec_.body.diameter;
  const double iz =
      spec_.model == ModelKind::kSymmetric ? spec_.body.Iy : spec_.body.Iz;
  moment_scale_ = {qsd / spec_.body.Ix, qsd / spec_.body.Iy, qsd / iz};
}

std::shared_ptr<const MotionModel> MotionModel::WithMaxStep(
    double max_step) const {
  CHECK_GT(max_step, 0.0);
  auto coarser = std::make_shared<MotionModel>(*this);
  coarser->spec_.max_step = max_step;
  return coarser;
}

StateGuard MotionModel::Guard() const {
  StateGuard guard;
  guard.theta_index =
      spec_.model == ModelKind::kSymmetric ? int{kSymTheta} : int{kAsymTheta};
  return guard;
}

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
