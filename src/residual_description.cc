// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// What structured residuals show (DescribeResiduals, diagnose.h), in the
// terms an engineer checks a missing effect by: which frequencies (the
// motion's own modes, the spin and its harmonics), a trend in time, a
// dependence on the angle the bearing sits at, a dependence on roll; and
// the readings far off the fitted motion (wild_points.h), which a smooth
// missing effect does not leave: a wild point, or a transient the model
// lacks (a filter in the signal conditioning starting at rest).

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "fit3dof/angles.h"
#include "fit3dof/diagnose.h"
#include "fit3dof/wild_points.h"
#include "format.h"
#include "line_statistics.h"
#include "spectral_lines.h"

namespace fit3dof {
namespace {

// A regression's share of a residual's variance below which it is not
// worth naming.
constexpr double kNamedShare = 0.1;

// The upper point of the F distribution with (k, m) degrees of freedom
// that a standard normal deviate z marks, by Paulson's cube-root normal
// approximation (within a few percent for m >= 10), solved by bisection.
double FQuantile(int k, int m, double z) {
  const double a = 2.0 / (9.0 * k), b = 2.0 / (9.0 * m);
  const auto deviate = [&](double f) {
    const double c = std::cbrt(f);
    return ((1.0 - b) * c - (1.0 - a)) / std::sqrt(b * c * c + a);
  };
  double lo = 0.0, hi = 1e4;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (deviate(mid) < z ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The share k regressors take of white noise's variance over n samples
// with chance 1e-3, the residual checks' own (residual_check.cc): the
// regression's F statistic (n - k - 1) R^2 / (k (1 - R^2)) at its upper
// 0.1% point. On a 47-sample run six roll harmonics take 13% of noise on
// average and 41% once in a thousand: noise alone had been described as
// "a dependence on the roll angle, harmonics 1-3 (17%)".
double ChanceShare(int k, int n, double z) {
  const int m = std::max(1, n - k - 1);
  const double f = k * FQuantile(k, m, z);
  return f / (f + m);
}

// The deviate ResidualsDepend holds a share to: chance 1e-5 a test, six
// tests a segment. It refuses an explanation, so it must all but never
// refuse the true model's: at 1e-3 (the description's), on draw 152's 3-s
// coning run with a nonlinear damping, the true model's pitch residual
// took 37% on roll's harmonics (36% by chance once in a thousand) and the
// record was left `not_explained`. An even calibration error of the pitch
// reading (draw 152's coning run) leaves 73% on the pitch angle, where 43%
// is the 1e-5 mark.
constexpr double kZ1e5 = 4.2648907939228;

// Frequencies within this fraction of a reference are called "at" it.
constexpr double kNear = 0.05;

// The lag-1 autocorrelation of `v` about its mean.
double Lag1Of(const Eigen::VectorXd& v) {
  const Eigen::VectorXd c = v.array() - v.mean();
  const int n = static_cast<int>(c.size());
  const double den = c.squaredNorm();
  if (n < 2 || !(den > 0.0)) return 0.0;
  return c.head(n - 1).dot(c.tail(n - 1)) / den;
}

// How the columns of x meet r by least squares: the share of r's variance
// (about its mean) they explain, and the samples that share is as likely
// from as from independent ones. Where the errors are serially correlated
// (the lag-1 autocorrelation rho of what the regression leaves, when
// positive) and so is a regressor (rho_x, the largest of its columns'),
// a coefficient's variance grows by (1 + rho rho_x) / (1 - rho rho_x)
// (Bartlett): AR(1) reading errors of 0.6 on a 3-s run follow roll's slow
// harmonics as a missing effect would, and had been described as "a
// dependence on the roll angle, harmonics 1-3 (50%)" (draw 164's colored
// `pair` record). What the regression takes out of a residual of its own
// shape (a drift, a roll-locked error) leaves rho near 0 and n as it is.
struct Regression {
  double share = 0.0;
  double samples = 0.0;
};

Regression Regress(const Eigen::MatrixXd& x, const Eigen::VectorXd& r) {
  const int n = static_cast<int>(r.size());
  Regression g{0.0, static_cast<double>(n)};
  Eigen::MatrixXd design(n, x.cols() + 1);
  design << Eigen::VectorXd::Ones(n), x;
  const Eigen::VectorXd centred = r.array() - r.mean();
  const double total = centred.squaredNorm();
  if (!(total > 0.0)) return g;
  const Eigen::VectorXd left =
      r - design * design.colPivHouseholderQr().solve(r);
  g.share = std::clamp(1.0 - left.squaredNorm() / total, 0.0, 1.0);
  double rho_x = 0.0;
  for (int j = 0; j < x.cols(); ++j) rho_x = std::max(rho_x, Lag1Of(x.col(j)));
  // rho less its noise (sd 1 / sqrt(n)): a white residual's own lag-1
  // (0.15 on 47 samples) had hidden a drift of three times the noise. And
  // with the regression's bias put back (what k smooth columns take out of
  // a residual's lag-1, about (k + 1) / n).
  const double rho = std::max(
      0.0, Lag1Of(left) + (x.cols() + 1.0) / n - 1.0 / std::sqrt(1.0 * n));
  const double product = rho * rho_x;
  g.samples = n * (1.0 - product) / (1.0 + product);
  return g;
}

// Whether a regression's share is worth naming: above kNamedShare and
// above what noise reaches with the chance standard normal deviate `z`
// marks, on the regression's effective samples.
bool Named(const Regression& g, int k, double z) {
  return g.share >
         std::max(kNamedShare, ChanceShare(k, static_cast<int>(g.samples), z));
}

std::string Percent(double share) {
  return FormatNumber("%.0f", 100.0 * share) + "%";
}

// What a residual line at f (Hz) of a record `duration` s long sits at:
// the periodogram's first bin (one cycle over the record: a slow drift,
// which a missing effect that changes over the run leaves, the roll's of
// a spin that slows), a mode of the motion, a harmonic of the spin, or
// neither.
std::string LineName(double f,
                     double duration,
                     const std::vector<SpectralLine>& modes,
                     double spin_hz) {
  if (f * duration < 1.5) return "one cycle over the record: a slow drift";
  for (const SpectralLine& m : modes) {
    if (std::abs(f - m.frequency_hz) <= kNear * m.frequency_hz) {
      return "at the motion's mode of " + FormatNumber("%.3g", m.frequency_hz) +
             " Hz";
    }
  }
  for (int h = 1; h <= 3 && spin_hz > 0.0; ++h) {
    if (std::abs(f - h * spin_hz) <= kNear * h * spin_hz) {
      return "at " + std::to_string(h) + " x spin";
    }
  }
  return "at neither the motion's modes nor the spin";
}

// A channel's residual (measured minus computed, deg; roll's within a
// turn), its computed angle and whether its dependences (Dependences) are
// asked: pitch's and yaw's, not roll's. Roll's residual is described by
// its lines alone: its angle grows without bound, and over a slow roll its
// harmonics and a trend are slow functions of time that serially
// correlated reading errors follow as an effect would (AR(1) errors of 0.6
// on a 3-s run at 30 deg/s: "roll: a dependence on the roll angle,
// harmonics 1-3 (58-66%)" in 3 of 20 records); a roll-locked error over
// several turns shows as a line at the spin's harmonics.
struct Channel {
  const char* name;
  Eigen::VectorXd residual, angle;
  bool dependences = true;
};

// The shares of a channel's residual variance that a trend in time, the
// angle's powers 1-3 (a calibration curve, a stiffness that changes with
// amplitude) and roll's harmonics 1-3 take, each with whether it is worth
// naming (Named, at the deviate `z`).
struct Dependence {
  double trend = 0.0, amplitude = 0.0, locked = 0.0;
  bool trend_named = false, amplitude_named = false, locked_named = false;
  bool Any() const { return trend_named || amplitude_named || locked_named; }
};

Dependence Dependences(const Channel& c,
                       const Eigen::VectorXd& t,
                       const Eigen::VectorXd& roll,
                       double z) {
  const int n = static_cast<int>(t.size());
  Dependence d;
  const Eigen::VectorXd centred_t = t.array() - t.mean();
  const Regression trend = Regress(centred_t, c.residual);
  d.trend = trend.share;
  d.trend_named = Named(trend, 1, z);
  Eigen::MatrixXd powers(n, 3);
  const double scale = std::max(c.angle.cwiseAbs().maxCoeff(), 1e-12);
  for (int p = 0; p < 3; ++p) {
    powers.col(p) = (c.angle / scale).array().pow(p + 1);
  }
  const Regression amplitude = Regress(powers, c.residual);
  d.amplitude = amplitude.share;
  d.amplitude_named = Named(amplitude, 3, z);
  Eigen::MatrixXd harmonics(n, 6);
  for (int h = 1; h <= 3; ++h) {
    harmonics.col(2 * h - 2) = (h * roll).array().cos();
    harmonics.col(2 * h - 1) = (h * roll).array().sin();
  }
  const Regression locked = Regress(harmonics, c.residual);
  d.locked = locked.share;
  d.locked_named = Named(locked, 6, z);
  return d;
}

// What channel `c`'s residual shows (lines against the motion's `modes`
// and the spin's harmonics, a trend, dependences), or empty.
std::string DescribeChannel(const Channel& c,
                            const Eigen::VectorXd& t,
                            const Eigen::VectorXd& roll,
                            const std::vector<SpectralLine>& modes,
                            double spin_hz) {
  const int n = static_cast<int>(t.size());
  const double dt = (t(n - 1) - t(0)) / (n - 1);
  std::string text;
  const auto add = [&](const std::string& s) {
    text += (text.empty() ? "" : ", ") + s;
  };
  const std::vector<double> r(c.residual.data(), c.residual.data() + n);
  for (const SpectralLine& line : ResidualLines(r, dt)) {
    add("a line at " + FormatNumber("%.3g", line.frequency_hz) + " Hz (" +
        LineName(line.frequency_hz, n * dt, modes, spin_hz) + ")");
  }
  const Dependence d =
      c.dependences ? Dependences(c, t, roll, kZ999) : Dependence();
  if (d.trend_named) add("a trend in time (" + Percent(d.trend) + ")");
  if (d.amplitude_named) {
    add(std::string("a dependence on the ") + c.name + " angle (" +
        Percent(d.amplitude) + ")");
  }
  if (d.locked_named) {
    add("a dependence on the roll angle, harmonics 1-3 (" + Percent(d.locked) +
        ")");
  }
  return text.empty() ? "" : std::string(c.name) + ": " + text;
}

// The readings the residual screen (ScreenResiduals) finds far off the
// fitted motion, the first three described, or empty.
std::string FarReadings(const SegmentFit& s) {
  constexpr int kDescribed = 3;
  const std::vector<WildPoint> far = ScreenResiduals(s.data, s.computed, {});
  if (far.empty()) return "";
  std::string text =
      std::string(far.size() == 1 ? "a reading" : "readings") +
      " far off the fitted motion (a wild point, or a transient the model "
      "lacks): ";
  for (size_t i = 0; i < far.size() && i < kDescribed; ++i) {
    text += (i > 0 ? "; " : "") + far[i].Describe();
  }
  if (far.size() > kDescribed) {
    text += "; " + std::to_string(far.size() - kDescribed) + " more";
  }
  return text;
}

// The channels of `s` whose readings lie on a grid (ReadingStepDeg), each
// with the RMS its rounding alone leaves (the step over sqrt(12)) beside its
// residual's: a residual that size is the rounding's sawtooth, which reads
// as structure where the motion crosses the counts at a steady pace.
std::string GridReadings(const SegmentFit& s) {
  static const char* const kNames[] = {"roll", "pitch", "yaw"};
  std::string text;
  for (int ch = 0; ch < 3; ++ch) {
    const double step = ReadingStepDeg(s.data, ch);
    if (!(step > 0.0)) continue;
    text += std::string(text.empty() ? "" : "; ") + kNames[ch] +
            " read in counts of " + FormatNumber("%.3g", step) +
            " deg: their rounding alone leaves " +
            FormatNumber("%.3g", step / std::sqrt(12.0)) +
            " deg RMS, the residual " +
            FormatNumber("%.3g", s.rms_residual_deg[ch]);
  }
  return text;
}

// The pitch and yaw channels of segment `s` (at least 16 samples) into
// channels[0..1], roll's into channels[2], its times into *t and its
// fitted roll (rad) into *roll.
void SegmentChannels(const SegmentFit& s,
                     Eigen::VectorXd* t,
                     Eigen::VectorXd* roll,
                     Channel channels[3]) {
  const int n = s.data.size();
  t->resize(n);
  roll->resize(n);
  channels[0] = {"pitch", Eigen::VectorXd(n), Eigen::VectorXd(n)};
  channels[1] = {"yaw", Eigen::VectorXd(n), Eigen::VectorXd(n)};
  channels[2] = {"roll", Eigen::VectorXd(n), Eigen::VectorXd(n), false};
  for (int i = 0; i < n; ++i) {
    (*t)(i) = s.data.t[i];
    (*roll)(i) = s.computed[3 * i] * kDegree;
    const double measured[3] = {s.data.theta[i], s.data.psi[i], s.data.phi[i]};
    const double computed[3] = {
        s.computed[3 * i + 1], s.computed[3 * i + 2], s.computed[3 * i]};
    for (int c = 0; c < 3; ++c) {
      double r = measured[c] - computed[c];
      if (c == 2) r -= WholeTurns(r);  // roll is compared modulo a turn
      channels[c].angle(i) = computed[c];
      channels[c].residual(i) = r;
    }
  }
}

// The modes of a segment's motion that its residuals' lines are named
// against: the strongest lines of the computed pitch and yaw of its
// `channels` (SegmentChannels), sampled at times `t`.
std::vector<SpectralLine> MotionModes(const Channel channels[3],
                                      const Eigen::VectorXd& t) {
  const int n = static_cast<int>(t.size());
  const double dt = (t(n - 1) - t(0)) / (n - 1);
  std::vector<SpectralLine> modes;
  for (int c = 0; c < 2; ++c) {
    const Eigen::VectorXd& a = channels[c].angle;
    for (const SpectralLine& m : SpectralLines(
             std::vector<double>(a.data(), a.data() + n), dt, 4.0, 2)) {
      modes.push_back(m);
    }
  }
  return modes;
}

// The segments DescribeResiduals and ResidualsDepend look at: enough
// samples for the regressions.
constexpr int kLeastSamples = 16;

// The least pooled lag-1 autocorrelation named: a tenth of each sample's
// variance shared with the next.
constexpr double kNamedLag1 = 0.1;

// What a broadband residual correlated from one sample to the next shows
// (its pooled lag-1 autocorrelation above what noise reaches with chance
// 1e-3, one-sided: a fit lowers that of noise); or empty. Reading errors
// that are not white (a filtered or wandering reading) and process noise
// leave such a residual, and so does an effect too weak to show its shape
// (draw 165's `coning` yaw stiffness outside the catalog: theta 0.49, psi
// 0.56): draws 163-164's colored `correlated` records ended
// `not_explained` as "broadband" with every channel's lag-1 at 0.2-0.3,
// each under its own limit. The standard errors already count it (fit.h:
// each channel's own autocorrelation, Morelli and Klein 1995).
std::string CorrelatedNote(const FitResult& fit) {
  // Each channel's lag-1 as the residual check reads it; pooled over the
  // three (scale-free: the channels' noise levels differ), each with the
  // same samples.
  int samples = 0;
  for (const SegmentFit& s : fit.segments) samples += 3 * s.data.size();
  if (samples < 3 * kLeastSamples) return "";
  const ChannelValues lag = ResidualLag1(fit);
  const double pooled = (lag.phi + lag.theta + lag.psi) / 3.0;
  const double limit =
      std::max(kNamedLag1, kZ999 / std::sqrt(static_cast<double>(samples)));
  if (!(pooled > limit)) return "";
  return ", yet correlated from one sample to the next (lag-1 "
         "autocorrelation " +
         FormatNumber("%.2f", pooled) + " over the channels: phi " +
         FormatNumber("%.2f", lag.phi) + " theta " +
         FormatNumber("%.2f", lag.theta) + " psi " +
         FormatNumber("%.2f", lag.psi) + "; noise stays under " +
         FormatNumber("%.2f", limit) +
         "): slow structure of no shape named here, as reading errors "
         "that are not white (a filtered or wandering reading), process "
         "noise (random moments the motion integrates) or an effect too "
         "weak on this record to show its own shape leave; the standard "
         "errors count the correlation (each channel's own "
         "autocorrelation), and a filter-error fit (solver: {method: "
         "filter_error}) tells process noise apart";
}

}  // namespace

bool ResidualsDepend(const FitResult& fit) {
  for (const SegmentFit& s : fit.segments) {
    if (s.data.size() < kLeastSamples) continue;
    Eigen::VectorXd t, roll;
    Channel channels[3];
    SegmentChannels(s, &t, &roll, channels);
    // Pitch and yaw: the residual check's test of what the aerodynamic
    // moments leave. Roll's residual is described (DescribeResiduals), not
    // tested: what roll's equation leaves (Cl_0, Cl_p) the check judges by
    // the residual's size and lag-1 autocorrelation already.
    for (int c = 0; c < 2; ++c) {
      if (Dependences(channels[c], t, roll, kZ1e5).Any()) return true;
    }
  }
  return false;
}

std::string DescribeResiduals(const FitResult& fit) {
  std::string text, far;
  for (const SegmentFit& s : fit.segments) {
    if (s.data.size() < kLeastSamples) continue;
    Eigen::VectorXd t, roll;
    Channel channels[3];
    SegmentChannels(s, &t, &roll, channels);
    const std::vector<SpectralLine> modes = MotionModes(channels, t);
    const double spin_hz = SpinHz(s);
    std::string segment;
    for (const Channel& c : channels) {
      const std::string part = DescribeChannel(c, t, roll, modes, spin_hz);
      if (!part.empty()) segment += (segment.empty() ? "" : "; ") + part;
    }
    // The readings' notes, each under its segment's name when there are
    // several.
    for (const std::string& note : {FarReadings(s), GridReadings(s)}) {
      if (note.empty()) continue;
      far += (far.empty() ? "" : "; ") +
             (fit.segments.size() > 1 ? "'" + s.name + "': " : "") + note;
    }
    if (segment.empty()) continue;
    if (fit.segments.size() > 1) segment = "'" + s.name + "': " + segment;
    text += (text.empty() ? "" : "; ") + segment;
  }
  if (!far.empty()) far = "; " + far;
  if (text.empty()) {
    return "no line, trend, angle or roll dependence stands out: the "
           "residual is broadband" +
           CorrelatedNote(fit) + far;
  }
  return "the residuals show " + text +
         " (shares: of the channel's residual variance)" + far;
}

}  // namespace fit3dof
