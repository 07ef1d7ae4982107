// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "profile_error_bar.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "fit3dof/input_error.h"
#include "fit3dof/parameters.h"
#include "fit3dof/thread_budget.h"
#include "fit_memo.h"

namespace fit3dof {
namespace {

// The probes' offsets in linear RMS errors: the second only when the sum of
// squares has not risen by E^2 at the first.
constexpr double kProbes[] = {3.0, 15.0};
// The least rise counted, in E^2: a flatter profile (or a refit that found
// a lower sum) gives at most 10 x the offset.
constexpr double kLeastRise = 0.01;
// A probe whose rise falls short of a quadratic profile's by more than
// this factor is followed by one at the secant's three-error offset.
constexpr double kFlatter = 0.8;
// How many probes at most follow a flatter one, each where the last one's
// secant puts three errors.
constexpr int kFurtherProbes = 3;

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
  // Only its sum of squares (and, swept, its values) is read: no profiles
  // of its own. A frozen Cm_alpha's refit on a bearing ridge had profiled
  // Cm_bearing within it, and later swept its angle: a pair of runs' 5
  // refits ran 54 more.
  at.solver.profile_ridges = false;
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
  // A frozen angle (SweepBearingAngle) likewise keeps the saturated
  // moment, Cm_bearing taking the ratio.
  const int angle = FindParameter(c.model, "bearing_angle");
  const int moment = FindParameter(c.model, "Cm_bearing");
  const double old = at.parameters[position].value;
  if (position == moment && angle >= 0 && at.parameters[angle].free &&
      old * value > 0.0) {
    at.parameters[angle].value *= old / value;
  }
  if (position == angle && moment >= 0 && at.parameters[moment].free &&
      old * value > 0.0) {
    at.parameters[moment].value *= old / value;
  }
  at.parameters[position].value = value;
  at.parameters[position].free = false;
  at.parameters[position].auto_start = false;
  at.SettleTies();
  return at;
}

// A profile's solution and what its refits start from: the case `c` and
// its `data`, the solution `fit`, and other solutions along the ridge a
// refit starts from too (SweepBearingAngle's probes: the refit from the
// solution stays on its branch of the ridge).
struct Refits {
  const Case& c;
  const std::vector<TimeHistory>& data;
  const FitResult& fit;
  const std::vector<FitResult>& branches;
};

// The solution among r.branches whose value of `name` is nearest `value`,
// or null when there are none.
const FitResult* NearestBranch(const Refits& r,
                               const std::string& name,
                               double value) {
  const FitResult* nearest = nullptr;
  double distance = 0.0;
  for (const FitResult& b : r.branches) {
    const ParameterEstimate* e = SharedEstimate(b, name);
    if (e == nullptr) continue;
    const double d = std::abs(e->value - value);
    if (nearest == nullptr || d < distance) {
      nearest = &b;
      distance = d;
    }
  }
  return nearest;
}

// The refit of r.c from `from` with the parameter at `position` (`name`)
// frozen at `value`, into *frozen; false when it failed. Memoized:
// diagnose reports one solution from several places (a step, a tie's
// model, the final model), and each profiles it; the refits from the same
// solution are the same fits (the suite's short bearing + calibration +
// roll torque record: 45 refits, 15 of them distinct).
bool RefitFrozen(const Refits& r,
                 const FitResult& from,
                 int position,
                 const std::string& name,
                 double value,
                 FitResult* frozen) {
  try {
    *frozen =
        MemoizedFitSamples(FrozenCase(r.c, from, position, value), r.data);
  } catch (const InputError& error) {
    VLOG(1) << name << " frozen at " << value << ": " << error.what();
    return false;
  }
  return true;
}

// The rise, in E^2 of the solution r.fit, of a refit's sum of residuals
// `sum` over the solution's.
double RiseOf(const Refits& r,
              double sum,
              const std::string& name,
              double value) {
  const double e2 = r.fit.probable_error * r.fit.probable_error;
  const double s2 = r.fit.sum_of_residuals * r.fit.sum_of_residuals;
  const double rise = (sum * sum - s2) / e2;
  VLOG(1) << name << " frozen at " << value << ": sum of squares up " << rise
          << " E^2";
  return rise;
}

// The rise of the sum of squares, in E^2, with the parameter of `e` frozen
// at `offset` from the solution on side `sign`, refitted from the solution
// and from the nearest branch (the lower sum counts); false when every
// refit failed.
bool Rise(const Refits& r,
          const ParameterEstimate& e,
          double sign,
          double offset,
          ProfileErrorBar* out,
          double* rise) {
  const double value = e.value + sign * offset;
  const FitResult* starts[] = {&r.fit, NearestBranch(r, e.name, value)};
  double least = std::numeric_limits<double>::infinity();
  for (const FitResult* from : starts) {
    if (from == nullptr) continue;
    ++out->refits;
    FitResult frozen;
    if (RefitFrozen(r, *from, e.position, e.name, value, &frozen)) {
      least = std::min(least, frozen.sum_of_residuals);
    }
  }
  if (!std::isfinite(least)) return false;
  out->farthest = std::max(out->farthest, offset);
  *rise = RiseOf(r, least, e.name, value);
  return true;
}

// The probes past a bounded one (at `offset`, risen by `rise` E^2, at
// least 1) whose profile is flatter than quadratic: each where the last
// one's secant puts the rise of 9 E^2 (within three times its offset),
// while the rise there stays short of 80% of 9 E^2, at most
// kFurtherProbes of them; *width becomes the widest secant. On another
// pair of runs with the bearing angle at 0.5 deg (fitted at 3.0 +- 1.4)
// Cm_bearing's profile rose by 3.2 E^2 0.0027 out and by 3.9 E^2 0.0064
// out: one further probe had left the truth, there, 4.0 errors off.
void FurtherOut(const Refits& r,
                const ParameterEstimate& e,
                double sign,
                double offset,
                double rise,
                ProfileErrorBar* out,
                double* width) {
  for (int i = 0; i < kFurtherProbes; ++i) {
    // Within three times the offset, the rise being at least E^2.
    offset *= 3.0 / std::sqrt(rise);
    if (!Rise(r, e, sign, offset, out, &rise)) return;
    *width = std::max(*width, offset / std::sqrt(std::max(rise, kLeastRise)));
    if (rise < 1.0 || rise >= kFlatter * 9.0) return;
  }
}

// One side's secant width (sign +1 or -1); false when no frozen refit
// succeeded on that side.
bool SideWidth(const Refits& r,
               const ParameterEstimate& e,
               double sign,
               ProfileErrorBar* out,
               double* width,
               bool* bounded) {
  bool any = false;
  for (const double k : kProbes) {
    const double offset = k * e.rms_error;
    double rise = 0.0;
    if (!Rise(r, e, sign, offset, out, &rise)) break;
    any = true;
    *width = offset / std::sqrt(std::max(rise, kLeastRise));
    *bounded = rise >= 1.0;
    if (!*bounded) continue;
    // Bounded, but flatter than quadratic: the secant to three errors
    // understates the profile's own three-error offset, which lies further
    // out where the profile keeps flattening (a bearing angle of 1.31 +-
    // 0.12 deg, truth 1: Cm_bearing 3.3 secant errors off, 2.9 by the
    // profile). Probed again where the secant puts it, after either probe:
    // on a pair of runs with a bearing angle of 0.5 deg, fitted at 2.4 +-
    // 1.3, Cm_bearing rose by E^2 only at the second probe (1.8 E^2, 0.0022
    // out), and 0.005 out by 2.0 E^2; the secant's 0.0017 had put the
    // truth, 0.0059 out, 3.6 errors off.
    if (rise < kFlatter * k * k) {
      FurtherOut(r, e, sign, offset, rise, out, width);
    }
    break;
  }
  return any;
}

// The sweep's step in the angle (a ratio), the probes below the fitted
// angle, and the rise (E^2) within which a probe counts: three errors.
constexpr double kSweepRatio = 2.0;
constexpr int kSweepDown = 2;
constexpr double kWithinThree = 9.0;
// At most this many probes above the fitted angle: 2^8 times it.
constexpr int kSweepUp = 8;

// The refit of r.c with the angle `e` frozen at `angle` from `from`, into
// *probe, and its rise in E^2 of the solution r.fit; false when that
// refit failed.
bool AngleProbe(const Refits& r,
                const ParameterEstimate& e,
                const FitResult& from,
                double angle,
                AngleSweep* out,
                FitResult* probe,
                double* rise) {
  ++out->refits;
  if (!RefitFrozen(r, from, e.position, e.name, angle, probe)) return false;
  *rise = RiseOf(r, probe->sum_of_residuals, e.name, angle);
  return std::isfinite(*rise);
}

// The distance the ridge moved parameter `e` of the solution in `probe`
// (NaN when the probe does not hold it).
double Moved(const ParameterEstimate& e, const FitResult& probe) {
  const ParameterEstimate* moved = SharedEstimate(probe, e.name);
  if (moved == nullptr) return std::numeric_limits<double>::quiet_NaN();
  // The angle's sign means nothing (bearing_moment.h); other terms keep
  // theirs.
  return e.name == "bearing_angle" ? std::abs(moved->value) - std::abs(e.value)
                                   : moved->value - e.value;
}

// Whether `e` is one of the parameters a sweep widens: free, shared, with
// an RMS error.
bool Widened(const ParameterEstimate& e) {
  return e.segment.empty() && e.free && e.rms_error > 0.0;
}

// Between the last refit within three errors (`within`, risen by
// `r_within` E^2; the solution itself at 0) and the first beyond
// (`beyond`, by r_beyond > 9): each parameter's value where the rise
// reaches 9 E^2, interpolated in the rise, puts three of its errors there.
// Without it the last probe within, 2.8 errors out at one step of the
// sweep, set the width, and the next step's truth fell outside.
void AtThreeErrors(const FitResult& fit,
                   const FitResult& within,
                   double r_within,
                   const FitResult& beyond,
                   double r_beyond,
                   AngleSweep* out) {
  const double share = (kWithinThree - r_within) / (r_beyond - r_within);
  for (size_t i = 0; i < fit.parameters.size(); ++i) {
    const ParameterEstimate& e = fit.parameters[i];
    if (!Widened(e)) continue;
    const double near = &within == &fit ? 0.0 : Moved(e, within);
    const double far = Moved(e, beyond);
    const double at_nine = near + share * (far - near);
    if (std::isfinite(at_nine)) {
      out->widths[i] = std::max(out->widths[i], std::abs(at_nine) / 3.0);
    }
  }
}

// A probe within three errors (`rise` E^2) widens out->widths to the
// distance it moved each free shared parameter over sqrt(max(rise, 1)),
// and out's range of angles to its `angle`.
void Counted(const FitResult& fit,
             const FitResult& probe,
             double angle,
             double rise,
             AngleSweep* out) {
  const double errors = std::sqrt(std::max(rise, 1.0));
  for (size_t i = 0; i < fit.parameters.size(); ++i) {
    const ParameterEstimate& e = fit.parameters[i];
    if (!Widened(e)) continue;
    const double distance = std::abs(Moved(e, probe));
    if (std::isfinite(distance)) {
      out->widths[i] = std::max(out->widths[i], distance / errors);
    }
  }
  out->lowest = out->lowest > 0.0 ? std::min(out->lowest, angle) : angle;
  out->highest = std::max(out->highest, angle);
  out->probes.push_back(probe);
}

// One side of the sweep: steps of `ratio` from the fitted angle, each
// refitted from the last one counted, at most `steps` of them and none
// past `largest_deg`; past three errors, one probe at the geometric mean
// of the last angle within and the first beyond, the 9 E^2 crossing
// between the probes either side of it (AtThreeErrors), and the side
// ends.
void SweepSide(const Refits& r,
               const ParameterEstimate& e,
               double ratio,
               int steps,
               double largest_deg,
               AngleSweep* out) {
  const FitResult& fit = r.fit;
  FitResult from = fit;
  const FitResult* within = &fit;
  double r_within = 0.0;
  double angle = std::abs(e.value);
  for (int k = 0; k < steps; ++k) {
    const double next = std::min(angle * ratio, largest_deg);
    if (!(next != angle)) return;
    FitResult probe;
    double rise = 0.0;
    if (!AngleProbe(r, e, from, next, out, &probe, &rise)) {
      return;
    }
    if (rise <= kWithinThree) {
      Counted(fit, probe, next, rise, out);
      from = std::move(probe);
      within = &from;
      r_within = rise;
      angle = next;
      continue;
    }
    const double between = std::sqrt(angle * next);
    FitResult middle;
    double r_middle = 0.0;
    if (!AngleProbe(r, e, from, between, out, &middle, &r_middle)) {
      AtThreeErrors(fit, *within, r_within, probe, rise, out);
    } else if (r_middle <= kWithinThree) {
      Counted(fit, middle, between, r_middle, out);
      AtThreeErrors(fit, middle, r_middle, probe, rise, out);
    } else {
      AtThreeErrors(fit, *within, r_within, middle, r_middle, out);
    }
    return;
  }
}

// One side's tally `side` added into *sweep (widths the wider, the range
// of angles the union).
void Merge(const AngleSweep& side, AngleSweep* sweep) {
  sweep->refits += side.refits;
  sweep->probes.insert(
      sweep->probes.end(), side.probes.begin(), side.probes.end());
  for (size_t i = 0; i < side.widths.size(); ++i) {
    sweep->widths[i] = std::max(sweep->widths[i], side.widths[i]);
  }
  if (side.probes.empty()) return;
  sweep->lowest =
      sweep->lowest > 0.0 ? std::min(sweep->lowest, side.lowest) : side.lowest;
  sweep->highest = std::max(sweep->highest, side.highest);
}

}  // namespace

bool SweepBearingAngle(const Case& c,
                       const std::vector<TimeHistory>& data,
                       const FitResult& fit,
                       double largest_deg,
                       AngleSweep* out) {
  const ParameterEstimate* e = SharedEstimate(fit, "bearing_angle");
  const ParameterEstimate* moment = SharedEstimate(fit, "Cm_bearing");
  if (e == nullptr || moment == nullptr || !e->free || !moment->free ||
      !(std::abs(e->value) > 0.0) ||
      c.solver.method == FitMethod::kFilterError ||
      (c.AnySigmaAuto() && fit.segments.size() != 1)) {
    return false;
  }
  const std::vector<FitResult> none;
  const Refits refits{c, data, fit, none};
  // Down and up are independent: in parallel, each with its own tally.
  const double ratios[2] = {1.0 / kSweepRatio, kSweepRatio};
  const int steps[2] = {kSweepDown, kSweepUp};
  AngleSweep sides[2];
  ParallelFor(2, [&](int i) {
    sides[i].widths.assign(fit.parameters.size(), 0.0);
    SweepSide(refits, *e, ratios[i], steps[i], largest_deg, &sides[i]);
  });
  AngleSweep sweep;
  sweep.widths.assign(fit.parameters.size(), 0.0);
  for (const AngleSweep& side : sides) Merge(side, &sweep);
  if (!sweep.probes.empty()) {
    sweep.lowest = std::min(sweep.lowest, std::abs(e->value));
    sweep.highest = std::max(sweep.highest, std::abs(e->value));
  }
  *out = std::move(sweep);
  return true;
}

bool ProfileOf(const Case& c,
               const std::vector<TimeHistory>& data,
               const FitResult& fit,
               const std::string& name,
               ProfileErrorBar* out) {
  return ProfileAcross(c, data, fit, name, {}, out);
}

bool ProfileAcross(const Case& c,
                   const std::vector<TimeHistory>& data,
                   const FitResult& fit,
                   const std::string& name,
                   const std::vector<FitResult>& branches,
                   ProfileErrorBar* out) {
  const ParameterEstimate* e = SharedEstimate(fit, name);
  if (e == nullptr || !e->free || !(e->rms_error > 0.0) ||
      c.solver.method == FitMethod::kFilterError ||
      (c.AnySigmaAuto() && fit.segments.size() != 1)) {
    return false;
  }
  const Refits refits{c, data, fit, branches};
  // The two sides' refits are independent: in parallel, each with its own
  // tally, within the process's thread budget.
  struct Side {
    ProfileErrorBar tally;
    double width = 0.0;
    bool bounded = true;
    bool any = false;
  };
  Side sides[2];
  ParallelFor(2, [&](int i) {
    Side& side = sides[i];
    side.any = SideWidth(refits,
                         *e,
                         i == 0 ? -1.0 : 1.0,
                         &side.tally,
                         &side.width,
                         &side.bounded);
  });
  ProfileErrorBar profile;
  profile.linear = e->rms_error;
  profile.rms_error = e->rms_error;
  bool any = false;
  for (const Side& side : sides) {
    profile.refits += side.tally.refits;
    profile.farthest = std::max(profile.farthest, side.tally.farthest);
    if (!side.any) continue;
    any = true;
    profile.rms_error = std::max(profile.rms_error, side.width);
    profile.bounded = profile.bounded && side.bounded;
  }
  if (!any) return false;
  *out = profile;
  return true;
}

}  // namespace fit3dof
