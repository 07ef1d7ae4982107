// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Wild points (wild_points.h): samples out of reach, jumps, and residuals
// the fit cannot reach, found by robust statistics.

#include "fit3dof/wild_points.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <queue>
#include <utility>

#include "fit3dof/angles.h"
#include "fit3dof/data_selection.h"
#include "format.h"
#include "glog/logging.h"

namespace fit3dof {
namespace {

// A sample this many robust sigmas from its prediction is wild. For Gaussian
// noise the chance is 1e-23 per sample: a clean record of any length never
// trips it, while a 40-degree spike in 0.01-degree noise is thousands out.
constexpr double kThreshold = 10.0;
// The robust sigma of a prediction error is taken over blocks of samples,
// so that a decaying motion (large curvature errors early, small late) is
// judged by its own neighbourhood; never below a quarter of the whole
// channel's, nor below what no sensor resolves.
constexpr int kBlock = 32;
constexpr double kGlobalFloor = 0.25;
constexpr double kFloorDeg = 1e-6;
constexpr double kMadToSigma = 1.4826;
// More wild points than this fraction of a channel is not a few bad samples
// but a noisy channel; the screen stops there.
constexpr double kMaxFraction = 0.1;
constexpr int kMinSamples = 8;
// Pitch at +-90 deg is where the model's Euler angles are singular. Roll
// and yaw run on, but not past a billion degrees (2.8 million turns): no
// run spins that long, and a double holds such an angle to no better than
// 1e-7 deg.
constexpr double kThetaReachDeg = 90.0;
constexpr double kAngleReachDeg = 1e9;

// Long double so that a prediction involving 1e308 does not overflow.
using Real = long double;

// The four nearest unflagged neighbours of sample i: two on each side, or
// more on one side at an edge. False when there are fewer than four.
bool Neighbours(const std::vector<char>& flagged,
                int i,
                std::array<int, 4>* nodes) {
  const int n = static_cast<int>(flagged.size());
  std::array<int, 4> left, right;
  int nl = 0, nr = 0;
  for (int j = i - 1; j >= 0 && nl < 4; --j) {
    if (!flagged[j]) left[nl++] = j;
  }
  for (int j = i + 1; j < n && nr < 4; ++j) {
    if (!flagged[j]) right[nr++] = j;
  }
  if (nl + nr < 4) return false;
  int take_left = std::min(nl, 2);
  int take_right = std::min(nr, 2);
  take_left += std::min(nl - take_left, 4 - take_left - take_right);
  take_right = 4 - take_left;
  int k = 0;
  for (int j = 0; j < take_left; ++j) (*nodes)[k++] = left[j];
  for (int j = 0; j < take_right; ++j) (*nodes)[k++] = right[j];
  return true;
}

// The cubic (Lagrange) prediction error at sample i, and its noise gain
// sqrt(1 + sum w^2): for white noise of sigma s the error has sigma
// s * gain, whatever the spacing of the neighbours.
struct Prediction {
  Real error = 0;
  Real gain = 1;
};

Prediction Predict(const std::vector<double>& t,
                   const std::vector<double>& x,
                   int i,
                   const std::array<int, 4>& nodes) {
  Real predicted = 0, sum_w2 = 0;
  for (int a = 0; a < 4; ++a) {
    Real w = 1;
    for (int b = 0; b < 4; ++b) {
      if (b == a) continue;
      w *= (Real(t[i]) - t[nodes[b]]) / (Real(t[nodes[a]]) - t[nodes[b]]);
    }
    predicted += w * x[nodes[a]];
    sum_w2 += w * w;
  }
  return {Real(x[i]) - predicted, std::sqrt(1 + sum_w2)};
}

Real Median(std::vector<Real> v) {
  CHECK(!v.empty());
  const size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + m, v.end());
  return v[m];
}

// kMadToSigma * median |v - median v|; 0 for an empty set.
Real RobustSigma(const std::vector<Real>& v) {
  if (v.empty()) return 0;
  const Real center = Median(v);
  std::vector<Real> spread(v.size());
  for (size_t j = 0; j < v.size(); ++j) spread[j] = std::abs(v[j] - center);
  return kMadToSigma * Median(spread);
}

// The standard deviation of rounding to a grid of `step` (uniform over a
// step); 0 for no grid.
Real RoundingSigma(double step) { return step / std::sqrt(12.0); }

struct Jump {
  int sample;
  double deviation;  // deg
  double sigmas;
};

// The jump test on one series; samples flagged on entry are skipped and
// are no one's neighbours. Flags the worst sample first and re-predicts its
// neighbours without it, so that a spike does not drag its neighbours out.
std::vector<Jump> FindJumps(const std::vector<double>& t,
                            const std::vector<double>& x,
                            std::vector<char> flagged,
                            double quantum) {
  const int n = static_cast<int>(x.size());
  if (n < kMinSamples) return {};
  std::vector<Real> z(n, 0);
  std::vector<char> valid(n, 0);
  std::array<int, 4> nodes;
  for (int i = 0; i < n; ++i) {
    if (flagged[i] || !Neighbours(flagged, i, &nodes)) continue;
    const Prediction p = Predict(t, x, i, nodes);
    z[i] = p.error / p.gain;
    valid[i] = 1;
  }
  std::vector<Real> all;
  for (int i = 0; i < n; ++i) {
    if (valid[i]) all.push_back(z[i]);
  }
  // A grid's rounding error is uniform over a step (sigma q / sqrt(12));
  // at ten of those no rounding reaches the threshold, whatever the
  // neighbours' weights (the error is at most (q / 2)(1 + sum |w|), under
  // 1.12 q times the gain).
  const Real floor = std::max<Real>(
      {kGlobalFloor * RobustSigma(all), kFloorDeg, RoundingSigma(quantum)});
  const int blocks = (n + kBlock - 1) / kBlock;
  std::vector<Real> scale(blocks);
  for (int b = 0; b < blocks; ++b) {
    std::vector<Real> local;
    for (int i = std::max(0, (b - 1) * kBlock);
         i < std::min(n, (b + 2) * kBlock);
         ++i) {
      if (valid[i]) local.push_back(z[i]);
    }
    scale[b] = std::max(RobustSigma(local), floor);
  }
  auto sigmas = [&](int i, Prediction* p) -> Real {
    if (!Neighbours(flagged, i, &nodes)) return 0;
    *p = Predict(t, x, i, nodes);
    return std::abs(p->error / p->gain) / scale[i / kBlock];
  };
  std::priority_queue<std::pair<Real, int>> queue;
  for (int i = 0; i < n; ++i) {
    if (valid[i]) queue.push({std::abs(z[i]) / scale[i / kBlock], i});
  }
  const std::vector<char> known = flagged;
  const int max_flags = std::max(1, static_cast<int>(kMaxFraction * n));
  int flags = 0;
  while (!queue.empty() && flags < max_flags) {
    const auto [stored, i] = queue.top();
    queue.pop();
    if (flagged[i]) continue;
    Prediction p;
    const Real current = sigmas(i, &p);
    if (current != stored) continue;  // a newer entry is queued
    if (!(current > kThreshold)) break;
    flagged[i] = 1;
    ++flags;
    // Its neighbours were predicted with it; predict them again.
    for (int j = std::max(0, i - 4); j <= std::min(n - 1, i + 4); ++j) {
      if (flagged[j]) continue;
      Prediction q;
      queue.push({sigmas(j, &q), j});
    }
  }
  // The worst sample is not always the wild one: a spike at the edge of the
  // record, predicted by extrapolation, can score below its neighbour that
  // was interpolated through it. With every wild point out, a sample that
  // its neighbours now predict well was only collateral: take it back.
  for (bool changed = true; changed;) {
    changed = false;
    for (int i = 0; i < n; ++i) {
      if (!flagged[i] || known[i]) continue;
      flagged[i] = 0;
      Prediction p;
      if (sigmas(i, &p) > kThreshold) {
        flagged[i] = 1;
      } else {
        changed = true;
      }
    }
  }
  std::vector<Jump> jumps;
  for (int i = 0; i < n; ++i) {
    if (!flagged[i] || known[i]) continue;
    flagged[i] = 0;
    Prediction p;
    const Real out = sigmas(i, &p);
    flagged[i] = 1;
    jumps.push_back(
        {i, static_cast<double>(p.error), static_cast<double>(out)});
  }
  return jumps;
}

// Quantum's candidates and tests.
constexpr int kQuantumQuantiles = 8;
constexpr double kOnGrid = 0.1;      // of a step
constexpr double kGridShare = 0.95;  // of the readings
constexpr int kLeastSteps = 4;

// The step of the grid near `guess` that the readings `x` sit on, or 0.
// The step is fitted by least squares to the sample-to-sample `changes`
// and their whole counts c_i (q = sum c_i d_i / sum c_i^2); each reading's
// count is the sum of the counts before it, and the readings must lie
// within kOnGrid of a step of the grid, kGridShare of them, the grid's
// offset taken per block of kBlock samples (a wild point may shift the
// counts after it by one; the step's own error drifts the grid by 0.015
// deg over a block of Table 6's roll in 2-deg counts). Readings off any
// grid lie that close 20% of the time. Changes alone do not tell: 18 and
// 19 counts of 2.13 deg are within a fifth of 5 of 7.77 deg.
double GridStep(const std::vector<double>& x,
                const std::vector<double>& changes,
                double guess) {
  if (!(guess >= kFloorDeg)) return 0.0;  // finer than any sensor resolves
  double cd = 0.0, cc = 0.0;
  for (double d : changes) {
    const double counts = std::round(d / guess);
    cd += counts * d;
    cc += counts * counts;
  }
  if (!(cc > 0.0)) return 0.0;
  const double step = cd / cc;
  const int n = static_cast<int>(x.size());
  std::vector<Real> offsets(n);
  Real counts = 0;
  for (int i = 0; i < n; ++i) {
    if (i > 0) counts += std::round(changes[i - 1] / step);
    offsets[i] = x[i] - counts * step;
  }
  int on = 0;
  for (int b = 0; b * kBlock < n; ++b) {
    const auto first = offsets.begin() + b * kBlock;
    const auto last = offsets.begin() + std::min(n, (b + 1) * kBlock);
    const Real center = Median(std::vector<Real>(first, last));
    for (auto o = first; o != last; ++o) {
      on += std::abs(*o - center) <= kOnGrid * step;
    }
  }
  return on >= kGridShare * n ? step : 0.0;
}

// Whether rounding to `step` shows in the cubic prediction errors of the
// series (sigma step / sqrt(12) where the rounding wraps): the 90th
// percentile of their size at least a quarter of that. A few spikes on a
// smooth series leave it at the noise.
bool Rounded(const std::vector<double>& t,
             const std::vector<double>& x,
             double step) {
  constexpr double kShare = 0.9;
  constexpr double kLeast = 0.25;
  const int n = static_cast<int>(x.size());
  const std::vector<char> none(n, 0);
  std::vector<Real> sizes;
  std::array<int, 4> nodes;
  for (int i = 0; i < n; ++i) {
    if (!Neighbours(none, i, &nodes)) continue;
    const Prediction p = Predict(t, x, i, nodes);
    sizes.push_back(std::abs(p.error / p.gain));
  }
  if (sizes.empty()) return false;
  const size_t at =
      std::min(sizes.size() - 1, static_cast<size_t>(kShare * sizes.size()));
  std::nth_element(sizes.begin(), sizes.begin() + at, sizes.end());
  return sizes[at] >= kLeast * RoundingSigma(step);
}

// The step of a channel's readings when they lie on a grid (an encoder's
// count, a converter's least bit, with noise well below the step), or 0.
// On such a channel the reading's own error is the rounding, up to half a
// step, and the slow sawtooth it traces against a smooth motion jumps by a
// step where it wraps: on 2-deg roll counts at 1.9 deg a sample, wraps 49
// robust sigmas of the sawtooth off the cubic through their neighbours
// had been called wild.
// Candidates are quantiles of the sample-to-sample changes and of their
// changes (a fast roll moves many counts a sample, 18 or 19 of them:
// its second differences are whole counts), and their halves and thirds.
// Each is refined by least squares on the whole counts of the changes,
// and taken when nearly all the readings lie on its grid (GridStep) over a
// span of at least four steps, and the rounding roughens the series
// (Rounded): a roll
// at a constant rate is a grid of its own, 38 deg a sample on Table 6,
// and taken for one it would hide spikes of 100 deg. Of the steps taken,
// the largest (a grid's halves are grids too).
double Quantum(const std::vector<double>& t, const std::vector<double>& x) {
  const int n = static_cast<int>(x.size());
  if (n < kMinSamples) return 0.0;
  for (double v : x) {
    if (!std::isfinite(v)) return 0.0;
  }
  const auto [low, high] = std::minmax_element(x.begin(), x.end());
  std::vector<double> changes(n - 1), second(n - 2);
  for (int i = 0; i + 1 < n; ++i) changes[i] = x[i + 1] - x[i];
  for (int i = 0; i + 2 < n; ++i) second[i] = changes[i + 1] - changes[i];
  double best = 0.0;
  for (const std::vector<double>* differences : {&changes, &second}) {
    std::vector<double> sizes;
    for (double d : *differences) {
      if (d != 0.0) sizes.push_back(std::abs(d));
    }
    std::sort(sizes.begin(), sizes.end());
    for (int k = 0; k < kQuantumQuantiles && !sizes.empty(); ++k) {
      const double size = sizes[sizes.size() * k / kQuantumQuantiles];
      for (int divisor = 1; divisor <= 3; ++divisor) {
        const double step = GridStep(x, changes, size / divisor);
        if (step > best && *high - *low >= kLeastSteps * step &&
            Rounded(t, x, step)) {
          best = step;
        }
      }
    }
  }
  return best;
}

// The robust sigma of the prediction errors of a whole series.
Real Roughness(const std::vector<double>& t,
               const std::vector<double>& x,
               const std::vector<char>& skip) {
  std::vector<Real> z;
  std::array<int, 4> nodes;
  for (size_t i = 0; i < x.size(); ++i) {
    if (skip[i] || !Neighbours(skip, static_cast<int>(i), &nodes)) continue;
    const Prediction p = Predict(t, x, static_cast<int>(i), nodes);
    z.push_back(p.error / p.gain);
  }
  return RobustSigma(z);
}

// The series the jump test screens for a channel: for roll, the smoother
// of the series as given and unwrapped. Roll is compared modulo 360 deg (the
// listing's INTGRL), so a record may hold it wrapped into a turn; unwrapped,
// the test sees the motion rather than the wraps. A record whose roll already
// runs on (possibly faster than half a turn per sample) is left as it is.
std::vector<double> ScreenedSeries(const std::vector<double>& t,
                                   const std::vector<double>& x,
                                   int channel,
                                   const std::vector<char>& flagged) {
  if (channel == 0) {
    std::vector<double> u = UnwrapDegrees(x, flagged);
    if (Roughness(t, u, flagged) < Roughness(t, x, flagged)) return u;
  }
  return x;
}

// The jump test on a channel's series as ScreenedSeries gives it.
// `quantum`: the step of the channel's readings (ReadingQuantum), or 0.
std::vector<Jump> FindChannelJumps(const std::vector<double>& t,
                                   const std::vector<double>& x,
                                   int channel,
                                   const std::vector<char>& flagged,
                                   double quantum) {
  return FindJumps(t, ScreenedSeries(t, x, channel, flagged), flagged, quantum);
}

// Quantum of a channel's readings as ScreenedSeries gives them (nothing
// flagged): a wrap of roll into the turn is no count.
double ReadingQuantum(const std::vector<double>& t,
                      const std::vector<double>& x,
                      int channel) {
  return Quantum(t,
                 ScreenedSeries(t, x, channel, std::vector<char>(x.size(), 0)));
}

WildPoint FromJump(const Jump& j,
                   const TimeHistory& data,
                   int channel,
                   WildPointTest test) {
  const std::vector<double>& x = data.channel(channel);
  return {j.sample,
          data.t[j.sample],
          channel,
          x[j.sample],
          j.deviation,
          j.sigmas,
          test};
}

void SortPoints(std::vector<WildPoint>* points) {
  std::sort(points->begin(),
            points->end(),
            [](const WildPoint& a, const WildPoint& b) {
              return a.sample != b.sample ? a.sample < b.sample
                                          : a.channel < b.channel;
            });
}

}  // namespace

double ReadingStepDeg(const TimeHistory& data, int channel) {
  return ReadingQuantum(data.t, data.channel(channel), channel);
}

bool ParseOutlierPolicy(const std::string& text, OutlierPolicy* policy) {
  if (text == "warn") {
    *policy = OutlierPolicy::kWarn;
  } else if (text == "reject") {
    *policy = OutlierPolicy::kReject;
  } else {
    return false;
  }
  return true;
}

const char* OutlierPolicyName(OutlierPolicy policy) {
  return policy == OutlierPolicy::kReject ? "reject" : "warn";
}

std::string WildPoint::Describe() const {
  std::string line = std::string(ChannelName(channel)) + " = " +
                     FormatNumber("%.6g", value) +
                     " deg at t = " + FormatNumber("%.6g", t) + " s: ";
  switch (test) {
    case WildPointTest::kReach:
      return line +
             (channel == 1 ? "at or beyond +-90 deg" : "beyond 1e9 deg") +
             ", where no motion of the model goes";
    case WildPointTest::kJump:
      return line + FormatNumber("%.3g", deviation) +
             " deg off the cubic through its neighbours (" +
             FormatNumber("%.3g", sigmas) + " robust sigmas)";
    case WildPointTest::kResidual:
      return line + FormatNumber("%.3g", deviation) +
             " deg off the fitted motion (" + FormatNumber("%.3g", sigmas) +
             " robust sigmas)";
  }
  return line;
}

std::vector<WildPoint> ScreenData(const TimeHistory& data) {
  std::vector<WildPoint> points;
  const int n = data.size();
  if (n < kMinSamples) return points;
  for (int channel = 0; channel < 3; ++channel) {
    const std::vector<double>& x = data.channel(channel);
    std::vector<char> flagged(n, 0);
    const double reach = channel == 1 ? kThetaReachDeg : kAngleReachDeg;
    for (int i = 0; i < n; ++i) {
      if (!(std::abs(x[i]) < reach)) {
        flagged[i] = 1;
        points.push_back({i,
                          data.t[i],
                          channel,
                          x[i],
                          std::abs(x[i]) - reach,
                          std::numeric_limits<double>::infinity(),
                          WildPointTest::kReach});
      }
    }
    for (const Jump& j : FindChannelJumps(
             data.t, x, channel, flagged, ReadingQuantum(data.t, x, channel))) {
      points.push_back(FromJump(j, data, channel, WildPointTest::kJump));
    }
  }
  SortPoints(&points);
  return points;
}

std::vector<WildPoint> ScreenResiduals(const TimeHistory& data,
                                       const std::vector<double>& computed,
                                       const std::vector<int>& known) {
  const int n = data.size();
  CHECK_EQ(computed.size(), 3 * static_cast<size_t>(n));
  std::vector<WildPoint> points;
  if (n < kMinSamples) return points;
  for (int channel = 0; channel < 3; ++channel) {
    const std::vector<double>& x = data.channel(channel);
    std::vector<double> r(n);
    std::vector<char> flagged(n, 0);
    for (int i : known) flagged.at(i) = 1;
    bool finite = true;
    for (int i = 0; i < n; ++i) {
      r[i] = x[i] - computed[3 * i + channel];
      // Roll is compared modulo 360 deg, as the fit does.
      if (channel == 0) r[i] -= WholeTurns(r[i]);
      finite &= std::isfinite(r[i]) || flagged[i];
    }
    if (!finite) continue;  // a motion that blew up has no residuals to judge
    const double quantum = ReadingQuantum(data.t, x, channel);
    std::vector<Jump> jumps =
        FindChannelJumps(data.t, r, channel, flagged, quantum);
    for (const Jump& j : jumps) flagged[j.sample] = 1;
    // Beyond ten robust sigmas of the channel's residuals.
    std::vector<Real> kept;
    for (int i = 0; i < n; ++i) {
      if (!flagged[i]) kept.push_back(r[i]);
    }
    if (!kept.empty()) {
      const Real center = Median(kept);
      const Real sigma = std::max<Real>(
          {RobustSigma(kept), kFloorDeg, RoundingSigma(quantum)});
      for (int i = 0; i < n; ++i) {
        const Real out = std::abs(r[i] - center) / sigma;
        if (!flagged[i] && out > kThreshold) {
          jumps.push_back({i,
                           static_cast<double>(r[i] - center),
                           static_cast<double>(out)});
        }
      }
    }
    for (const Jump& j : jumps) {
      points.push_back(FromJump(j, data, channel, WildPointTest::kResidual));
    }
  }
  SortPoints(&points);
  return points;
}

TimeHistory DropSamples(const TimeHistory& data, const std::vector<int>& drop) {
  std::vector<char> gone(data.size(), 0);
  for (int i : drop) gone.at(i) = 1;
  TimeHistory kept;
  for (int i = 0; i < data.size(); ++i) {
    if (!gone[i])
      kept.Append(data.t[i], data.phi[i], data.theta[i], data.psi[i]);
  }
  return kept;
}

}  // namespace fit3dof
