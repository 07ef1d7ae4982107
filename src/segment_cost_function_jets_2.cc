// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Jet width 2 of SegmentCostFunction (a unit of its own, so that the
// widths build in parallel).

#include "segment_cost_function_lanes.h"

// The sanitized build leaves this width out (FIT3DOF_FEWER_JET_WIDTHS):
// the same template as widths 4 and 8, lane for lane the same arithmetic,
// and compiling it there costs CI minutes.
#ifndef FIT3DOF_FEWER_JET_WIDTHS
namespace fit3dof {

template bool SegmentCostFunction::EvaluateLanes<2>(const MotionModel&,
                                                    const double*,
                                                    const int*,
                                                    int,
                                                    double*,
                                                    double**) const;

}  // namespace fit3dof
#endif
