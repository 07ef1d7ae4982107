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

// ProfileOf where the ridge has branches the refits from the solution do
// not reach: each frozen refit starts from `fit` and from the solution
// among `branches` nearest the frozen value (AngleSweep::probes), and the
// lower sum of squares counts. On a pair of runs with the bearing moment
// saturating at 2 deg, fitted at 0.28 deg, Cm_alpha's refits from the
// solution stayed at small angles, and its profile error bar was 1.04
// times the linear one, the truth 4.7 of them off.
bool ProfileAcross(const Case& c,
                   const std::vector<TimeHistory>& data,
                   const FitResult& fit,
                   const std::string& name,
                   const std::vector<FitResult>& branches,
                   ProfileErrorBar* out);

// Error bars along a bearing moment's ridge where the record does not
// determine the angle (fit.h, CheckRidges): the fit repeated with
// bearing_angle frozen at its fitted value times 2^k (Cm_bearing scaled to
// keep the saturated moment Cm_bearing x bearing_angle, the rest refitted
// from the probe before), down to a quarter of it and up while the sum of
// squares stays within 9 E^2 (three errors) and the angle within the
// record's largest, with one probe at the geometric mean of the last one
// within and the first beyond. Eq. 27's error bars see the ridge only
// where the fit stopped on it; the profiles of Cm_bearing and Cm_alpha
// (ProfileOf) see it only within their probes of the solution, on the
// branch the solution is on. A probe that moves a free shared parameter by
// d while the sum of squares rises by r E^2 (r <= 9) puts it within
// sqrt(r) errors at that distance: its error bar is at least
// d / sqrt(max(r, 1)) (no extrapolation below one error). On a pair of
// runs with the moment saturating at 2 deg (draw 113), the angle fitted
// 0.28 +- 0.22 deg and Cm_alpha -0.157981 +- 0.000039 against -0.1578:
// frozen at 2.24 deg the sum of squares rose by 8.3 E^2 with Cm_alpha at
// -0.157758.
struct AngleSweep {
  // Per entry of the fit's parameters, the widest d / sqrt(max(r, 1)) over
  // the probes within 9 E^2; 0 where none moved it or it is not a free
  // shared parameter with an RMS error.
  std::vector<double> widths;
  // The range of angles within 9 E^2 the sweep reached, the fitted one
  // included (deg; both 0 when no probe was within).
  double lowest = 0.0;
  double highest = 0.0;
  int refits = 0;
  // The refits within 9 E^2, for ProfileAcross.
  std::vector<FitResult> probes;
};

// The sweep of `fit`'s bearing_angle, the fit of case `c` to `data`, up to
// the record's largest total angle `largest_deg`. False when the angle or
// Cm_bearing is not free, or for fits whose weights are estimated (as
// ProfileOf).
bool SweepBearingAngle(const Case& c,
                       const std::vector<TimeHistory>& data,
                       const FitResult& fit,
                       double largest_deg,
                       AngleSweep* out);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_PROFILE_ERROR_BAR_H_
