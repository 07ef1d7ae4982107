// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The score test (score_test.cc): every catalog candidate's statistic at
// a solution is the same whether the candidate is linearized whole or
// takes the solution's Jacobian of the free parameters and integrates only
// its own terms' columns (InformationAtSolution).

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "diagnose_internal.h"
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

}  // namespace
}  // namespace fit3dof
