// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The model's mass properties and the free stream, in the report's units
// (ft, ft^2, slug ft^2, ft/s, lbf/ft^2).

#ifndef FIT3DOF_BODY_H_
#define FIT3DOF_BODY_H_

namespace fit3dof {

struct Body {
  double area = 0.0;      // reference area S, ft^2
  double diameter = 0.0;  // reference length d, ft
  double Ix = 0.0;        // roll moment of inertia, slug ft^2
  double Iy = 0.0;        // pitch moment of inertia
  double Iz = 0.0;        // yaw moment of inertia (symmetric model: = Iy)
};

struct Flow {
  double velocity = 0.0;          // U, ft/s
  double dynamic_pressure = 0.0;  // q = rho U^2 / 2, lbf/ft^2
};

}  // namespace fit3dof

#endif  // FIT3DOF_BODY_H_
