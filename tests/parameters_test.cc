// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/parameters.h"

#include <map>
#include <regex>
#include <set>

#include "fit3dof/scaling.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

// Names by index from docs/parameters.md, the project's naming contract.
std::map<int, std::string> DesignNames(const std::string& heading) {
  const std::string text =
      testing::ReadText(testing::SourcePath("docs/parameters.md"));
  const size_t begin = text.find(heading);
  EXPECT_NE(begin, std::string::npos);
  const size_t end = text.find("\n## ", begin + 1);
  const std::string section = text.substr(begin, end - begin);
  std::map<int, std::string> names;
  const std::regex cell(R"(\|\s*(\d+)\s*\|\s*`([A-Za-z0-9_]+)`)");
  for (auto it = std::sregex_iterator(section.begin(), section.end(), cell);
       it != std::sregex_iterator();
       ++it) {
    names[std::stoi((*it)[1])] = (*it)[2];
  }
  return names;
}

TEST(Parameters, TablesHaveTheReportsSizeAndOrder) {
  // The report's 30 and 72, then the extensions: the roll interaction
  // (4), the symmetric trim moment (2), the bearing moment (2) and the
  // calibration nonlinearity (2), the reading drift (2), the dynamic
  // pressure's drift (1), the flow's yaw-plane stiffness (1), the
  // readings' lag (2), the pitch reading's gain (1) and the bearing's dry
  // friction: against the rate vector, about each axis, about the pitch
  // axis alone and the yaw axis alone (4), the readings' second roll
  // harmonic (4), the calibration error's signed square (2) and its
  // calibration range (1).
  EXPECT_EQ(kReportParameters[0], 30);
  EXPECT_EQ(kReportParameters[1], 72);
  EXPECT_EQ(NumParameters(ModelKind::kSymmetric), 58);
  EXPECT_EQ(NumParameters(ModelKind::kAsymmetric), 98);
  for (ModelKind model : {ModelKind::kSymmetric, ModelKind::kAsymmetric}) {
    const auto& table = ParameterTable(model);
    std::set<std::string> names;
    for (size_t i = 0; i < table.size(); ++i) {
      EXPECT_EQ(table[i].index, static_cast<int>(i) + 1);
      EXPECT_TRUE(names.insert(table[i].name).second) << table[i].name;
      EXPECT_FALSE(table[i].units.empty()) << table[i].name;
    }
  }
}

TEST(Parameters, NamesMatchTheDesignDocument) {
  for (auto [model, heading] :
       {std::pair{ModelKind::kSymmetric, "## Symmetric model"},
        std::pair{ModelKind::kAsymmetric, "## Asymmetric model"}}) {
    const auto names = DesignNames(heading);
    const auto& table = ParameterTable(model);
    int checked = 0;
    for (const auto& [index, name] : names) {
      ASSERT_LE(index, static_cast<int>(table.size()));
      EXPECT_EQ(table[index - 1].name, name) << "index " << index;
      ++checked;
    }
    // Every named entry of the document (spares excepted) was compared.
    EXPECT_GE(checked, model == ModelKind::kSymmetric ? 27 : 70);
  }
}

TEST(Parameters, FindsNamesAndAliases) {
  EXPECT_EQ(FindParameter(ModelKind::kSymmetric, "Cm_alpha"), 0);
  EXPECT_EQ(FindParameter(ModelKind::kSymmetric, "t1"), 20);
  EXPECT_EQ(FindParameter(ModelKind::kSymmetric, "tunnel_Cm_theta"), 20);
  EXPECT_EQ(FindParameter(ModelKind::kAsymmetric, "t3"), 63);
  EXPECT_EQ(FindParameter(ModelKind::kAsymmetric, "Izx"), 59);
  EXPECT_EQ(FindParameter(ModelKind::kSymmetric, "Izx"), -1);
  EXPECT_EQ(FindParameter(ModelKind::kSymmetric, "Cm_alfa"), -1);
  EXPECT_EQ(SuggestParameter(ModelKind::kSymmetric, "Cm_alfa"), "Cm_alpha");
  EXPECT_EQ(SuggestParameter(ModelKind::kSymmetric, "xyzzy_quux"), "");
}

TEST(Parameters, LayoutPointsAtTheRightEntries) {
  const auto& sym = ParameterTable(ModelKind::kSymmetric);
  EXPECT_EQ(sym[Layout(ModelKind::kSymmetric).theta_offset].name, "theta_T");
  EXPECT_EQ(sym[Layout(ModelKind::kSymmetric).first_initial].name, "phi0");
  const auto& asym = ParameterTable(ModelKind::kAsymmetric);
  EXPECT_EQ(asym[Layout(ModelKind::kAsymmetric).psi_offset].name, "psi_T");
  EXPECT_EQ(asym[Layout(ModelKind::kAsymmetric).first_initial + 5].name, "r0");
  EXPECT_EQ(asym[Layout(ModelKind::kAsymmetric).product_of_inertia].name,
            "Izx");
  for (ModelKind model : {ModelKind::kSymmetric, ModelKind::kAsymmetric}) {
    const auto& table = ParameterTable(model);
    EXPECT_EQ(table[Layout(model).q_drift].name, "q_drift");
    EXPECT_EQ(table[Layout(model).flow_yaw_stiffness].name, "Cn_beta_flow");
    EXPECT_EQ(table[Layout(model).lag].name, "theta_lag");
    EXPECT_EQ(table[Layout(model).lag + 1].name, "psi_lag");
    EXPECT_EQ(table[Layout(model).gain].name, "theta_gain");
    EXPECT_EQ(table[Layout(model).roll_harmonic2].name, "theta_cos_2phi");
    EXPECT_EQ(table[Layout(model).roll_harmonic2 + 3].name, "psi_sin_2phi");
    EXPECT_EQ(table[Layout(model).calibration_square].name, "theta_cal2");
    EXPECT_EQ(table[Layout(model).calibration_square + 1].name, "psi_cal2");
    EXPECT_EQ(table[Layout(model).cal_range].name, "cal_range");
  }
  EXPECT_TRUE(IsInitialCondition(ModelKind::kSymmetric, 29));
  EXPECT_FALSE(IsInitialCondition(ModelKind::kSymmetric, 23));
}

// REG of both listings: the symmetric program divides by IPRM = I/(qSd) or
// MPRM = IPRM 2U/d, the roll terms also by RATIO = I_x/I.
TEST(Scaling, MatchesTheListingsReg) {
  Body body{0.39, 0.7047, 0.0372, 0.244, 0.250};
  Flow flow{4774.0, 150.4};
  const double iprm =
      body.Iy / (flow.dynamic_pressure * body.area * body.diameter);
  const double mprm = iprm * 2.0 * flow.velocity / body.diameter;
  const double ratio = body.Ix / body.Iy;
  const auto sym = InternalScaleFactors(ModelKind::kSymmetric, body, flow);
  EXPECT_DOUBLE_EQ(sym[0], 1.0 / iprm);             // Cm_alpha
  EXPECT_DOUBLE_EQ(sym[1], 1.0 / mprm);             // Cm_q
  EXPECT_DOUBLE_EQ(sym[9], 1.0 / (iprm * ratio));   // Cl_0
  EXPECT_DOUBLE_EQ(sym[12], 1.0 / (mprm * ratio));  // Cl_p
  EXPECT_DOUBLE_EQ(sym[21], 1.0 / iprm);            // t3 uses I = Iy
  EXPECT_DOUBLE_EQ(sym[25], M_PI / 180.0);          // phidot0
  const auto asym = InternalScaleFactors(ModelKind::kAsymmetric, body, flow);
  const double qsd = flow.dynamic_pressure * body.area * body.diameter;
  const double rate = body.diameter / (2.0 * flow.velocity);
  EXPECT_DOUBLE_EQ(asym[28], qsd / body.Iz);         // Cn_beta: MZ1
  EXPECT_DOUBLE_EQ(asym[35], qsd / body.Iz * rate);  // Cn_r: MZ2
  EXPECT_DOUBLE_EQ(asym[52], qsd / body.Ix * rate);  // Cl_p: MX2
  EXPECT_DOUBLE_EQ(asym[59], 1.0);                   // Izx
  EXPECT_DOUBLE_EQ(asym[62], qsd / body.Iy);         // t1: MY1
}

}  // namespace
}  // namespace fit3dof
