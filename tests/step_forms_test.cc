// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A step's effect in the form a model holds it in (Effect::other_form):
// FinalValues (src/diagnose.cc), each step's values as the final model has
// them; WithoutStep (src/diagnose_ties.cc), a model without the step.

#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "diagnose_internal.h"
#include "diagnose_search.h"
#include "fit3dof/diagnose.h"
#include "gtest/gtest.h"

namespace fit3dof {
namespace {

// An estimate named `name`, free or held.
ParameterEstimate Estimate(const std::string& name, double value, bool free) {
  ParameterEstimate e;
  e.name = name;
  e.value = value;
  e.free = free;
  return e;
}

// A diagnosis whose one step added the calibration nonlinearity, recorded
// by `step_terms`, and whose final fit holds `fitted` (name, value, free).
Diagnosis WithCalibrationStep(
    const std::vector<std::string>& step_terms,
    const std::vector<std::tuple<std::string, double, bool>>& fitted) {
  Diagnosis d;
  FitResult fit;
  fit.model = ModelKind::kSymmetric;
  fit.parameters.push_back(Estimate("Cm_alpha", -0.14, true));
  for (const auto& [name, value, free] : fitted) {
    fit.parameters.push_back(Estimate(name, value, free));
  }
  d.fits.push_back(fit);
  d.final_fit = 0;
  DiagnosisStep step;
  step.effect = "calibration_nonlinearity";
  for (const std::string& name : step_terms) {
    step.step_parameters.push_back(Estimate(name, 0.0, true));
  }
  d.steps.push_back(step);
  return d;
}

std::vector<std::string> Names(const std::vector<ParameterEstimate>& values) {
  std::vector<std::string> names;
  for (const ParameterEstimate& e : values) names.push_back(e.name);
  return names;
}

// A later round took the step back to the cube (its step_parameters), but
// the final model, the one before a tie, holds the signed square: the
// step's values are the square's, not the cube's held zeros.
TEST(FinalValues, ReportsTheFormTheFinalModelHolds) {
  Diagnosis d = WithCalibrationStep({"theta_cal3", "psi_cal3"},
                                    {{"theta_cal3", 0.0, false},
                                     {"psi_cal3", 0.0, false},
                                     {"theta_cal2", -0.038, true},
                                     {"psi_cal2", 0.094, true}});
  FinalValues(&d);
  EXPECT_EQ(Names(d.steps[0].parameters),
            (std::vector<std::string>{"theta_cal2", "psi_cal2"}));
  EXPECT_DOUBLE_EQ(d.steps[0].parameters[0].value, -0.038);
}

// The other way: a step taken as the signed square, a final model in the
// cube.
TEST(FinalValues, ReportsTheOwnFormWhereTheFinalModelWentBack) {
  Diagnosis d = WithCalibrationStep({"theta_cal2", "psi_cal2"},
                                    {{"theta_cal3", -0.02, true},
                                     {"psi_cal3", 0.02, true},
                                     {"theta_cal2", 0.0, false},
                                     {"psi_cal2", 0.0, false}});
  FinalValues(&d);
  EXPECT_EQ(Names(d.steps[0].parameters),
            (std::vector<std::string>{"theta_cal3", "psi_cal3"}));
  EXPECT_DOUBLE_EQ(d.steps[0].parameters[1].value, 0.02);
  EXPECT_EQ(Names(d.final_parameters).size(), 5u);
}

// A case of the symmetric model with the calibration's terms named in
// `free` free (cal_range held at 8 deg, as the search holds it).
Case WithFreeTerms(const std::vector<std::string>& free) {
  Case c;
  c.parameters.assign(NumParameters(ModelKind::kSymmetric), {});
  for (const std::string& name : free) {
    c.parameters[FindParameter(c.model, name)].free = true;
    c.parameters[FindParameter(c.model, name)].value = 0.05;
  }
  c.parameters[FindParameter(c.model, "cal_range")].value = 8.0;
  return c;
}

bool IsFree(const Case& c, const std::string& name) {
  return c.parameters[FindParameter(c.model, name)].free;
}

// A step the search later took back to the cube (its step_parameters),
// taken out of a model that still holds the signed square: the square's
// terms are held at zero too. By the step's terms alone the square had
// stayed free, and "without the calibration" still held it.
TEST(WithoutStep, TakesOutTheFormTheModelHolds) {
  const Case square = WithFreeTerms({"theta_cal2", "psi_cal2"});
  DiagnosisStep step;
  step.effect = "calibration_nonlinearity";
  for (const char* name : {"theta_cal3", "psi_cal3"}) {
    step.step_parameters.push_back(Estimate(name, 0.0, true));
  }
  const Case without = WithoutStep(square, step);
  for (const char* name :
       {"theta_cal2", "psi_cal2", "theta_cal3", "psi_cal3"}) {
    EXPECT_FALSE(IsFree(without, name)) << name;
    EXPECT_EQ(without.parameters[FindParameter(without.model, name)].value, 0.0)
        << name;
  }
  // The range is no term of either form's: it keeps its value.
  EXPECT_EQ(without.parameters[FindParameter(without.model, "cal_range")].value,
            8.0);
}

}  // namespace
}  // namespace fit3dof
