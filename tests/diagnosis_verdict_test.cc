// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The verdict's words (diagnosis_verdict.cc, Conclude) on diagnoses built
// by hand: what a search leaves in a Diagnosis, read back as the engineer
// reads it.

#include <string>
#include <utility>

#include "diagnose_internal.h"
#include "fit3dof/diagnose.h"
#include "gtest/gtest.h"

namespace fit3dof {
namespace {

// A search whose last step took the residuals to the noise level's limit
// and was not adopted, a probe outside the catalog having outdone the
// catalog past it (draw 127's 3-s run with a roll reading error, sigma:
// auto, before a probe had to predict the held-out part: probable error
// 1.12 against a limit of 1.51).
Diagnosis PartialAtTheNoiseLevel() {
  Diagnosis d;
  d.fits.resize(2);
  d.fits[0].probable_error = 1.9;
  d.fits[1].probable_error = 1.12;
  d.final_fit = 0;
  d.partial_fit = 1;
  DiagnosisStep step;
  step.effect = "roll_interaction";
  step.description = "a pitch and yaw reading error that varies with roll";
  step.after.white = true;
  step.after.at_noise_level = true;
  step.after.noise_limit = 1.51;
  d.partial = {step};
  d.final.probable_error = 1.9;
  d.final.noise_limit = 1.51;
  d.outside_catalog.effect = "pressure_drift";
  d.outside_catalog.bic_drop = 12.3;
  return d;
}

TEST(Conclude, AStepAtTheNoiseLevelOutdoneByAProbeSaysSo) {
  Diagnosis d = PartialAtTheNoiseLevel();
  Conclude(&d);
  EXPECT_EQ(d.verdict, Verdict::kNotExplained);
  EXPECT_NE(d.verdict_text.find("lowers the probable error to 1.12 and "
                                "leaves the residuals at the noise level's "
                                "limit (1.51) or below, but past it an "
                                "effect outside the catalog outdid the "
                                "catalog's"),
            std::string::npos)
      << d.verdict_text;
  EXPECT_EQ(d.verdict_text.find("past the noise level's limit"),
            std::string::npos)
      << d.verdict_text;
  EXPECT_NE(d.verdict_text.find("explains more than any catalog effect "
                                "(BIC lower by 12.3)"),
            std::string::npos)
      << d.verdict_text;
}

// White residuals past the limit are the noise's size, and say so; a
// step that leaves structure says that instead.
TEST(Conclude, AStepPastTheNoiseLevelSaysWhatItLeaves) {
  Diagnosis white = PartialAtTheNoiseLevel();
  white.outside_catalog = CandidateFit();
  white.partial[0].after.at_noise_level = false;
  white.partial[0].after.noise_limit = 1.0;
  Conclude(&white);
  EXPECT_NE(white.verdict_text.find("leaves white residuals, past the noise "
                                    "level's limit (1)"),
            std::string::npos)
      << white.verdict_text;
  EXPECT_NE(white.verdict_text.find("sigma: auto"), std::string::npos)
      << white.verdict_text;

  Diagnosis structured = white;
  structured.partial[0].after.white = false;
  Conclude(&structured);
  EXPECT_NE(structured.verdict_text.find("leaves the residuals structured"),
            std::string::npos)
      << structured.verdict_text;
}

// The catalog effects a probe outdid are named with their BIC drops: the
// nearest catalog explanation (draw 128's cone with a bearing moment,
// outdone by a pressure drift 96.4 to 78.7).
TEST(Conclude, TheCatalogEffectsAProbeOutdidAreNamed) {
  Diagnosis d = PartialAtTheNoiseLevel();
  d.partial.clear();
  d.outside_catalog.bic_drop = 96.4;
  d.outdone_by_probe = {"bearing_moment"};
  CandidateFit outdone;
  outdone.effect = "bearing_moment";
  outdone.bic_drop = 78.7;
  outdone.rejected = "a dynamic pressure drifting ... explains it better";
  d.rejected = {outdone};
  Conclude(&d);
  EXPECT_EQ(d.verdict, Verdict::kNotExplained);
  EXPECT_NE(d.verdict_text.find("explains more than any catalog effect (BIC "
                                "lower by 96.4); outdone by it, not added: "
                                "bearing_moment (BIC lower by 78.7)"),
            std::string::npos)
      << d.verdict_text;
}

// A final fit of one run whose roll sweeps `span_deg` over 34 samples
// (its motion through them, for the residuals' description).
FitResult RollingFit(double span_deg) {
  FitResult fit;
  SegmentFit s;
  for (int i = 0; i < 34; ++i) {
    const double phi = span_deg * i / 33.0;
    s.data.Append(0.084 * i, phi, 8.0, 0.0);
    s.computed.insert(s.computed.end(), {phi, 8.0, 0.0});
  }
  fit.segments.push_back(s);
  return fit;
}

// A search that added nothing, its residuals white but past sigma, whose
// last round refused a trim moment, a roll reading error and a flow
// angularity for the held-out part (draw 136's 34-sample run over 109 deg
// of roll, a roll reading error at 1.5 times the noise).
Diagnosis UnconfirmedOverPartOfARevolution() {
  Diagnosis d;
  d.fits = {RollingFit(109.2)};
  d.final.probable_error = 1.48;
  d.final.noise_limit = 1.21;
  d.final.whiteness_limit = 0.53;
  d.final.white = true;
  const std::string held_out =
      std::string(kHeldOutRefusal) + " (log-likelihood gain -2.5, needs 4)";
  for (const auto& [effect, drop] : {std::pair{"trim_moment", 39.6},
                                     {"roll_interaction", 36.0},
                                     {"flow_angularity", 27.4}}) {
    CandidateFit k;
    k.effect = effect;
    k.bic_drop = drop;
    k.rejected = held_out;
    d.rejected.push_back(k);
  }
  return d;
}

TEST(Conclude, RollLockedEffectsUnconfirmedOverPartOfARevolutionAreNamed) {
  Diagnosis d = UnconfirmedOverPartOfARevolution();
  Conclude(&d);
  EXPECT_EQ(d.verdict, Verdict::kNotExplained);
  EXPECT_NE(d.verdict_text.find("each below the limit 0.53"), std::string::npos)
      << d.verdict_text;
  // The flow angularity is an offset, not roll-locked: not named.
  EXPECT_NE(d.verdict_text.find("roll-locked effects lower BIC (trim_moment "
                                "by 39.6, roll_interaction by 36.0) but do "
                                "not predict the held-out samples better "
                                "over this record's 109 deg of roll: a "
                                "record spanning a revolution of roll"),
            std::string::npos)
      << d.verdict_text;
}

TEST(Conclude, RollLockedEffectsAreNamedOnlyWhereTheRecordCannotTell) {
  Diagnosis separated = UnconfirmedOverPartOfARevolution();
  separated.fits = {RollingFit(400.0)};  // over a revolution
  Conclude(&separated);
  EXPECT_EQ(separated.verdict_text.find("roll-locked"), std::string::npos)
      << separated.verdict_text;

  // Weak in sample, or refused for another reason: not named.
  Diagnosis weak = UnconfirmedOverPartOfARevolution();
  weak.rejected[0].bic_drop = 9.0;
  weak.rejected[1].rejected = "it moves Cm_q by 5 of its standard errors";
  Conclude(&weak);
  EXPECT_EQ(weak.verdict_text.find("roll-locked"), std::string::npos)
      << weak.verdict_text;
}

}  // namespace
}  // namespace fit3dof
