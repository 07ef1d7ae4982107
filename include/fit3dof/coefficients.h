// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A read-only view of a model's parameters in internal units (the listings'
// CON array), indexed by the report's 1-based parameter number so that the
// moment models read like the Fortran MBAR subroutines.
//
// `active` marks the parameters whose terms are evaluated. A parameter that
// is frozen at exactly zero contributes nothing, so its term is skipped:
// with Jets every skipped product saves a full derivative-vector operation,
// which is what makes a fit with a few free parameters of the 72-parameter
// model cheap.

#ifndef FIT3DOF_COEFFICIENTS_H_
#define FIT3DOF_COEFFICIENTS_H_

#include <bitset>
#include <utility>

#include "fit3dof/parameters.h"

namespace fit3dof {

using ActiveSet = std::bitset<kMaxParameters>;

template <typename T>
class CoefficientView {
 public:
  CoefficientView(const T* internal, const ActiveSet& active)
      : internal_(internal), active_(active) {}

  // Report index (1-based), as in Table 4b / 4c.
  bool on(int index) const { return active_[index - 1]; }
  const T& operator()(int index) const { return internal_[index - 1]; }

 private:
  const T* internal_;
  const ActiveSet& active_;
};

// The scalar of an expression that mixes a state scalar Tx with a
// coefficient scalar Tk. The equations of motion are templated on both so
// that one definition serves every use: double/double (simulation),
// Jet/Jet (derivatives by forward Jets), Jet/double (the state Jacobian of
// the right-hand side) and double/Jet (its coefficient Jacobian; only the
// operations that involve coefficients then carry derivative lanes).
template <typename Tx, typename Tk>
using Promoted = decltype(std::declval<Tx>() * std::declval<Tk>());

}  // namespace fit3dof

#endif  // FIT3DOF_COEFFICIENTS_H_
