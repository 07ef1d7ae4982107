// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Jet widths 16, 24 and 32 of SegmentCostFunction.

#include "segment_cost_function_lanes.h"

namespace fit3dof {

template bool SegmentCostFunction::EvaluateLanes<16>(
    const double*, const int*, int, double*, double**) const;
template bool SegmentCostFunction::EvaluateLanes<24>(
    const double*, const int*, int, double*, double**) const;
template bool SegmentCostFunction::EvaluateLanes<32>(
    const double*, const int*, int, double*, double**) const;

}  // namespace fit3dof
