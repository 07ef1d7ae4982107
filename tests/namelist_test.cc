// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/namelist.h"

#include <string>

#include "fit3dof/config.h"
#include "fit3dof/fit.h"
#include "fit3dof/input_error.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

std::string ParseError(const std::string& text) {
  try {
    ParseDeck(text, "deck.nml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Namelist, ReadsFortranNamelistSyntax) {
  const Deck deck = ParseDeck(
      " A TITLE CARD\n"
      " &NAM nswtch=0, BOUND=1.5D-3, AREA = .39 ! a comment\n"
      "   AACON(5)=1.0, 2.0E1 3*0.5, NCON=1,1,0, 2*,1\n"
      "   DIA=7.0D-1 IANGLE=1\n"
      " &END\n"
      " $NAM NITER=10, NSESWH=1 $END\n"
      " &NAM IUPDAT=.TRUE. /\n",
      "deck.nml");
  ASSERT_EQ(deck.groups.size(), 3u);
  ASSERT_EQ(deck.titles.size(), 1u);
  EXPECT_EQ(deck.titles[0], "A TITLE CARD");
  const DeckGroup& g = deck.groups[0];
  EXPECT_EQ(g.name, "NAM");
  ASSERT_EQ(g.assignments.size(), 7u);
  EXPECT_EQ(g.assignments[0].variable, "NSWTCH");
  EXPECT_DOUBLE_EQ(g.assignments[1].values[0].number, 1.5e-3);
  EXPECT_DOUBLE_EQ(g.assignments[2].values[0].number, 0.39);
  const DeckAssignment& aacon = g.assignments[3];
  EXPECT_EQ(aacon.variable, "AACON");
  EXPECT_EQ(aacon.index, 5);
  ASSERT_EQ(aacon.values.size(), 5u);
  EXPECT_DOUBLE_EQ(aacon.values[1].number, 20.0);
  EXPECT_DOUBLE_EQ(aacon.values[4].number, 0.5);
  const DeckAssignment& ncon = g.assignments[4];
  ASSERT_EQ(ncon.values.size(), 6u);
  EXPECT_EQ(ncon.values[3].kind, DeckValue::kNull);
  EXPECT_EQ(ncon.line, 3);
  EXPECT_DOUBLE_EQ(g.assignments[5].values[0].number, 0.7);
  EXPECT_EQ(deck.groups[2].assignments[0].values[0].kind, DeckValue::kLogical);
  EXPECT_TRUE(deck.groups[2].assignments[0].values[0].logical);
}

TEST(Namelist, MalformedDecksNameTheLine) {
  EXPECT_NE(ParseError(" &NAM AREA=0.39,\n DIA=1.2.3 &END\n")
                .find("deck.nml:2: DIA: '1.2.3'"),
            std::string::npos)
      << ParseError(" &NAM AREA=0.39,\n DIA=1.2.3 &END\n");
  EXPECT_NE(ParseError(" &NAM AREA=0.39\n\n DIA 0.7 &END\n")
                .find("deck.nml:3: AREA: expected a value, found 'DIA' (a "
                      "variable needs '='"),
            std::string::npos)
      << ParseError(" &NAM AREA=0.39\n\n DIA 0.7 &END\n");
  EXPECT_NE(ParseError(" &NAM AREA=0.39\n").find("not closed"),
            std::string::npos);
  EXPECT_NE(ParseError(" &NAM AACON(0)=1 &END\n").find("indices start at 1"),
            std::string::npos);
  EXPECT_NE(ParseError("just a title\n").find("no NAMELIST group"),
            std::string::npos);
  EXPECT_NE(ParseError(" &NAM NCON=x*1 &END\n").find("bad repeat count"),
            std::string::npos);
  // Unknown variables are found when the deck is converted.
  const Deck deck =
      ParseDeck(" &NAM AREA=0.39,\n   SPEED=3 &END\n", "deck.nml");
  try {
    DeckRuns(deck, "");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("deck.nml:2: SPEED: not a variable"),
              std::string::npos)
        << e.what();
  }
}

// A deck in Table 4 syntax fits exactly like the hand-written equivalent.
TEST(Namelist, DeckFitsLikeTheEquivalentConfig) {
  const Case deck =
      LoadDeckCase(testing::SourcePath("configs/examples/deck/table6.nml"),
                   testing::SourcePath("configs/report/data/table6_clean.csv"));
  const Case config = LoadConfig(
      testing::SourcePath("configs/examples/deck/table6_equivalent.yaml"));
  EXPECT_EQ(deck.model, config.model);
  EXPECT_DOUBLE_EQ(deck.flow.dynamic_pressure, config.flow.dynamic_pressure);
  const FitResult a = Fit(deck);
  const FitResult b = Fit(config);
  ASSERT_TRUE(a.converged && b.converged);
  ASSERT_EQ(a.parameters.size(), b.parameters.size());
  for (size_t i = 0; i < a.parameters.size(); ++i) {
    EXPECT_EQ(a.parameters[i].name, b.parameters[i].name);
    EXPECT_DOUBLE_EQ(a.parameters[i].value, b.parameters[i].value)
        << a.parameters[i].name;
  }
  EXPECT_DOUBLE_EQ(a.probable_error, b.probable_error);
}

// Groups read like the 1978 program: each changes only what it names;
// IUPDAT = 1 chains the next run; the asymmetric program is recognized.
TEST(Namelist, GroupsAccumulateAndChain) {
  const Deck deck = ParseDeck(
      " &NAM AREA=0.3491, DIA=0.6667, IX=0.0301, IY=0.2583, IZ=0.2565,\n"
      "   IZX=0.0016, RO=2.0D-5, U=2900., AACON(2)=-0.23, AACON(29)=0.23,\n"
      "   NCON(63)=1, IUPDAT=1, INLCON=1, IGPNO=3 &END\n"
      " &NAM NITER=7, IUPDAT=0 &END\n"
      " &NAM SAMPLE=0.5 &END\n",
      "sharp.nml");
  const std::vector<DeckRun> runs = DeckRuns(deck, "/data/run.csv");
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0].name, "sharp-1");
  EXPECT_EQ(runs[1].start_from, "sharp-1");
  EXPECT_EQ(runs[2].start_from, "");
  const Case second = ParseConfig(runs[1].config_yaml, "second", "/");
  EXPECT_EQ(second.model, ModelKind::kAsymmetric);
  EXPECT_DOUBLE_EQ(second.body.Iz, 0.2565);
  EXPECT_EQ(second.solver.max_iterations, 7);
  EXPECT_DOUBLE_EQ(second.parameters[FindParameter(second.model, "Izx")].value,
                   0.0016);
  EXPECT_TRUE(second.parameters[FindParameter(second.model, "t1")].free);
  EXPECT_EQ(second.segments[0].initial_conditions,
            InitialConditionMode::kGiven);
  const Case third = ParseConfig(runs[2].config_yaml, "third", "/");
  EXPECT_DOUBLE_EQ(third.segments[0].selection.fraction, 0.5);
  EXPECT_EQ(third.solver.max_iterations, 7);  // kept from group 2
  ASSERT_FALSE(runs[0].ignored.empty());
  EXPECT_EQ(runs[0].ignored[0], "IGPNO");
  // The manifest form chains with start_from.
  const std::string yaml = DeckToYaml(deck, "/data/run.csv");
  EXPECT_NE(yaml.find("start_from: \"sharp-1\""), std::string::npos) << yaml;
}

TEST(Namelist, MissingConstantsNameTheGroup) {
  const Deck deck =
      ParseDeck(" &NAM AREA=0.39, DIA=0.7, IX=0.03 &END\n", "x.nml");
  try {
    DeckRuns(deck, "");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("x.nml group 1: IY (body.Iy)"),
              std::string::npos)
        << e.what();
  }
}

TEST(NamelistCli, ConvertsADeckAndBatchRunsOne) {
  const std::string dir = testing::ScratchDirectory("namelist_cli");
  const std::string deck =
      testing::SourcePath("configs/examples/deck/table6.nml");
  const std::string data =
      testing::SourcePath("configs/report/data/table6_clean.csv");
  auto r = testing::RunFit3dof("namelist " + deck + " --data=" + data +
                               " --out=" + dir + "/table6.yaml");
  ASSERT_EQ(r.exit_status, 0) << r.output;
  EXPECT_NE(r.output.find("IGPNO accepted and ignored"), std::string::npos)
      << r.output;
  const Case c = LoadConfig(dir + "/table6.yaml");
  EXPECT_TRUE(c.parameters[0].free);
  r = testing::RunFit3dof("batch " + deck + " --data=" + data +
                          " --progress=false --out_dir=" + dir + "/batch");
  EXPECT_EQ(r.exit_status, 0) << r.output;
  EXPECT_NE(
      testing::ReadText(dir + "/batch/summary.csv").find("table6,converged"),
      std::string::npos);
  testing::WriteText(dir + "/bad.nml", " &NAM AREA=0.39,\n  DIA==0.7 &END\n");
  r = testing::RunFit3dof("namelist " + dir + "/bad.nml");
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_NE(r.output.find("bad.nml:2"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace fit3dof
