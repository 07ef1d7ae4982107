// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Jet width 4 of SegmentCostFunction (a unit of its own, so that the
// widths build in parallel).

#include "segment_cost_function_lanes.h"

namespace fit3dof {

template bool SegmentCostFunction::EvaluateLanes<4>(const MotionModel&,
                                                    const double*,
                                                    const int*,
                                                    int,
                                                    double*,
                                                    double**) const;

}  // namespace fit3dof
