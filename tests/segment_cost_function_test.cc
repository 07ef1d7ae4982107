// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/segment_cost_function.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <vector>

#include "fit3dof/config.h"
#include "fit3dof/parameters.h"
#include "fit3dof/simulator.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

struct Block {
  std::unique_ptr<SegmentCostFunction> cost;
  std::shared_ptr<const MotionModel> motion;
  std::vector<std::vector<double>> blocks;
};

// A segment of the Table 6 motion (or an asymmetric motion) with the given
// positions free: `shared` in block 0, `own` initial conditions in block 1.
Block Make(ModelKind model,
           const std::vector<int>& shared,
           const std::vector<int>& own,
           std::vector<double> scale = {},
           Incidence incidence = Incidence::kVelocityRatio,
           const std::vector<ParameterTie>& ties = {},
           double interval = 0.05) {
  Case c = LoadConfig(testing::SourcePath(
      model == ModelKind::kSymmetric ? "configs/report/table6_motion.yaml"
                                     : "configs/report/check_case_1.yaml"));
  c.solver.step = 0.01;
  c.incidence = incidence;
  std::vector<double> values = c.Values();
  if (model == ModelKind::kAsymmetric) {
    // Every aerodynamic term a little non-zero.
    for (int i = 0; i < 57; ++i) {
      if (values[i] == 0.0) values[i] = 0.01 * ((i * 5) % 7 - 3);
    }
    values[59] = 0.001;
  }
  ApplyTies(ties, values.data());
  std::vector<double> times;
  const int samples = static_cast<int>(std::lround(3.0 / interval));
  for (int i = 0; i < samples; ++i) times.push_back(interval * i);
  TimeHistory data = SimulateAt(c, values, times);
  for (int i = 0; i < data.size(); ++i) data.theta[i] += 0.01 * std::sin(i);
  std::vector<int> free = shared;
  free.insert(free.end(), own.begin(), own.end());
  std::vector<bool> flags(values.size(), false);
  for (int i : free) flags[i] = true;
  for (const ParameterTie& tie : ties) flags[tie.image] = flags[tie.source];
  if (scale.empty()) scale.assign(free.size(), 1.0);
  auto motion = std::make_shared<const MotionModel>(
      c.Spec(), ActiveParameters(values, flags));
  Block s;
  s.motion = motion;
  s.cost =
      std::make_unique<SegmentCostFunction>(motion,
                                            values,
                                            free,
                                            static_cast<int>(shared.size()),
                                            scale,
                                            data,
                                            ChannelValues{1.0, 0.01, 0.02});
  s.cost->set_ties(ties);
  std::vector<double> a, b;
  for (size_t j = 0; j < shared.size(); ++j)
    a.push_back(values[shared[j]] / scale[j]);
  for (size_t j = 0; j < own.size(); ++j) {
    b.push_back(values[own[j]] / scale[shared.size() + j]);
  }
  if (!a.empty()) s.blocks.push_back(a);
  if (!b.empty()) s.blocks.push_back(b);
  return s;
}

// The cost function's Jacobian against central differences of its own
// residuals, one column at a time with a step that moves the residuals by
// about 1e-3 (well above the roundoff in roll, hundreds of degrees, and
// well inside the linear range).
void CheckGradient(Block& s) {
  const int m = s.cost->num_residuals();
  std::vector<double*> blocks;
  std::vector<std::vector<double>> jacobian_storage;
  std::vector<double*> jacobians;
  for (auto& b : s.blocks) {
    blocks.push_back(b.data());
    jacobian_storage.emplace_back(m * b.size());
    jacobians.push_back(jacobian_storage.back().data());
  }
  std::vector<double> residuals(m);
  ASSERT_TRUE(
      s.cost->Evaluate(blocks.data(), residuals.data(), jacobians.data()));
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    const int size = static_cast<int>(s.blocks[b].size());
    for (int col = 0; col < size; ++col) {
      double scale = 0.0;
      for (int r = 0; r < m; ++r)
        scale = std::max(scale, std::abs(jacobians[b][r * size + col]));
      ASSERT_GT(scale, 0.0) << "block " << b << " column " << col;
      const double h = 1e-3 / scale;
      std::vector<double> plus(m), minus(m);
      const double saved = s.blocks[b][col];
      s.blocks[b][col] = saved + h;
      ASSERT_TRUE(s.cost->Evaluate(blocks.data(), plus.data(), nullptr));
      s.blocks[b][col] = saved - h;
      ASSERT_TRUE(s.cost->Evaluate(blocks.data(), minus.data(), nullptr));
      s.blocks[b][col] = saved;
      for (int r = 0; r < m; ++r) {
        const double numeric = (plus[r] - minus[r]) / (2.0 * h);
        EXPECT_NEAR(jacobians[b][r * size + col], numeric, 2e-5 * scale)
            << "block " << b << " column " << col << " residual " << r;
      }
    }
  }
}

TEST(SegmentCostFunction, JacobianMatchesNumericDifferencesAtEveryWidth) {
  {  // 3 free: Jet<4>, one block.
    Block s = Make(ModelKind::kSymmetric, {0, 1, 4}, {});
    CheckGradient(s);
  }
  {  // 10 free: Jet<12>, shared and own blocks, scaled coordinates.
    Block s = Make(ModelKind::kSymmetric,
                   {0, 1, 4, 5},
                   {24, 25, 26, 27, 28, 29},
                   {0.01, 0.1, 1.0, 10.0, 0.5, 2.0, 0.5, 1.0, 0.5, 1.0});
    CheckGradient(s);
  }
  {  // only initial conditions free: a single "own" block.
    Block s = Make(ModelKind::kSymmetric, {}, {26, 29});
    CheckGradient(s);
  }
  {  // the dynamic pressure's drift: every moment's time-varying factor.
    const int drift = Layout(ModelKind::kSymmetric).q_drift;
    Block s = Make(ModelKind::kSymmetric, {0, 1, drift}, {});
    s.blocks[0][2] = 0.02;
    for (auto method : {SegmentCostFunction::JacobianMethod::kJetLanes,
                        SegmentCostFunction::JacobianMethod::kSensitivities}) {
      s.cost->set_jacobian_method(method);
      CheckGradient(s);
    }
  }
}

// Evaluates s's residuals and Jacobian (one vector per block) by `method`.
void EvaluateBy(Block& s,
                SegmentCostFunction::JacobianMethod method,
                std::vector<double>* residuals,
                std::vector<std::vector<double>>* jacobian) {
  s.cost->set_jacobian_method(method);
  std::vector<const double*> blocks;
  std::vector<double*> jacobians;
  residuals->assign(s.cost->num_residuals(), 0.0);
  jacobian->clear();
  for (auto& b : s.blocks) {
    jacobian->emplace_back(s.cost->num_residuals() * b.size(), 0.0);
  }
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    blocks.push_back(s.blocks[b].data());
    jacobians.push_back((*jacobian)[b].data());
  }
  ASSERT_TRUE(
      s.cost->Evaluate(blocks.data(), residuals->data(), jacobians.data()));
}

// The forward sensitivities give the Jet lanes' residuals exactly and their
// derivatives to rounding, for every kind of parameter: coefficients of
// both programs, tunnel terms, the product of inertia, the measurement
// model (offsets, roll interaction, the readings' lag and gain), the dynamic
// pressure's drift, the flow's yaw-plane stiffness and initial conditions, with
// both incidence definitions.
TEST(SegmentCostFunction, SensitivitiesEqualJetLanes) {
  std::vector<int> symmetric;
  for (int i = 0; i < 23; ++i) symmetric.push_back(i);   // + theta_T
  for (int i = 30; i < 34; ++i) symmetric.push_back(i);  // roll interaction
  symmetric.push_back(Layout(ModelKind::kSymmetric).q_drift);
  symmetric.push_back(Layout(ModelKind::kSymmetric).flow_yaw_stiffness);
  symmetric.push_back(Layout(ModelKind::kSymmetric).lag);
  symmetric.push_back(Layout(ModelKind::kSymmetric).lag + 1);
  symmetric.push_back(Layout(ModelKind::kSymmetric).gain);
  std::vector<int> asymmetric;
  for (int i = 0; i < 65; ++i) asymmetric.push_back(i);
  for (int i = 72; i < 76; ++i) asymmetric.push_back(i);
  asymmetric.push_back(Layout(ModelKind::kAsymmetric).q_drift);
  asymmetric.push_back(Layout(ModelKind::kAsymmetric).flow_yaw_stiffness);
  asymmetric.push_back(Layout(ModelKind::kAsymmetric).lag);
  asymmetric.push_back(Layout(ModelKind::kAsymmetric).lag + 1);
  asymmetric.push_back(Layout(ModelKind::kAsymmetric).gain);
  const std::vector<int> symmetric_initial = {24, 25, 26, 27, 28, 29};
  const std::vector<int> asymmetric_initial = {66, 67, 68, 69, 70, 71};
  std::vector<Block> blocks;
  blocks.push_back(Make(ModelKind::kSymmetric, symmetric, symmetric_initial));
  blocks.push_back(Make(ModelKind::kSymmetric,
                        symmetric,
                        symmetric_initial,
                        {},
                        Incidence::kAngleOfAttack));
  blocks.push_back(
      Make(ModelKind::kAsymmetric, asymmetric, asymmetric_initial));
  blocks.push_back(Make(ModelKind::kAsymmetric,
                        asymmetric,
                        asymmetric_initial,
                        {},
                        Incidence::kAngleOfAttack));
  blocks.push_back(Make(ModelKind::kSymmetric,
                        {0, 1, 4, 5},
                        symmetric_initial,
                        {0.01, 0.1, 1.0, 10.0, 0.5, 2.0, 0.5, 1.0, 0.5, 1.0}));
  for (size_t t = 0; t < blocks.size(); ++t) {
    Block& s = blocks[t];
    std::vector<double> r_jet, r_sens;
    std::vector<std::vector<double>> j_jet, j_sens;
    EvaluateBy(
        s, SegmentCostFunction::JacobianMethod::kJetLanes, &r_jet, &j_jet);
    EvaluateBy(s,
               SegmentCostFunction::JacobianMethod::kSensitivities,
               &r_sens,
               &j_sens);
    ASSERT_EQ(r_jet, r_sens) << "case " << t;
    for (size_t b = 0; b < j_jet.size(); ++b) {
      const int size = static_cast<int>(s.blocks[b].size());
      const int rows = s.cost->num_residuals();
      for (int col = 0; col < size; ++col) {
        double scale = 0.0;
        for (int r = 0; r < rows; ++r) {
          scale = std::max(scale, std::abs(j_jet[b][r * size + col]));
        }
        for (int r = 0; r < rows; ++r) {
          ASSERT_NEAR(j_sens[b][r * size + col],
                      j_jet[b][r * size + col],
                      1e-11 * scale)
              << "case " << t << " block " << b << " column " << col
              << " residual " << r;
        }
      }
    }
  }
}

// The asymmetric program with the symmetric relations tied
// (model_conversion.h): each image follows its source, whose Jacobian
// column then carries the image's too, alike by Jet lanes and by
// sensitivities and equal to differences of the residuals.
TEST(SegmentCostFunction, TiedImagesFollowTheirSources) {
  const ModelKind a = ModelKind::kAsymmetric;
  auto at = [&](const char* name) { return FindParameter(a, name); };
  const std::vector<ParameterTie> ties = {
      {at("Cn_beta"), at("Cm_alpha"), -1.0},
      {at("Cn_r"), at("Cm_q"), 1.0},
      {at("Cn_p_alpha"), at("Cm_p_beta"), 1.0},
      {at("psi_cos_phi"), at("theta_cos_phi"), 0.5},
      {at("Cn_beta3"), at("Cm_alpha3"), -1.0}};  // a frozen source
  const std::vector<int> shared = {
      at("Cm_alpha"), at("Cm_q"), at("Cm_p_beta"), at("theta_cos_phi")};
  const std::vector<int> initial = {66, 67, 68, 69, 70, 71};
  for (auto method : {SegmentCostFunction::JacobianMethod::kJetLanes,
                      SegmentCostFunction::JacobianMethod::kSensitivities}) {
    Block s = Make(a, shared, initial, {}, Incidence::kVelocityRatio, ties);
    s.cost->set_jacobian_method(method);
    CheckGradient(s);
    // Moving a source moves its image: the full vector follows the tie.
    s.blocks[0][0] += 0.01;
    const double* p[2] = {s.blocks[0].data(), s.blocks[1].data()};
    const std::vector<double> full = s.cost->FullValues(p);
    EXPECT_EQ(full[at("Cn_beta")], -full[at("Cm_alpha")]);
    EXPECT_EQ(full[at("psi_cos_phi")], 0.5 * full[at("theta_cos_phi")]);
    EXPECT_EQ(full[at("Cn_beta3")], -full[at("Cm_alpha3")]);
  }
  Block s = Make(a, shared, initial, {}, Incidence::kVelocityRatio, ties);
  std::vector<double> r_jet, r_sens;
  std::vector<std::vector<double>> j_jet, j_sens;
  EvaluateBy(s, SegmentCostFunction::JacobianMethod::kJetLanes, &r_jet, &j_jet);
  EvaluateBy(
      s, SegmentCostFunction::JacobianMethod::kSensitivities, &r_sens, &j_sens);
  ASSERT_EQ(r_jet, r_sens);
  for (size_t b = 0; b < j_jet.size(); ++b) {
    for (size_t i = 0; i < j_jet[b].size(); ++i) {
      ASSERT_NEAR(
          j_sens[b][i], j_jet[b][i], 1e-9 * (1.0 + std::abs(j_jet[b][i])));
    }
  }
}

TEST(SegmentCostFunction, MoreThan32FreeTakesSeveralPasses) {
  std::vector<int> shared;
  for (int i = 0; i < 57; ++i) shared.push_back(i);
  shared.push_back(59);
  Block s = Make(ModelKind::kAsymmetric, shared, {66, 67, 68, 69, 70, 71});
  ASSERT_EQ(s.cost->num_free(), 64);  // 2 passes of 32
  CheckGradient(s);
}

// Frozen parameters reach the equations as constants: the residuals do not
// depend on which parameters are free.
TEST(SegmentCostFunction, ResidualsDoNotDependOnWhatIsFree) {
  Block a = Make(ModelKind::kSymmetric, {0}, {});
  Block b = Make(ModelKind::kSymmetric, {0, 1, 4, 5}, {26});
  std::vector<double> ra(a.cost->num_residuals()), rb(b.cost->num_residuals());
  const double* pa[1] = {a.blocks[0].data()};
  const double* pb[2] = {b.blocks[0].data(), b.blocks[1].data()};
  ASSERT_TRUE(a.cost->Evaluate(pa, ra.data(), nullptr));
  ASSERT_TRUE(b.cost->Evaluate(pb, rb.data(), nullptr));
  for (size_t i = 0; i < ra.size(); ++i) EXPECT_NEAR(ra[i], rb[i], 1e-12);
}

// Roll is compared modulo 360 deg.
TEST(SegmentCostFunction, RollResidualIsTakenModulo360) {
  Block s = Make(ModelKind::kSymmetric, {0}, {});
  std::vector<double> r(s.cost->num_residuals());
  const double* p[1] = {s.blocks[0].data()};
  ASSERT_TRUE(s.cost->Evaluate(p, r.data(), nullptr));
  for (int i = 0; i < s.cost->num_samples(); ++i) {
    EXPECT_LT(std::abs(r[3 * i]), 1e-6);  // sigma_phi = 1: phi matches
  }
}

// A parameter set whose motion blows up makes the evaluation fail cleanly
// (false, no NaN handed to Ceres), with and without a Jacobian.
// Jacobians from the motion at a coarser step (set_jacobian_step): the
// residuals are the model's to the bit and the derivatives near the
// model's (4x the step: 4e-5 of a column at worst on Table 6's motion), by
// Jet lanes and by sensitivities; a step no coarser than the model's gives
// the model's Jacobian to the bit.
TEST(SegmentCostFunction, ACoarserJacobianStepKeepsTheResiduals) {
  const std::vector<int> initial = {24, 25, 26, 27, 28, 29};
  for (const auto method :
       {SegmentCostFunction::JacobianMethod::kJetLanes,
        SegmentCostFunction::JacobianMethod::kSensitivities}) {
    Block s = Make(ModelKind::kSymmetric, {0, 1, 4, 5}, initial);
    std::vector<double> r_model, r_coarse, r_same;
    std::vector<std::vector<double>> j_model, j_coarse, j_same;
    EvaluateBy(s, method, &r_model, &j_model);
    s.cost->set_jacobian_step(4 * 0.01);
    EvaluateBy(s, method, &r_coarse, &j_coarse);
    s.cost->set_jacobian_step(0.01);
    EvaluateBy(s, method, &r_same, &j_same);
    EXPECT_EQ(r_coarse, r_model);
    EXPECT_EQ(r_same, r_model);
    EXPECT_EQ(j_same, j_model);
    double worst = 0.0;
    for (size_t b = 0; b < j_model.size(); ++b) {
      const int size = static_cast<int>(s.blocks[b].size());
      for (int col = 0; col < size; ++col) {
        double difference = 0.0, norm = 0.0;
        for (int r = 0; r < s.cost->num_residuals(); ++r) {
          const double e = j_model[b][r * size + col];
          difference += std::pow(j_coarse[b][r * size + col] - e, 2);
          norm += e * e;
        }
        worst = std::max(worst, std::sqrt(difference / norm));
      }
    }
    std::cout << "coarser Jacobian: worst column off by " << worst << "\n";
    EXPECT_GT(worst, 0.0);  // the coarser motion is used
    EXPECT_LT(worst, 1e-3);
  }
}

// Where the coarser motion blows up (samples 0.75 s apart: RK4 at that
// step is unstable on this motion, spinning at 11 rad/s), the Jacobian is
// the model's.
TEST(SegmentCostFunction, ACoarserMotionThatBlowsUpGivesTheModelsJacobian) {
  Block s = Make(ModelKind::kSymmetric,
                 {0, 1},
                 {},
                 {},
                 Incidence::kVelocityRatio,
                 {},
                 0.75);
  const double* p[1] = {s.blocks[0].data()};
  const std::vector<double> full = s.cost->FullValues(p);
  const TimeHistory& data = s.cost->data();
  std::vector<double> angles(3 * data.size());
  ASSERT_FALSE(s.motion->WithMaxStep(0.75)->Evaluate(
      full.data(), data.t.data(), data.size(), angles.data(), nullptr));
  std::vector<double> r_model, r_coarse;
  std::vector<std::vector<double>> j_model, j_coarse;
  EvaluateBy(
      s, SegmentCostFunction::JacobianMethod::kJetLanes, &r_model, &j_model);
  s.cost->set_jacobian_step(0.75);
  EvaluateBy(
      s, SegmentCostFunction::JacobianMethod::kJetLanes, &r_coarse, &j_coarse);
  EXPECT_EQ(r_coarse, r_model);
  EXPECT_EQ(j_coarse, j_model);
}

// The Jacobian a solve will not use (set_remember_residuals,
// skip_next_jacobian; stage_solver.cc): at the point of the last
// residual-only evaluation, the next evaluation with Jacobians returns
// those residuals and zero Jacobians without integrating; anywhere else,
// or a second time, it evaluates in full.
TEST(SegmentCostFunction, ASkippedJacobianReturnsTheRememberedResiduals) {
  const std::vector<int> shared = {
      FindParameter(ModelKind::kSymmetric, "Cm_alpha"),
      FindParameter(ModelKind::kSymmetric, "Cm_q")};
  Block s = Make(ModelKind::kSymmetric, shared, {});
  const int m = s.cost->num_residuals();
  double* blocks[] = {s.blocks[0].data()};
  std::vector<double> trial(m), residuals(m), jacobian(2 * m);
  double* jacobians[] = {jacobian.data()};
  const auto largest = [&] {
    double d = 0.0;
    for (double j : jacobian) d = std::max(d, std::abs(j));
    return d;
  };
  s.cost->set_remember_residuals(true);
  EXPECT_TRUE(std::isnan(s.cost->remembered_cost()));
  ASSERT_TRUE(s.cost->Evaluate(blocks, trial.data(), nullptr));
  double cost = 0.0;
  for (double r : trial) cost += 0.5 * r * r;
  EXPECT_NEAR(s.cost->remembered_cost(), cost, 1e-12 * cost);

  s.cost->skip_next_jacobian();
  ASSERT_TRUE(s.cost->Evaluate(blocks, residuals.data(), jacobians));
  EXPECT_EQ(residuals, trial);
  EXPECT_EQ(largest(), 0.0);
  EXPECT_EQ(s.cost->jacobian_evaluations(), 0);

  // Asked once: the next evaluation integrates it.
  ASSERT_TRUE(s.cost->Evaluate(blocks, residuals.data(), jacobians));
  EXPECT_EQ(residuals, trial);
  EXPECT_GT(largest(), 0.0);
  EXPECT_EQ(s.cost->jacobian_evaluations(), 1);

  // Elsewhere than the remembered point: in full.
  s.cost->skip_next_jacobian();
  s.blocks[0][0] *= 1.01;
  ASSERT_TRUE(s.cost->Evaluate(blocks, residuals.data(), jacobians));
  EXPECT_NE(residuals, trial);
  EXPECT_GT(largest(), 0.0);
  EXPECT_EQ(s.cost->jacobian_evaluations(), 2);
}

// With Jacobians from a coarser motion, the residuals of an evaluation
// with Jacobians are the model's: at the point of the last residual-only
// evaluation (a solve's accepted step) the remembered ones, the same to the
// bit; after the ties change, those of the tied motion, never the stale
// ones.
TEST(SegmentCostFunction, AJacobianAtTheRememberedPointKeepsItsResiduals) {
  const int cm_alpha = FindParameter(ModelKind::kSymmetric, "Cm_alpha");
  Block s = Make(ModelKind::kSymmetric,
                 {cm_alpha, FindParameter(ModelKind::kSymmetric, "Cm_q")},
                 {});
  const int m = s.cost->num_residuals();
  double* blocks[] = {s.blocks[0].data()};
  std::vector<double> trial(m), residuals(m), jacobian(2 * m);
  double* jacobians[] = {jacobian.data()};
  s.cost->set_jacobian_step(4 * 0.01);
  s.cost->set_remember_residuals(true);
  ASSERT_TRUE(s.cost->Evaluate(blocks, trial.data(), nullptr));
  ASSERT_TRUE(s.cost->Evaluate(blocks, residuals.data(), jacobians));
  EXPECT_EQ(residuals, trial);
  EXPECT_EQ(s.cost->jacobian_evaluations(), 1);

  s.cost->set_ties({{FindParameter(ModelKind::kSymmetric, "Cm_alpha_delta2"),
                     cm_alpha,
                     1.0}});
  std::vector<double> tied(m);
  ASSERT_TRUE(s.cost->Evaluate(blocks, residuals.data(), jacobians));
  s.cost->set_remember_residuals(false);
  ASSERT_TRUE(s.cost->Evaluate(blocks, tied.data(), nullptr));
  EXPECT_NE(tied, trial);
  EXPECT_EQ(residuals, tied);
}

TEST(SegmentCostFunction, BlowUpReturnsFalse) {
  Block s = Make(ModelKind::kSymmetric, {0}, {});
  std::vector<double> unstable = {+40.0};
  std::vector<double> r(s.cost->num_residuals()), j(s.cost->num_residuals());
  const double* p[1] = {unstable.data()};
  double* jacobians[1] = {j.data()};
  EXPECT_FALSE(s.cost->Evaluate(p, r.data(), nullptr));
  EXPECT_FALSE(s.cost->Evaluate(p, r.data(), jacobians));
}

}  // namespace
}  // namespace fit3dof
