// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// An error bar from the profile of the sum of squares, for a parameter
// whose linear one (Eq. 27) cannot be trusted: one on a curved ridge of the
// sum of squares, where the delta method at the solution sees only the
// ridge's width there. The fit is repeated with the parameter frozen at
// value +- k x its RMS error, everything else refitted from the solution.
// Along a quadratic profile the sum of squares then rises by k^2 E^2 (E
// the probable error, Eq. 26); where it rises by less, the profile is
// flatter than the linear error bar says, and the error bar is the secant's:
//
//   RMS error = k sigma E / sqrt(S_k^2 - S^2),    sigma the linear one,
//
// the offset at which the rise would reach E^2 (one degree of freedom of
// chi-square). The probe starts at k = 3 and goes to k = 15 when the rise
// stays below E^2 there. When it rises by E^2 but by less than 80% of a
// quadratic's k^2 E^2 (at either probe), the profile flattens on that
// side, and one more probe goes where that secant puts the rise of 9 E^2,
// and so on while the rise there stays short of 80% of 9 E^2 (three at
// most): the widest secant counts, so that three error bars reach where
// the profile has risen by about 9 E^2 (the offset a test within three
// errors needs). The wider of the two sides counts. Error bars are only
// widened: a profile steeper than the linear one (a sum of squares rising
// faster than quadratically) keeps the linear error bar. The two sides are
// refitted in parallel, within the process's thread budget
// (thread_budget.h).
//
// On one 3-s run with a bearing moment, Cm_bearing = -0.0094 +- 0.0010 with
// its saturation angle undetermined (3.4 +- 5.7 deg); frozen anywhere from
// -0.0094 to -0.03 it fitted the record as well (sum of residuals 10.85 to
// 10.87; truth -0.02).

#ifndef FIT3DOF_SRC_PROFILE_ERROR_BAR_H_
#define FIT3DOF_SRC_PROFILE_ERROR_BAR_H_

#include <string>
#include <vector>

#include "fit3dof/case.h"
#include "fit3dof/fit.h"
#include "fit3dof/time_history.h"

namespace fit3dof {

struct ProfileErrorBar {
  double linear = 0.0;     // the RMS error at the solution (Eq. 27)
  double rms_error = 0.0;  // from the profile (at least the linear one)
  double farthest = 0.0;   // the largest offset probed, in the parameter
  // Whether the sum of squares rose by E^2 within the probes on both
  // sides; when not, rms_error extrapolates the secant beyond them (at
  // most 10 x the farthest offset, where the rise is no more than 1% of
  // E^2) and the parameter is not determined by the record.
  bool bounded = true;
  int refits = 0;  // frozen fits run
};

// The profile error bar of the free shared parameter `name` of `fit`, the
// fit of case `c` to `data` (one record per segment, as FitSamples takes
// them). False (and *out untouched) when the parameter is not free or has
// no RMS error, or when no frozen refit succeeded. Not for fits whose
// weights are estimated (sigma: auto with several segments, or the
// filter-error method): their sums of squares are not comparable between
// refits.
bool ProfileOf(const Case& c,
               const std::vector<TimeHistory>& data,
               const FitResult& fit,
               const std::string& name,
               ProfileErrorBar* out);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_PROFILE_ERROR_BAR_H_
