// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The verdict's words (diagnosis_verdict.cc, Conclude) on diagnoses built
// by hand: what a search leaves in a Diagnosis, read back as the engineer
// reads it.

#include <string>

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

}  // namespace
}  // namespace fit3dof
