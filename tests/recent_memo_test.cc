// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The memo of recent results (recent_memo.h): an equal key returns the
// value added with it, the oldest entries leave first, and the counts say
// how often it was asked and answered.

#include "recent_memo.h"

#include <string>
#include <vector>

#include "gtest/gtest.h"

namespace fit3dof {
namespace {

TEST(RecentMemo, ReturnsTheValueOfAnEqualKey) {
  RecentMemo<std::string, int> memo(4);
  EXPECT_FALSE(memo.Find("a").has_value());
  memo.Add("a", 1);
  memo.Add("b", 2);
  ASSERT_TRUE(memo.Find("a").has_value());
  EXPECT_EQ(*memo.Find("a"), 1);
  EXPECT_EQ(*memo.Find("b"), 2);
  EXPECT_FALSE(memo.Find("c").has_value());
  const MemoCounts counts = memo.Counts();
  EXPECT_EQ(counts.calls, 5);
  EXPECT_EQ(counts.hits, 3);
}

TEST(RecentMemo, TheOldestLeaveFirst) {
  RecentMemo<int, int> memo(2);
  memo.Add(1, 10);
  memo.Add(2, 20);
  memo.Add(3, 30);
  EXPECT_FALSE(memo.Find(1).has_value());
  EXPECT_EQ(*memo.Find(2), 20);
  EXPECT_EQ(*memo.Find(3), 30);
}

TEST(RecentMemo, SamplesAndCasesCompareByValue) {
  TimeHistory a;
  a.Append(0.0, 1.0, 2.0, 3.0);
  TimeHistory b = a;
  EXPECT_TRUE(SameSamples({a}, {b}));
  b.psi[0] = 3.5;
  EXPECT_FALSE(SameSamples({a}, {b}));
  EXPECT_FALSE(SameSamples({a}, {a, a}));
  Case c;
  Case d = c;
  EXPECT_TRUE(SameCase(c, d));
  d.source = "elsewhere.yaml";
  EXPECT_FALSE(SameCase(c, d));
}

}  // namespace
}  // namespace fit3dof
