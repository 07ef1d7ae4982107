// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Starting values from the motion itself, for free parameters given no
// value (`value: auto`).
//
// Pitch and yaw. For small angles, linear aerodynamics and constant spin p,
// the complex angle z = theta + i psi of the symmetric program (Eq. 6 with
// the moments of Table 4b) obeys
//
//   z'' - (C2 + i R p) z' - (C1 + i C4 p) z = 0,
//
// with C1 = Cm_alpha q S d / I, C2 = Cm_q q S d / I d/2U and C4 = Cm_p_alpha
// q S d / I d/2U (the internal constants of scaling.h). Its solution is the
// tricyclic motion of Murphy (BRL Report 1216, 1963) and Nicolaides: two
// damped rotating arms K_j exp(s_j t) about a trim point. With s_1 and s_2
// measured,
//
//   C2 = Re(s1 + s2),   R p = Im(s1 + s2),
//   C1 = -Re(s1 s2),    C4 p = -Im(s1 s2).
//
// The exponents come from the matrix-pencil method (Hua and Sarkar, IEEE
// Trans. ASSP 38(5), 1990) on the first few cycles of the differenced record
// (differencing removes the trim arm): a rank-2 SVD of the Hankel matrix of
// the samples, then the eigenvalues exp(s_j dt) of the shift between its
// leading singular vectors. The method is robust to measurement noise,
// unlike a plain two-term linear prediction (Prony).
//
// Roll. The roll record gives the spin p(t) (a quadratic fit of the
// unwrapped phi) and its rate pdot = Mx = C10 + C13 p: Cl_p = pdot / p (or
// Cl_0 = pdot when only Cl_0 is free).
//
// Terms without a linear-theory estimate (nonlinear, tunnel, trim) start at
// zero. The asymmetric program gets the symmetric estimates for its pitch
// and yaw counterparts (Cm_alpha, -Cn_beta; Cm_q, Cn_r; Cm_p_beta,
// Cn_p_alpha).

#ifndef FIT3DOF_START_VALUES_H_
#define FIT3DOF_START_VALUES_H_

#include <complex>
#include <string>
#include <vector>

#include "fit3dof/case.h"
#include "fit3dof/time_history.h"

namespace fit3dof {

struct EpicyclicFit {
  bool ok = false;
  std::complex<double> s1, s2;  // exponents (1/s), fast arm first
  std::string message;          // why not, when !ok
};

// The two arms of theta + i psi over the first `cycles` cycles of a record
// sampled at (nearly) constant spacing.
EpicyclicFit FitEpicycle(const TimeHistory& record, double cycles = 4.0);

// Fills the starting values of the parameters that `auto_start` marks
// (report units, positions of ParameterTable(c.model)) in `values`, from
// `record` (the first segment's samples). Returns one line per estimate for
// the log and the report.
std::vector<std::string> EstimateStartValues(
    const Case& c,
    const TimeHistory& record,
    const std::vector<bool>& auto_start,
    std::vector<double>* values);

}  // namespace fit3dof

#endif  // FIT3DOF_START_VALUES_H_
