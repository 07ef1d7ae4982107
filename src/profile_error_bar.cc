// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "profile_error_bar.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>

#include "fit3dof/input_error.h"
#include "fit3dof/parameters.h"

namespace fit3dof {
namespace {

// The probes' offsets in linear RMS errors: the second only when the sum of
// squares has not risen by E^2 at the first.
constexpr double kProbes[] = {3.0, 15.0};
// The least rise counted, in E^2: a flatter profile (or a refit that found
// a lower sum) gives at most 10 x the offset.
constexpr double kLeastRise = 0.01;

// The case `c` at the solution `fit`, refitted from there with the
// parameter at `position` frozen at `value`: no continuation or
// multi-start (the solution is near), and the weights the solution had.
Case FrozenCase(const Case& c,
                const FitResult& fit,
                int position,
                double value) {
  Case at = CaseAtSolution(c, fit);
  at.solver.continuation = false;
  at.solver.multi_start = false;
  at.solver.max_probable_error = 0.0;
  if (at.AnySigmaAuto()) {
    // One segment (ProfileOf): its estimated noise levels, held.
    at.sigma = fit.segments[0].sigma_deg;
    at.sigma_auto = {{false, false, false}};
  }
  // A frozen Cm_bearing starts its refit back on the ridge (header): the
  // saturated moment Cm_bearing x bearing_angle kept, not the angle. From
  // the angle at the solution, Cm_bearing 15 errors off started a 3-s run's
  // refit at a probable error of 300, and it spent its 50 iterations
  // coming back.
  const int angle = FindParameter(c.model, "bearing_angle");
  const double old = at.parameters[position].value;
  if (ParameterTable(c.model)[position].name == "Cm_bearing" && angle >= 0 &&
      at.parameters[angle].free && old * value > 0.0) {
    at.parameters[angle].value *= old / value;
  }
  at.parameters[position].value = value;
  at.parameters[position].free = false;
  at.parameters[position].auto_start = false;
  at.SettleTies();
  return at;
}

// One side's secant width (sign +1 or -1); false when no frozen refit
// succeeded on that side.
bool SideWidth(const Case& c,
               const std::vector<TimeHistory>& data,
               const FitResult& fit,
               const ParameterEstimate& e,
               double sign,
               ProfileErrorBar* out,
               double* width,
               bool* bounded) {
  const double e2 = fit.probable_error * fit.probable_error;
  const double s2 = fit.sum_of_residuals * fit.sum_of_residuals;
  bool any = false;
  for (const double k : kProbes) {
    const double offset = k * e.rms_error;
    FitResult frozen;
    try {
      ++out->refits;
      frozen = FitSamples(
          FrozenCase(c, fit, e.position, e.value + sign * offset), data);
    } catch (const InputError& error) {
      VLOG(1) << e.name << " frozen at " << e.value + sign * offset << ": "
              << error.what();
      break;
    }
    any = true;
    out->farthest = std::max(out->farthest, offset);
    const double rise = frozen.sum_of_residuals * frozen.sum_of_residuals - s2;
    *width = offset * fit.probable_error /
             std::sqrt(std::max(rise, kLeastRise * e2));
    *bounded = rise >= e2;
    VLOG(1) << e.name << " frozen at " << e.value + sign * offset
            << ": sum of squares up " << rise / e2 << " E^2";
    if (*bounded) break;
  }
  return any;
}

}  // namespace

bool ProfileOf(const Case& c,
               const std::vector<TimeHistory>& data,
               const FitResult& fit,
               const std::string& name,
               ProfileErrorBar* out) {
  const ParameterEstimate* e = SharedEstimate(fit, name);
  if (e == nullptr || !e->free || !(e->rms_error > 0.0) ||
      c.solver.method == FitMethod::kFilterError ||
      (c.AnySigmaAuto() && fit.segments.size() != 1)) {
    return false;
  }
  ProfileErrorBar profile;
  profile.linear = e->rms_error;
  profile.rms_error = e->rms_error;
  bool any = false;
  for (const double sign : {-1.0, 1.0}) {
    double width = 0.0;
    bool bounded = true;
    if (!SideWidth(c, data, fit, *e, sign, &profile, &width, &bounded)) {
      continue;
    }
    any = true;
    profile.rms_error = std::max(profile.rms_error, width);
    profile.bounded = profile.bounded && bounded;
  }
  if (!any) return false;
  *out = profile;
  return true;
}

}  // namespace fit3dof
