// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Conversion of the parameters between the report's units and the internal
// units of the equations of motion (the listings' REG and REGOUT). Inside,
// a moment divided by its moment of inertia is
//
//   M / I = (q S d / I) * (static coefficient terms)
//         + (q S d / I) * (d / 2U) * (rate coefficient terms),
//
// so every coefficient is multiplied once by its factor and the equations
// then work with rates in rad/s and angles in radians.

#ifndef FIT3DOF_SCALING_H_
#define FIT3DOF_SCALING_H_

#include <vector>

#include "fit3dof/body.h"
#include "fit3dof/parameters.h"

namespace fit3dof {

// internal value = report value * factor, per parameter of ParameterTable.
std::vector<double> InternalScaleFactors(ModelKind model,
                                         const Body& body,
                                         const Flow& flow);

}  // namespace fit3dof

#endif  // FIT3DOF_SCALING_H_
