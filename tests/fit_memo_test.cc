// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The memo of fits diagnose repeats (fit_memo.h): an equal case fitted to
// equal data is the earlier fit, exactly; any difference in the case or
// the data is a new fit; the oldest fits leave first.

#include "fit_memo.h"

#include <cmath>
#include <string>
#include <vector>

#include "fit3dof/parameters.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

// A config fitting Cm_alpha and Cm_q to the short run of
// tools/diagnose_suite (testing::ShortRun, noise seed 7).
Case ShortRunFit(const std::string& dir) {
  Case c = testing::ShortRun(dir, "", 7);
  c.parameters[FindParameter(c.model, "Cm_alpha")] = {-0.2, true, false};
  c.parameters[FindParameter(c.model, "Cm_q")] = {-2.0, true, false};
  return c;
}

std::vector<TimeHistory> Data(const FitResult& fit) {
  std::vector<TimeHistory> data;
  for (const SegmentFit& s : fit.segments) data.push_back(s.data);
  return data;
}

void ExpectSameFit(const FitResult& a, const FitResult& b) {
  EXPECT_EQ(a.sum_of_residuals, b.sum_of_residuals);
  ASSERT_EQ(a.parameters.size(), b.parameters.size());
  for (size_t i = 0; i < a.parameters.size(); ++i) {
    EXPECT_EQ(a.parameters[i].value, b.parameters[i].value);
    const double sa = a.parameters[i].standard_error;  // NaN when frozen
    const double sb = b.parameters[i].standard_error;
    EXPECT_TRUE(sa == sb || (std::isnan(sa) && std::isnan(sb))) << i;
  }
}

TEST(FitMemo, AnEqualCaseToEqualDataIsTheEarlierFit) {
  const Case c = ShortRunFit(testing::ScratchDirectory("fit_memo_equal"));
  const std::vector<TimeHistory> data = Data(Fit(c));
  const FitMemoCounts before = GetFitMemoCounts();
  const FitResult first = MemoizedFitSamples(c, data);
  const FitResult second = MemoizedFitSamples(Case(c), data);
  const FitMemoCounts after = GetFitMemoCounts();
  EXPECT_EQ(after.calls - before.calls, 2);
  EXPECT_EQ(after.hits - before.hits, 1);
  ExpectSameFit(first, second);
  // And the memo's fit is the fit itself.
  ExpectSameFit(first, FitSamples(c, data));
}

TEST(FitMemo, AnyDifferenceIsANewFit) {
  const Case c = ShortRunFit(testing::ScratchDirectory("fit_memo_differs"));
  const std::vector<TimeHistory> data = Data(Fit(c));
  const FitResult base = MemoizedFitSamples(c, data);

  Case frozen = c;  // a frozen term's value
  frozen.parameters[FindParameter(c.model, "Cm_alpha_delta2")].value = -1.0;
  std::vector<TimeHistory> moved = data;  // one reading
  moved[0].theta[10] += 0.01;
  Case elsewhere = c;  // the file its warnings name
  elsewhere.source = "elsewhere.yaml";

  const FitMemoCounts before = GetFitMemoCounts();
  const FitResult other_case = MemoizedFitSamples(frozen, data);
  const FitResult other_data = MemoizedFitSamples(c, moved);
  MemoizedFitSamples(elsewhere, data);
  const FitMemoCounts after = GetFitMemoCounts();
  EXPECT_EQ(after.calls - before.calls, 3);
  EXPECT_EQ(after.hits - before.hits, 0);
  EXPECT_NE(other_case.sum_of_residuals, base.sum_of_residuals);
  EXPECT_NE(other_data.sum_of_residuals, base.sum_of_residuals);
}

TEST(FitMemo, TheOldestFitLeavesFirst) {
  Case c = ShortRunFit(testing::ScratchDirectory("fit_memo_capacity"));
  std::vector<TimeHistory> data = Data(Fit(c));
  for (TimeHistory& h : data) {  // 12 samples: cheap fits
    h.t.resize(12), h.phi.resize(12), h.theta.resize(12), h.psi.resize(12);
  }
  c.solver.continuation = false;
  c.solver.multi_start = false;
  const int cm_q = FindParameter(c.model, "Cm_q");
  auto fit_from = [&](int k) {
    Case start = c;
    start.parameters[cm_q].value = -2.0 - 0.01 * k;
    MemoizedFitSamples(start, data);
  };
  for (int k = 0; k <= kFitMemoCapacity; ++k) fit_from(k);
  const FitMemoCounts before = GetFitMemoCounts();
  fit_from(kFitMemoCapacity);  // the newest: kept
  fit_from(1);                 // kept
  fit_from(0);                 // the oldest: gone
  const FitMemoCounts after = GetFitMemoCounts();
  EXPECT_EQ(after.hits - before.hits, 2);
}

}  // namespace
}  // namespace fit3dof
