// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Wild points: single samples that no motion of the model produces (a
// telemetry dropout, a bit error, 1e308 in one field). Left in, one of them
// takes a fit from a probable error of 1 to a thousand and nothing points at
// the data, because a least-squares fit spreads the damage over every
// parameter. They are found three ways:
//
//   reach      theta at or beyond +-90 deg, where the Euler angles of the
//              model are singular and no motion of it goes; phi or psi
//              beyond 1e9 deg (2.8 million turns);
//   jump       a sample far from the cubic through its two neighbours on
//              each side, measured in robust sigmas of that prediction error
//              in the surrounding samples (the motion itself is smooth at
//              any usable sampling rate; noise is not, but it is Gaussian-
//              like and its local spread is what the threshold scales by;
//              roll, compared modulo 360 deg by the fit, is unwrapped first
//              when the record holds it wrapped into a turn);
//   residual   after the fit, the same jump test on measured - computed (the
//              motion taken out, so that spikes smaller than the motion's
//              own curvature show), and residuals beyond ten robust sigmas
//              of their channel.
//
// Screening only names samples; what happens to them is the case's choice
// (data: {outliers: warn | reject}). Nothing here changes data.

#ifndef FIT3DOF_WILD_POINTS_H_
#define FIT3DOF_WILD_POINTS_H_

#include <string>
#include <vector>

#include "fit3dof/time_history.h"

namespace fit3dof {

// What a fit does with the wild points it finds.
enum class OutlierPolicy {
  kWarn,    // keep them, name each in the warnings and the report (default)
  kReject,  // drop their samples and fit again; also named
};

// "warn" / "reject"; false for anything else.
bool ParseOutlierPolicy(const std::string& text, OutlierPolicy* policy);
const char* OutlierPolicyName(OutlierPolicy policy);

enum class WildPointTest { kReach, kJump, kResidual };

struct WildPoint {
  int sample = 0;    // index in the screened series
  double t = 0.0;    // s
  int channel = 0;   // 0 phi, 1 theta, 2 psi
  double value = 0;  // the measured value, deg
  // How far the sample is from what its neighbours (or the fit) say, deg,
  // and that distance in robust sigmas (infinite for a reach failure).
  double deviation = 0.0;
  double sigmas = 0.0;
  WildPointTest test = WildPointTest::kJump;

  // One line: channel, time, value and why, e.g. "theta = 40.2 deg at
  // t = 3.06 s: 39.8 deg off the cubic through its neighbours (2.9e+03
  // robust sigmas)".
  std::string Describe() const;
};

// Wild points of measured data, before any fit: reach and jump tests on
// each channel, sorted by sample then channel. Records shorter than 8
// samples are not screened (too few neighbours to judge).
std::vector<WildPoint> ScreenData(const TimeHistory& data);

// Wild points among the residuals of a fit: `computed` holds phi, theta,
// psi per sample (3 * data.size()). Samples listed in `known` (indices,
// any order) are skipped and do not count as neighbours.
std::vector<WildPoint> ScreenResiduals(const TimeHistory& data,
                                       const std::vector<double>& computed,
                                       const std::vector<int>& known);

// The step of channel `channel`'s readings (deg) where they lie on a grid
// (encoder counts), or 0: nearly every reading on it over a span of at
// least four steps, the rounding roughening the series. Roll is judged
// unwrapped where its readings wrap into a turn.
double ReadingStepDeg(const TimeHistory& data, int channel);

// A copy of `data` without the samples at `drop` (indices, any order,
// repeats allowed).
TimeHistory DropSamples(const TimeHistory& data, const std::vector<int>& drop);

}  // namespace fit3dof

#endif  // FIT3DOF_WILD_POINTS_H_
