// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Parameter scaling (scaling.h): the factors between the report's units and
// the internal units of the equations of motion (REG and REGOUT).

#include "fit3dof/scaling.h"

#include <cmath>

#include "fit3dof/angles.h"

namespace fit3dof {

std::vector<double> InternalScaleFactors(ModelKind model,
                                         const Body& body,
                                         const Flow& flow) {
  const double qsd = flow.dynamic_pressure * body.area * body.diameter;
  const double rate = body.diameter / (2.0 * flow.velocity);
  // The symmetric program has one transverse inertia I (= I_y).
  const double iz = model == ModelKind::kSymmetric ? body.Iy : body.Iz;
  const auto& table = ParameterTable(model);
  std::vector<double> factors(table.size(), 1.0);
  for (size_t i = 0; i < table.size(); ++i) {
    switch (table[i].scaling) {
      case Scaling::kPitchStatic:
        factors[i] = qsd / body.Iy;
        break;
      case Scaling::kPitchRate:
        factors[i] = qsd / body.Iy * rate;
        break;
      case Scaling::kYawStatic:
        factors[i] = qsd / iz;
        break;
      case Scaling::kYawRate:
        factors[i] = qsd / iz * rate;
        break;
      case Scaling::kRollStatic:
        factors[i] = qsd / body.Ix;
        break;
      case Scaling::kRollRate:
        factors[i] = qsd / body.Ix * rate;
        break;
      case Scaling::kAngle:
      case Scaling::kAngleRate:
        factors[i] = kDegree;
        break;
      case Scaling::kInertia:
      case Scaling::kPerSecond:
      case Scaling::kSecond:
      case Scaling::kRatio:
      case Scaling::kUnused:
        factors[i] = 1.0;
        break;
    }
  }
  return factors;
}

}  // namespace fit3dof
