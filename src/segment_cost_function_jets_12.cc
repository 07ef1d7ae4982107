// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Jet width 12 of SegmentCostFunction: the width whose lanes cost least
// (segment_cost_function.h).

#include "segment_cost_function_lanes.h"

namespace fit3dof {

template bool SegmentCostFunction::EvaluateLanes<12>(const MotionModel&,
                                                     const double*,
                                                     const int*,
                                                     int,
                                                     double*,
                                                     double**) const;

}  // namespace fit3dof
