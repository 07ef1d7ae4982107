// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Jet widths 4, 8 and 12 of SegmentCostFunction (split from the wider ones
// so the two halves build in parallel).

#include "segment_cost_function_lanes.h"

namespace fit3dof {

template bool SegmentCostFunction::EvaluateLanes<4>(
    const double*, const int*, int, double*, double**) const;
template bool SegmentCostFunction::EvaluateLanes<8>(
    const double*, const int*, int, double*, double**) const;
template bool SegmentCostFunction::EvaluateLanes<12>(
    const double*, const int*, int, double*, double**) const;

}  // namespace fit3dof
