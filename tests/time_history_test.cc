// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/time_history.h"

#include <cmath>
#include <filesystem>

#include "fit3dof/case.h"
#include "fit3dof/input_error.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

std::string ReadError(const std::string& path) {
  try {
    ReadTimeHistory(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// The channel accessors follow the order of a record's columns, the order
// SegmentFit::computed and every per-channel loop use.
TEST(TimeHistory, ChannelsInColumnOrder) {
  TimeHistory h;
  h.Append(0.0, 1.0, 2.0, 3.0);
  h.channel(1)[0] = 5.0;
  EXPECT_EQ(h.channel(0), h.phi);
  EXPECT_EQ(h.theta[0], 5.0);
  EXPECT_EQ(&h.channel(2), &h.psi);
  ChannelValues v{0.1, 0.2, 0.3};
  v[2] = 0.4;
  const ChannelValues& c = v;
  EXPECT_EQ(c[0], 0.1);
  EXPECT_EQ(c[1], 0.2);
  EXPECT_EQ(v.psi, 0.4);
  EXPECT_DEATH(h.channel(3), "channel 3");
  EXPECT_DEATH(v[-1], "channel -1");
}

TEST(TimeHistory, RoundTripsThroughCsv) {
  const std::string dir = testing::ScratchDirectory("time_history_roundtrip");
  TimeHistory h;
  h.Append(0.0, 1.5, 5.18, -2.589);
  h.Append(0.06, 40.0, 5.0123456789, -2.6);
  WriteTimeHistory(dir + "/a.csv", h);
  const TimeHistory r = ReadTimeHistory(dir + "/a.csv");
  ASSERT_EQ(r.size(), 2);
  EXPECT_NEAR(r.theta[1], 5.0123456789, 1e-11);
  EXPECT_DOUBLE_EQ(r.psi[0], -2.589);
  EXPECT_FALSE(std::filesystem::exists(dir + "/a.csv.tmp"));
}

TEST(TimeHistory, ColumnsInAnyOrderExtraColumnsIgnored) {
  const std::string dir = testing::ScratchDirectory("time_history_columns");
  testing::WriteText(
      dir + "/b.csv",
      "psi,extra,t,theta,phi\n1.0,x,0.0,2.0,3.0\n1.5,y,0.1,2.5,3.5\n");
  const TimeHistory r = ReadTimeHistory(dir + "/b.csv");
  ASSERT_EQ(r.size(), 2);
  EXPECT_DOUBLE_EQ(r.t[1], 0.1);
  EXPECT_DOUBLE_EQ(r.phi[1], 3.5);
  EXPECT_DOUBLE_EQ(r.psi[0], 1.0);
}

TEST(TimeHistory, BadFilesNameTheFileAndLine) {
  const std::string dir = testing::ScratchDirectory("time_history_bad");
  testing::WriteText(dir + "/order.csv",
                     "t,phi,theta,psi\n0,0,0,0\n0.1,0,0,0\n0.1,0,0,0\n");
  EXPECT_NE(
      ReadError(dir + "/order.csv").find("order.csv:4: times must increase"),
      std::string::npos)
      << ReadError(dir + "/order.csv");
  testing::WriteText(dir + "/column.csv", "t,phi,theta\n0,0,0\n0.1,0,0\n");
  EXPECT_NE(ReadError(dir + "/column.csv").find("psi"), std::string::npos)
      << ReadError(dir + "/column.csv");
  testing::WriteText(dir + "/nan.csv",
                     "t,phi,theta,psi\n0,0,0,0\n0.1,0,nan,0\n");
  EXPECT_NE(ReadError(dir + "/nan.csv")
                .find("nan.csv:3: column 'theta': expected a finite decimal "
                      "number, got 'nan'"),
            std::string::npos)
      << ReadError(dir + "/nan.csv");
  testing::WriteText(dir + "/text.csv",
                     "t,phi,theta,psi\n0,0,0,0\n0.1,0,abc,0\n");
  EXPECT_NE(ReadError(dir + "/text.csv").find("text.csv"), std::string::npos)
      << ReadError(dir + "/text.csv");
  testing::WriteText(dir + "/short.csv", "t,phi,theta,psi\n0,0,0,0\n");
  EXPECT_NE(ReadError(dir + "/short.csv").find("at least two rows"),
            std::string::npos);
  EXPECT_NE(ReadError(dir + "/missing.csv").find("missing.csv"),
            std::string::npos)
      << ReadError(dir + "/missing.csv");
}

// Issue 9: tokens that are not whole numbers were read as 0 (or as their
// numeric prefix) and ended in a misleading "local minimum".
TEST(TimeHistory, EveryTokenIsAWholeFiniteNumber) {
  for (const char* token : {"",
                            "-",
                            ".",
                            "1.5e",
                            "+",
                            "e5",
                            "1e+",
                            "0x10",
                            "inf",
                            "1.2.3",
                            "1,5",
                            "\"\"",
                            "1 2",
                            "--1",
                            "1e5x"}) {
    const std::string text =
        std::string("t,phi,theta,psi\n0,0,0,0\n0.1,0,") + token + ",0\n";
    try {
      ParseTimeHistory(text, "run.csv");
      ADD_FAILURE() << "accepted '" << token << "'";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.find("run.csv:3"), 0u) << message;
      EXPECT_EQ(message.find("integer"), std::string::npos) << message;
      if (std::string(token) != "1,5") {
        EXPECT_NE(message.find("column 'theta'"), std::string::npos) << message;
      }
    }
  }
}

TEST(TimeHistory, AcceptsQuotedNumbersAndExponents) {
  const TimeHistory r = ParseTimeHistory(
      "\"t\",\"phi\",\"theta\",\"psi\"\n\"0\",\"1.25\",\"-2e-1\",\"+3.\"\n"
      "1E1,.5,-0.0,7\n",
      "quoted.csv");
  ASSERT_EQ(r.size(), 2);
  EXPECT_DOUBLE_EQ(r.phi[0], 1.25);
  EXPECT_DOUBLE_EQ(r.theta[0], -0.2);
  EXPECT_DOUBLE_EQ(r.psi[0], 3.0);
  EXPECT_DOUBLE_EQ(r.t[1], 10.0);
  EXPECT_DOUBLE_EQ(r.phi[1], 0.5);
}

// One period estimator for the continuation and the epicyclic start: a
// coning motion of period 0.4 s is found within a sample's worth, and a
// record with fewer crossings than asked for gives 0.
TEST(CrossingPeriod, FindsTheConingPeriod) {
  TimeHistory h;
  for (int i = 0; i <= 2000; ++i) {
    const double t = 0.001 * i;
    const double phase = 2.0 * M_PI * t / 0.4 + 0.3;
    h.Append(t, 0.0, 1.0 + 5.0 * std::cos(phase), -2.0 + 5.0 * std::sin(phase));
  }
  EXPECT_NEAR(CrossingPeriod(h, 8.0), 0.4, 0.4 / 20.0);
  EXPECT_EQ(CrossingPeriod(h, 21.0), 0.0);  // 5 cycles: 20 crossings
  EXPECT_EQ(CrossingPeriod(TimeHistory(), 2.0), 0.0);
}

// The total angle, not either channel's: (3, -4) deg is 5 deg off zero,
// larger than (4.5, 0); an empty record has none.
TEST(LargestTotalAngle, IsTheLargestOfTheCombinedAngle) {
  TimeHistory h;
  h.Append(0.0, 90.0, 4.5, 0.0);
  h.Append(0.1, 0.0, 3.0, -4.0);
  h.Append(0.2, 0.0, -1.0, 1.0);
  EXPECT_DOUBLE_EQ(LargestTotalAngle(h), 5.0);
  EXPECT_EQ(LargestTotalAngle(TimeHistory()), 0.0);
}

}  // namespace
}  // namespace fit3dof
