// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Implausible (effect_validation.cc): each effect's plausibility bound
// (Effect::bounds) against fitted values and the record's angles; WrongSign:
// a probe's terms against their physical sign; HoldOut: the two halves of
// the out-of-sample check.

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "diagnose_internal.h"
#include "diagnose_search.h"
#include "fit3dof/angles.h"
#include "fit3dof/diagnose.h"
#include "gtest/gtest.h"

namespace fit3dof {
namespace {

// A fit of the symmetric model with `values` (by name) and one segment
// whose pitch and yaw readings reach theta_deg and psi_deg.
FitResult Fitted(const std::vector<std::pair<std::string, double>>& values,
                 double theta_deg,
                 double psi_deg) {
  FitResult fit;
  fit.model = ModelKind::kSymmetric;
  for (const auto& [name, value] : values) {
    ParameterEstimate e;
    e.name = name;
    e.value = value;
    e.free = true;
    fit.parameters.push_back(e);
  }
  SegmentFit s;
  s.data.Append(0.0, 0.0, theta_deg, 0.0);
  s.data.Append(0.1, 0.0, 0.0, psi_deg);
  fit.segments.push_back(s);
  return fit;
}

std::string Verdict(const char* effect, const FitResult& fit) {
  return Implausible(*FindEffect(effect), Case(), fit);
}

// The calibration error is judged in each channel at that channel's own
// largest angle: a cubic term of 0.02 deg at 5 deg is 0.035 deg at 6 deg,
// 0.16 at 10, 1.28 at 20 (the bound: 0.2 deg, or 3% of the angle, 0.6 deg
// at 20). Before, the largest angles were never filled in and no
// calibration term was ever implausible.
TEST(Implausible, CalibrationAtEachChannelsLargestAngle) {
  // The verdict on one cubic term with the channels reaching theta, psi.
  const auto calibration =
      [](const char* name, double value, double theta, double psi) {
        return Verdict("calibration_nonlinearity",
                       Fitted({{name, value}}, theta, psi));
      };
  EXPECT_EQ(calibration("theta_cal3", 0.02, 6.0, 1.0), "");
  EXPECT_EQ(calibration("theta_cal3", 0.02, 10.0, 1.0), "");
  const std::string why = calibration("theta_cal3", 0.02, 20.0, 1.0);
  EXPECT_NE(why.find("calibration error over the range to the largest angle "
                     "of 20 deg of 1.28 exceeds 0.6"),
            std::string::npos)
      << why;
  // A large term in a channel that stays near zero is harmless.
  EXPECT_EQ(calibration("psi_cal3", 5.0, 20.0, 0.5), "");
  EXPECT_NE(calibration("psi_cal3", 5.0, 0.5, 20.0), "");
}

// A term the record determines is held to 3% of its channel's largest
// angle or three noise sigmas where 0.2 deg is more: on a yaw reading that
// never left 0.47 deg, psi_cal3 = 56 +- 26 deg (0.047 deg there, 10% of
// the angle) had stood in, with a nonlinear damping, for a dry friction on
// the pitch axis alone. Undetermined, or within the noise, it is harmless.
TEST(Implausible, DeterminedCalibrationOnAQuietChannel) {
  // The verdict on one cubic term value +- error, the pitch reading
  // reaching `theta` deg, the yaw reading 0.47 deg, noise 0.01 deg.
  const auto calibration =
      [](const char* name, double value, double error, double theta) {
        FitResult fit = Fitted({{name, value}}, theta, 0.47);
        fit.parameters[0].standard_error = error;
        fit.segments[0].sigma_deg = {0.01, 0.01, 0.01};
        return Verdict("calibration_nonlinearity", fit);
      };
  const std::string why = calibration("psi_cal3", 56.0, 26.0, 8.0);
  EXPECT_NE(why.find("of 0.47 deg of 0.0465 exceeds 0.03"), std::string::npos)
      << why;
  // Within two errors of zero; 0.015 deg, the noise's size.
  EXPECT_EQ(calibration("psi_cal3", 56.0, 40.0, 8.0), "");
  EXPECT_EQ(calibration("psi_cal3", 15.3, 5.1, 8.0), "");
  // On a channel that reaches 5 deg the bound is 0.15 deg, not 0.2.
  EXPECT_NE(calibration("theta_cal3", 0.18, 0.01, 5.0), "");
  EXPECT_EQ(calibration("theta_cal3", 0.14, 0.01, 5.0), "");
}

// In its other form (Effect::other_form) the calibration error is the
// signed square less its straight line over the calibration's range R:
// judged at its largest over the channel's range, which the line can move
// inside it (0.5 (u |u| - 1.6 u), u = x / 5 deg, R = 32/3 deg, is 0 at 8
// deg and -0.32 at 4), only with a nonlinear term the record determines
// (a line alone is the reading_gain probe's), and with a range above zero.
TEST(Implausible, CalibrationAsASignedSquareLessItsLine) {
  const auto calibration =
      [](double cal2, double cal2_error, double range, double range_error) {
        FitResult fit = Fitted(
            {{"theta_cal2", cal2}, {"psi_cal2", 0.0}, {"cal_range", range}},
            8.0,
            8.0);
        fit.parameters[0].standard_error = cal2_error;
        fit.parameters[1].standard_error = 0.006;
        fit.parameters[2].standard_error = range_error;
        fit.segments[0].sigma_deg = {0.01, 0.01, 0.01};
        return Verdict("calibration_nonlinearity", fit);
      };
  // The suite's draw 52: 0.071 +- 0.006 deg over +-8 deg, 0.045 deg at
  // most.
  EXPECT_EQ(calibration(0.071, 0.006, 8.0, 1.0), "");
  const std::string inside = calibration(0.5, 0.01, 32.0 / 3.0, 1.0);
  EXPECT_NE(inside.find("of 8 deg of 0.32 exceeds 0.24"), std::string::npos)
      << inside;
  const std::string line = calibration(0.01, 0.01, 40.0, 5.0);
  EXPECT_NE(line.find("a straight line"), std::string::npos) << line;
  const std::string below = calibration(0.071, 0.006, -5.0, 1.0);
  EXPECT_NE(below.find("below zero"), std::string::npos) << below;
}

// A calibration added as the signed square (Effect::other_form) is
// judged, where every bound is judged within its errors, by the square's
// own terms: 0.45 deg over +-8 deg (0.29 deg at most, bound 0.24) is within
// two errors of 0.1 of its bound, not within two of 0.01. Judged by the
// cube's terms, absent from the model, it had been shrunk by nothing.
TEST(ImplausibleAmongAsJudged, ACalibrationInItsOtherFormByItsOwnTerms) {
  Case c;
  c.parameters.assign(NumParameters(ModelKind::kSymmetric), {});
  for (const char* name : {"theta_cal2", "psi_cal2"}) {
    c.parameters[FindParameter(c.model, name)].free = true;
  }
  c.parameters[FindParameter(c.model, "cal_range")].value = 8.0;
  const Effect* calibration = FindEffect("calibration_nonlinearity");
  ASSERT_TRUE(FormHeld(c, *calibration));
  DiagnoseOptions options;
  options.bounds_within_errors = true;
  options.every_bound_within_errors = true;
  const auto judged = [&](double error) {
    FitResult fit =
        Fitted({{"theta_cal2", 0.45}, {"psi_cal2", 0.0}, {"cal_range", 8.0}},
               8.0,
               8.0);
    fit.parameters[0].standard_error = error;
    fit.parameters[1].standard_error = error;
    fit.parameters[2].free = false;
    fit.segments[0].sigma_deg = {0.01, 0.01, 0.01};
    EXPECT_NE(Implausible(*calibration, c, fit), "");
    return ImplausibleAmongAsJudged({calibration}, c, fit, options);
  };
  EXPECT_EQ(judged(0.1), "");
  EXPECT_NE(judged(0.01), "");
}

// Judged within its errors, a term on a ridge moves with the coefficient
// it shares the ridge with (RidgeMoves): a nonlinear damping of 4.9 times
// |Cm_q| at 6 deg, Cm_q_delta2 -1280 +- 73 and Cm_q -2.88 +- 0.36 at
// -0.9996 correlation (suite draw 104's 3-s run, a true 3.6 times), moved
// 2 errors toward zero with Cm_q following is within 4 times |Cm_q|; with
// Cm_q held, or without the correlations, it is not.
TEST(ImplausibleAmongAsJudged, ANonlinearDampingAlongItsRidge) {
  Case c;
  c.parameters.assign(NumParameters(ModelKind::kSymmetric), {});
  c.parameters[FindParameter(c.model, "Cm_q_delta2")].free = true;
  const Effect* damping = FindEffect("nonlinear_damping");
  DiagnoseOptions options;
  options.bounds_within_errors = true;
  const auto judged = [&](double correlation) {
    FitResult fit =
        Fitted({{"Cm_q", -2.88}, {"Cm_q_delta2", -1280.0}}, 6.0, 1.0);
    fit.parameters[0].standard_error = 0.36;
    fit.parameters[1].standard_error = 73.0;
    fit.correlation_names = {"Cm_q", "Cm_q_delta2"};
    fit.correlation.resize(2, 2);
    fit.correlation << 1.0, correlation, correlation, 1.0;
    EXPECT_NE(Implausible(*damping, c, fit), "");
    return ImplausibleAmongAsJudged({damping}, c, fit, options);
  };
  EXPECT_EQ(judged(-0.9996), "");
  EXPECT_NE(judged(0.0), "");
}

// A tunnel stiffness added before is judged within its errors by the
// terms its own list names (tunnel_Cm_theta and tunnel_Cn_psi, as the fit
// does; the list had named them t1 and t3). Draw 70's 3-s run with a tunnel
// stiffness, a nonlinear damping and a body yaw asymmetry: with the damping in,
// t1 = -0.139 +- 0.127 on Eq. 43's ridge (half of |Cm_alpha + t1| being 0.115),
// and the aliases had matched nothing, so the stiffness was judged at its
// point fit and refused the damping beside it.
TEST(ImplausibleAmongAsJudged, ATunnelStiffnessByItsOwnTermsWithinItsErrors) {
  Case c;
  c.parameters.assign(NumParameters(ModelKind::kSymmetric), {});
  const Effect* stiffness = FindEffect("tunnel_stiffness");
  ASSERT_EQ(TermsIn(c, *stiffness),
            (std::vector<std::string>{"tunnel_Cm_theta", "tunnel_Cn_psi"}));
  DiagnoseOptions options;
  options.bounds_within_errors = true;
  const auto judged = [&](double error) {
    FitResult fit = Fitted({{"Cm_alpha", -0.092},
                            {"tunnel_Cm_theta", -0.139},
                            {"tunnel_Cn_psi", -0.137}},
                           8.0,
                           8.0);
    for (ParameterEstimate& e : fit.parameters) e.standard_error = error;
    EXPECT_NE(Implausible(*stiffness, c, fit), "");
    return ImplausibleAmongAsJudged({stiffness}, c, fit, options);
  };
  EXPECT_EQ(judged(0.127), "");
  EXPECT_NE(judged(0.01).find("|t1|"), std::string::npos);
}

// A nonlinear damping may change Cm_q by up to 4 times its size at the
// record's largest angle: 3 times (a damping that reverses at 8 deg) is
// plausible, 5 is not.
TEST(Implausible, NonlinearTermAgainstItsLinearOne) {
  const double d2 = std::pow(8.0 * kDegree, 2);
  const auto damping = [&](double times) {
    return Verdict(
        "nonlinear_damping",
        Fitted({{"Cm_q", -5.5}, {"Cm_q_delta2", times * 5.5 / d2}}, 8.0, 1.0));
  };
  EXPECT_EQ(damping(3.0), "");
  const std::string why = damping(5.0);
  EXPECT_NE(why.find("it changes Cm_q by 27.5 over the record, more than 4 "
                     "times |Cm_q| = 5.5"),
            std::string::npos)
      << why;
}

// With Eq. 39's tunnel damping in the model the motion determines Cm_q +
// t2, and Cm_q alone slides along Eq. 43's ridge: the bound weighs against
// the larger of the two. A damping of 11.8 over the record with Cm_q at
// -0.33 along the ridge and t2 = -7 is plausible; with the tunnel term at
// zero it is not.
TEST(Implausible, NonlinearTermAlongTheTunnelRidge) {
  const double d2 = std::pow(8.0 * kDegree, 2);
  const auto damping = [&](double tunnel) {
    return Verdict("nonlinear_damping",
                   Fitted({{"Cm_q", -0.33},
                           {"tunnel_Cm_thetadot", tunnel},
                           {"Cm_q_delta2", 11.8 / d2}},
                          8.0,
                          1.0));
  };
  EXPECT_EQ(damping(-7.0), "");
  const std::string why = damping(0.0);
  EXPECT_NE(why.find("more than 4 times |Cm_q| = 0.33"), std::string::npos)
      << why;
  // A tunnel term that takes the sum toward zero does not tighten it.
  EXPECT_NE(damping(0.3), "");
  EXPECT_EQ(Verdict("nonlinear_damping",
                    Fitted({{"Cm_q", -5.5},
                            {"tunnel_Cm_thetadot", 5.0},
                            {"Cm_q_delta2", 3.0 * 5.5 / d2}},
                           8.0,
                           1.0)),
            "");
}

// In yaw the stiffness Cn_beta acts on the sideslip (-psi) and t3 on psi:
// their sum is Cn_beta - t3. A cubic term changing Cn_beta by 0.28 over
// the record passes beside Cn_beta = 0.05 and t3 = -0.04 (0.09), not
// beside t3 = +0.04 (0.01; Cn_beta's own 0.05 is the larger).
TEST(Implausible, NonlinearYawStiffnessAlongTheTunnelRidge) {
  const double d2 = std::pow(8.0 * kDegree, 2);
  const auto stiffness = [&](double t3) {
    return Verdict(
        "nonlinear_stiffness",
        Fitted(
            {{"Cn_beta", 0.05}, {"tunnel_Cn_psi", t3}, {"Cn_beta3", 0.28 / d2}},
            8.0,
            1.0));
  };
  EXPECT_EQ(stiffness(-0.04), "");
  const std::string why = stiffness(0.04);
  EXPECT_NE(why.find("more than 4 times |Cn_beta| = 0.05"), std::string::npos)
      << why;
}

// A roll damping damps: Cl_p positive by more than 2 standard errors is
// refused, within them (or negative) accepted.
TEST(Implausible, RollDampingThatDrivesTheRoll) {
  FitResult fit = Fitted({{"Cl_p", 0.0026}}, 8.0, 8.0);
  fit.parameters[0].standard_error = 0.0004;
  const std::string why = Verdict("roll_damping", fit);
  EXPECT_NE(why.find("Cl_p = 0.0026 +- 0.0004 drives the roll"),
            std::string::npos)
      << why;
  fit.parameters[0].standard_error = 0.002;
  EXPECT_EQ(Verdict("roll_damping", fit), "");
  fit.parameters[0].value = -0.0081;
  fit.parameters[0].standard_error = 0.0004;
  EXPECT_EQ(Verdict("roll_damping", fit), "");
}

TEST(Implausible, ReadingErrorTrimAngleAndBearingAngle) {
  EXPECT_EQ(
      Verdict(
          "roll_interaction",
          Fitted({{"theta_cos_phi", 0.1}, {"theta_sin_phi", 0.1}}, 8.0, 8.0)),
      "");
  EXPECT_NE(
      Verdict("roll_interaction",
              Fitted({{"psi_cos_phi", 0.2}, {"psi_sin_phi", 0.1}}, 8.0, 8.0)),
      "");
  // A trim angle of |(Cm_0, Cn_0)| / |Cm_alpha|: 1.4 deg, then 2.9 deg.
  EXPECT_EQ(Verdict("trim_moment",
                    Fitted({{"Cm_alpha", -0.2}, {"Cm_0", 0.005}}, 8.0, 8.0)),
            "");
  EXPECT_NE(Verdict("trim_moment",
                    Fitted({{"Cm_alpha", -0.2}, {"Cm_0", 0.01}}, 8.0, 8.0)),
            "");
  const auto bearing = [](double angle) {
    return Verdict("bearing_moment",
                   Fitted({{"Cm_alpha", -0.2},
                           {"Cm_bearing", -0.05},
                           {"bearing_angle", angle}},
                          8.0,
                          0.0));
  };
  EXPECT_EQ(bearing(1.0), "");
  EXPECT_NE(bearing(9.0).find("outside the record's angles"),
            std::string::npos);
}

// The tunnel terms are judged by their names (t1..t4 are aliases, which
// the estimates do not carry: the bounds had read zeros and never acted),
// against the stiffness or damping the record holds, the body-fixed term
// plus the tunnel one: along Eq. 43 each alone can go anywhere.
TEST(Implausible, TunnelTermsAgainstTheRecordsStiffnessAndDamping) {
  const auto stiffness = [](double cm_alpha, double t1, double t3) {
    return Verdict("tunnel_stiffness",
                   Fitted({{"Cm_alpha", cm_alpha},
                           {"tunnel_Cm_theta", t1},
                           {"tunnel_Cn_psi", t3}},
                          8.0,
                          8.0));
  };
  // The suite's truth, and a record's -0.23 shared out between the two.
  EXPECT_EQ(stiffness(-0.23, 0.016, -0.0056), "");
  EXPECT_EQ(stiffness(-0.151, -0.079, -0.079), "");
  // A confident wrong answer on a 3-s run: Cm_alpha -1.29 (truth -0.23)
  // and t1 = t3 = 1.06, half of |Cm_alpha| being 0.65.
  EXPECT_NE(stiffness(-1.29, 1.06, 1.06).find("|t1|"), std::string::npos);
  EXPECT_NE(stiffness(-0.23, 0.0, 0.2).find("|t3|"), std::string::npos);
  const auto damping = [](double cm_q, double t2, double t4) {
    return Verdict("tunnel_damping",
                   Fitted({{"Cm_q", cm_q},
                           {"tunnel_Cm_thetadot", t2},
                           {"tunnel_Cn_psidot", t4}},
                          8.0,
                          8.0));
  };
  EXPECT_EQ(damping(-5.5, -1.65, 2.24), "");
  EXPECT_NE(damping(-12.0, 9.0, 0.0).find("|t2|"), std::string::npos);
}

// A newcomer's fit may push an effect added before past its bound: the
// model with both is judged by every effect in it.
TEST(ImplausibleAmong, NamesTheEarlierEffectPushedPastItsBound) {
  const std::vector<const Effect*> added = {FindEffect("flow_angularity"),
                                            FindEffect("roll_interaction")};
  EXPECT_EQ(ImplausibleAmong(added,
                             Case(),
                             Fitted({{"theta_T", 0.1},
                                     {"theta_cos_phi", 0.15},
                                     {"theta_sin_phi", 0.1}},
                                    8.0,
                                    8.0)),
            "");
  const std::string why = ImplausibleAmong(
      added,
      Case(),
      Fitted(
          {{"theta_T", 0.1}, {"theta_cos_phi", 0.15}, {"theta_sin_phi", 0.2}},
          8.0,
          8.0));
  EXPECT_EQ(
      why.find("roll_interaction (added before): a reading error of 0.25"), 0u)
      << why;
}

// A probe's terms with a physical sign: a filter lags (a lead in pitch, of
// 2.6 of its errors, had stood in for a Magnus moment beside the other
// effects of a pair of runs), a friction opposes the motion. Within two
// standard errors of zero either sign is noise; terms without a sign (a
// gain, a drift) and terms not the probe's are not judged.
TEST(WrongSign, LagsAndFrictionsArePositive) {
  const auto judged =
      [](const char* probe, const char* name, double value, double error) {
        FitResult fit = Fitted({{name, value}}, 8.0, 8.0);
        fit.parameters[0].standard_error = error;
        return WrongSign(*FindProbe(probe), fit);
      };
  EXPECT_EQ(judged("reading_lag", "theta_lag", -0.017, 0.0067),
            "theta_lag = -0.017 +- 0.0067 is negative");
  EXPECT_EQ(judged("reading_lag", "psi_lag", -0.005, 0.0062), "");
  EXPECT_EQ(judged("reading_lag", "psi_lag", 0.017, 0.0067), "");
  EXPECT_NE(judged("bearing_friction", "Cm_friction", -3e-4, 2e-5), "");
  EXPECT_NE(judged("axis_friction", "Cm_axis_friction", -1e-4, 1e-5), "");
  EXPECT_NE(judged("pitch_friction", "Cm_pitch_friction", -1e-4, 1e-5), "");
  EXPECT_NE(judged("yaw_friction", "Cn_yaw_friction", -1e-4, 1e-5), "");
  EXPECT_EQ(judged("yaw_friction", "Cn_yaw_friction", 1e-4, 1e-5), "");
  EXPECT_EQ(judged("reading_gain", "theta_gain", -0.05, 0.001), "");
  EXPECT_EQ(judged("bearing_friction", "theta_lag", -0.017, 0.0067), "");
}

// Each term past zero is named (the probe's fit holds those at zero when
// its other terms keep their sign: SignHeld).
TEST(WrongSign, NamesEachTermPastZero) {
  FitResult fit = Fitted({{"theta_lag", 0.0066}, {"psi_lag", -0.00105}}, 8, 8);
  fit.parameters[0].standard_error = 0.00027;
  fit.parameters[1].standard_error = 0.00051;
  const Effect& lag = *FindProbe("reading_lag");
  auto wrong = WrongSignTerms(lag, fit);
  ASSERT_EQ(wrong.size(), 1u);
  EXPECT_EQ(wrong[0]->name, "psi_lag");
  fit.parameters[0].value = -0.0066;
  wrong = WrongSignTerms(lag, fit);
  ASSERT_EQ(wrong.size(), 2u);
  EXPECT_EQ(wrong[0]->name, "theta_lag");
  fit.parameters[1].value = -0.00095;  // within two errors of zero
  EXPECT_EQ(WrongSignTerms(lag, fit).size(), 1u);
}

// The two halves of HoldOut: half 0 holds out the odd runs of samples,
// half 1 the even ones; each sample but the first is held out by exactly
// one, and the first, where the initial conditions are fitted, is trained
// on by both. What each trains on is what it does not hold out.
TEST(HoldOut, TheTwoHalvesHoldOutEverySampleButTheFirstOnce) {
  TimeHistory d;
  for (int i = 0; i < 53; ++i) d.Append(0.06 * i, i, 2.0 * i, 3.0 * i);
  const HeldOut first = HoldOut({d}, 8, 0);
  const HeldOut second = HoldOut({d}, 8, 1);
  ASSERT_EQ(first.held.size(), 1u);
  ASSERT_EQ(second.held.size(), 1u);
  EXPECT_FALSE(first.held[0][0]);
  EXPECT_FALSE(second.held[0][0]);
  int held_first = 0;
  for (int i = 1; i < d.size(); ++i) {
    EXPECT_NE(first.held[0][i], second.held[0][i]) << "sample " << i;
    held_first += first.held[0][i];
  }
  // The first run (samples 0-6 of 53) is half 0's training, the second
  // (7-13) its held-out part.
  EXPECT_FALSE(first.held[0][6]);
  EXPECT_TRUE(first.held[0][7]);
  EXPECT_TRUE(second.held[0][6]);
  EXPECT_EQ(first.train[0].size(), d.size() - held_first);
  EXPECT_EQ(second.train[0].size(), 1 + held_first);
  EXPECT_EQ(second.train[0].t[0], 0.0);
  EXPECT_EQ(second.train[0].t[1], d.t[7]);
}

// A fit of a roll read in 2-deg counts (the motion 2.24 deg a sample, the
// grid's zero at 0.6 deg): `before` leaves the rounding's sawtooth, `after`
// takes `share` of it out of roll and lowers pitch's squares by
// `pitch_drop`.
std::pair<FitResult, FitResult> RoundedRollFits(double share,
                                                double pitch_drop) {
  SegmentFit before;
  const int n = 44;
  for (int i = 0; i < n; ++i) {
    const double phi = 2.24 * i + 0.3;
    const double read = 2.0 * std::round((phi - 0.6) / 2.0) + 0.6;
    before.data.Append(0.069 * i, read, 5.0, 0.0);
    before.computed.insert(before.computed.end(), {phi, 5.0, 0.0});
  }
  before.sigma_deg = {2.0 / std::sqrt(12.0), 0.01, 0.01};
  before.rms_residual_deg = {0.577, 0.01, 0.01};
  SegmentFit after = before;
  for (int i = 0; i < n; ++i) {
    after.computed[3 * i] +=
        share * (before.data.phi[i] - before.computed[3 * i]);
  }
  // One pitch reading off by 1 sigma before, on it after: a drop of 1 per
  // such reading.
  for (int i = 0; i < static_cast<int>(pitch_drop); ++i) {
    before.computed[3 * i + 1] += 0.01;
  }
  FitResult b, a;
  b.segments = {before};
  a.segments = {after};
  return {b, a};
}

// RestsOnRoundedReadings: a drop that only the roll counts' sawtooth pays
// for is refused, naming the channel; one the other channels earn alone
// stands.
TEST(RestsOnRoundedReadings, RefusesADropOnlyTheCountsSawtoothPaysFor) {
  const auto [before, after] = RoundedRollFits(0.5, 2.0);
  // Roll's squares fall by 3/4 of ~44 (half the sawtooth taken out).
  const std::string why = RestsOnRoundedReadings(before, after, 20.0, 10.0);
  EXPECT_NE(why.find("phi (counts of 2 deg"), std::string::npos) << why;
  // The same fall in roll beside a drop that leaves more than 10 without
  // it.
  EXPECT_EQ(RestsOnRoundedReadings(before, after, 50.0, 10.0), "");
  // A roll residual well above its rounding is the record's, not the
  // counts': its fall counts.
  auto [b3, a3] = RoundedRollFits(0.5, 2.0);
  b3.segments[0].rms_residual_deg.phi = 1.0;
  EXPECT_EQ(RestsOnRoundedReadings(b3, a3, 20.0, 10.0), "");
}

}  // namespace
}  // namespace fit3dof
