// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Initial conditions from the data (the report's INLCON = 0). The listing's
// ICS takes the first sample and a two-point difference, which puts the
// full measurement noise (amplified by 1/dt) into the starting rates. Here
// each channel gets a least-squares polynomial over the first samples
// (local polynomial regression, e.g. Savitzky-Golay smoothing evaluated at
// the end point), whose value and slope at the first time are the angle and
// its rate.

#ifndef FIT3DOF_INITIAL_CONDITIONS_H_
#define FIT3DOF_INITIAL_CONDITIONS_H_

#include <array>

#include "fit3dof/parameters.h"
#include "fit3dof/time_history.h"

namespace fit3dof {

struct PolynomialEstimate {
  double value = 0.0;  // at the first sample time
  double slope = 0.0;  // per second
};

// Least-squares polynomial of `degree` through the first `count` samples of
// (t, y), evaluated at t[0].
PolynomialEstimate LocalPolynomial(const std::vector<double>& t,
                                   const std::vector<double>& y,
                                   int count,
                                   int degree);

// The six initial-condition parameters of `model` (report units, in the
// model's order: symmetric phi0, phidot0, theta0, thetadot0, psi0,
// psidot0; asymmetric phi0, theta0, psi0, p0, q0, r0) at the record's first
// sample. The measured theta and psi include the offsets theta_T and psi_T
// (deg), which are removed first.
std::array<double, 6> EstimateInitialConditions(ModelKind model,
                                                const TimeHistory& record,
                                                double theta_offset,
                                                double psi_offset);

}  // namespace fit3dof

#endif  // FIT3DOF_INITIAL_CONDITIONS_H_
