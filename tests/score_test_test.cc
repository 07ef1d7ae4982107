// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The score test (score_test.cc): every catalog candidate's statistic at
// a solution is the same whether the candidate is linearized whole or
// takes the solution's Jacobian of the free parameters and integrates only
// its own terms' columns (InformationAtSolution); and the drop in BIC a
// score predicts (ScoreBicDrop) is the drop Bic reads from the sum of
// squares the score predicts.

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "diagnose_internal.h"
#include "diagnose_search.h"
#include "fit3dof/diagnose.h"
#include "fit3dof/fit.h"
#include "fit3dof/parameters.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

// The short run with a tunnel damping a few times the noise, fitted with
// Cm_alpha and Cm_q free: every catalog effect scored at that solution.
// Those in the symmetric program take the solution's Jacobian; the body
// asymmetry and the product of inertia switch to the asymmetric program
// (another parameter table) and are linearized whole.
TEST(Score, TheSolutionsJacobianGivesEachCandidatesOwnStatistic) {
  const std::string dir = testing::ScratchDirectory("score_shared");
  Case c = testing::ShortRun(dir,
                             "  tunnel_Cm_thetadot: -3.0\n"
                             "  tunnel_Cn_psidot: -3.0\n",
                             1);
  c.parameters[FindParameter(c.model, "tunnel_Cm_thetadot")].value = 0.0;
  c.parameters[FindParameter(c.model, "tunnel_Cn_psidot")].value = 0.0;
  c.parameters[FindParameter(c.model, "Cm_alpha")] = {-0.2, true, false};
  c.parameters[FindParameter(c.model, "Cm_q")] = {-2.0, true, false};
  const FitResult nominal = Fit(c);
  ASSERT_TRUE(nominal.converged) << nominal.termination;
  std::vector<TimeHistory> data;
  for (const SegmentFit& f : nominal.segments) data.push_back(f.data);
  const Case at = CaseAtSolution(c, nominal);
  const InformationAtSolution information(at, data);
  ASSERT_TRUE(information.ok);

  int shared = 0, whole = 0;
  for (const Effect& e : EffectCatalog()) {
    Case candidate;
    std::vector<std::string> added;
    if (!CandidateCase(at, e, &candidate, &added)) continue;
    const CandidateScore alone = Score(candidate, added, e.id, data);
    const CandidateScore given =
        Score(candidate, added, e.id, data, &information);
    const bool shares = SharesInformation(candidate, added, data, information);
    (shares ? shared : whole) += 1;
    EXPECT_EQ(shares, candidate.model == at.model) << e.id;
    std::cout << e.id << ": " << alone.score << " / " << given.score
              << (shares ? " (shared)" : " (whole)") << "\n";
    EXPECT_NEAR(given.score, alone.score, 1e-6 * (1.0 + alone.score)) << e.id;
    EXPECT_EQ(given.dof, alone.dof) << e.id;
    EXPECT_NEAR(given.novelty, alone.novelty, 1e-6) << e.id;
  }
  EXPECT_GE(shared, 10);
  EXPECT_GE(whole, 1);
}

// A score is the drop of the sum of squares in units of its variance over
// the residuals' degrees of freedom; its BIC drop is the one Bic reads
// between the fit and a fit with that sum and the candidate's terms more.
// On a 3-s record (114 residuals, 8 free) read as the score less ln(n)
// per term it had fallen 3.6 short of the refit's (draw 147).
TEST(ScoreBicDrop, IsBicsDropAtTheSumTheScorePredicts) {
  FitResult at;
  at.points = 38;
  at.free_parameters = 8;
  at.sum_of_residuals = std::sqrt(129.7);
  Candidate k;
  k.effect = nullptr;
  k.score.dof = 2;
  for (double score : {0.5, 19.3, 80.0}) {
    k.score.score = score;
    const double rss = at.sum_of_residuals * at.sum_of_residuals;
    const double residual_dof = 3.0 * at.points - at.free_parameters;
    FitResult after = at;
    after.free_parameters += k.score.dof;
    after.sum_of_residuals = std::sqrt(rss - score * rss / residual_dof);
    EXPECT_NEAR(ScoreBicDrop(k, at), Bic(at) - Bic(after), 1e-9) << score;
    EXPECT_GT(ScoreBicDrop(k, at),
              score - k.score.dof * std::log(3.0 * at.points))
        << score;
  }
  // A score past the residuals' degrees of freedom is a finite, large drop.
  k.score.score = 500.0;
  EXPECT_TRUE(std::isfinite(ScoreBicDrop(k, at)));
  EXPECT_GT(ScoreBicDrop(k, at), 1000.0);
}

}  // namespace
}  // namespace fit3dof
