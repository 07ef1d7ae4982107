// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/data_selection.h"

#include "gtest/gtest.h"

namespace fit3dof {
namespace {

TimeHistory Record(int n) {
  TimeHistory h;
  for (int i = 0; i < n; ++i) h.Append(0.1 * i, i, 2.0 * i, 3.0 * i);
  return h;
}

TEST(DataSelection, WholeRecordByDefault) {
  const TimeHistory s = SelectSamples(Record(11), DataSelection{});
  EXPECT_EQ(s.size(), 11);
}

TEST(DataSelection, StartFractionEvery) {
  DataSelection selection;
  selection.start = 3;       // t = 0.2
  selection.every = 2;       // 0.2, 0.4, 0.6, ...
  selection.fraction = 0.5;  // up to 0.2 + 0.5 * (1.0 - 0.2) = 0.6
  const TimeHistory s = SelectSamples(Record(11), selection);
  ASSERT_EQ(s.size(), 3);
  EXPECT_DOUBLE_EQ(s.t[0], 0.2);
  EXPECT_DOUBLE_EQ(s.t[2], 0.6);
  EXPECT_DOUBLE_EQ(s.theta[1], 8.0);
}

TEST(DataSelection, TimeWindowComesFirst) {
  DataSelection selection;
  selection.t_start = 0.45;
  selection.t_end = 0.85;
  selection.start = 2;
  const TimeHistory s = SelectSamples(Record(11), selection);
  ASSERT_EQ(s.size(), 3);
  EXPECT_NEAR(s.t[0], 0.6, 1e-12);
  EXPECT_NEAR(s.t[2], 0.8, 1e-12);
}

TEST(DataSelection, StartBeyondTheRecordLeavesNothing) {
  DataSelection selection;
  selection.start = 20;
  EXPECT_EQ(SelectSamples(Record(11), selection).size(), 0);
}

TEST(DataSelection, UnwrapsRoll) {
  const std::vector<double> wrapped = {350.0, 10.0, 30.0, 355.0, 5.0};
  const std::vector<double> u = UnwrapDegrees(wrapped);
  EXPECT_DOUBLE_EQ(u[1], 370.0);
  EXPECT_DOUBLE_EQ(u[3], 355.0);
  EXPECT_DOUBLE_EQ(u[4], 365.0);
}

}  // namespace
}  // namespace fit3dof
