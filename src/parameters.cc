// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Tables 4b and 4c of AEDC-TR-78-10 with the names of
// docs/parameters.md. The scaling of each entry follows the
// listings' REG subroutines (Table 1: symmetric, Table 2: asymmetric).

#include "fit3dof/parameters.h"

#include <algorithm>
#include <cstdlib>

namespace fit3dof {
namespace {

using S = Scaling;

// `entries` numbered from `first` on, in their order.
std::vector<ParameterInfo> Numbered(int first,
                                    std::vector<ParameterInfo> entries) {
  for (ParameterInfo& e : entries) e.index = first++;
  return entries;
}

// fit3dof extensions both programs have (parameters.h), numbered from
// `first` on: the roll interaction (Section 5.2, Figs. 9-12).
std::vector<ParameterInfo> RollInteraction(int first) {
  return Numbered(
      first,
      {
          {0,
           "theta_cos_phi",
           "",
           "deg",
           S::kAngle,
           "roll interaction: pitch reading error, cos(phi) harmonic"},
          {0,
           "theta_sin_phi",
           "",
           "deg",
           S::kAngle,
           "roll interaction: pitch reading error, sin(phi) harmonic"},
          {0,
           "psi_cos_phi",
           "",
           "deg",
           S::kAngle,
           "roll interaction: yaw reading error, cos(phi) harmonic"},
          {0,
           "psi_sin_phi",
           "",
           "deg",
           S::kAngle,
           "roll interaction: yaw reading error, sin(phi) harmonic"},
      });
}

// The gas bearing's moment and calibration nonlinearity (Section 5.2), then
// the faults diagnose probes for outside its catalog: a drift of the
// readings and of the dynamic pressure, a flow stiffer in one plane, a lag
// and a gain error of the readings, dry friction in the bearing (against
// the pitch-yaw rate, about each axis, about one axis alone), a reading
// error at the second harmonic of roll, the calibration error's signed
// square.
std::vector<ParameterInfo> BearingAndFaults(int first) {
  return Numbered(
      first,
      {
          {0,
           "Cm_bearing",
           "",
           "1/rad",
           S::kPitchStatic,
           "gas-bearing moment: stiffness near zero angle, fading beyond "
           "bearing_angle"},
          {0,
           "bearing_angle",
           "",
           "deg",
           S::kAngle,
           "gas-bearing moment: the angle where it saturates"},
          {0,
           "theta_cal3",
           "",
           "deg",
           S::kAngle,
           "calibration nonlinearity: pitch reading error at 5 deg, cubic"},
          {0,
           "psi_cal3",
           "",
           "deg",
           S::kAngle,
           "calibration nonlinearity: yaw reading error at 5 deg, cubic"},
          // A drift of the readings in time (outside diagnose's catalog).
          {0,
           "theta_drift",
           "",
           "deg/s",
           S::kAngleRate,
           "reading drift: pitch reading error growing in time"},
          {0,
           "psi_drift",
           "",
           "deg/s",
           S::kAngleRate,
           "reading drift: yaw reading error growing in time"},
          // A dynamic pressure drifting in time (outside diagnose's catalog).
          {0,
           "q_drift",
           "",
           "1/s",
           S::kPerSecond,
           "dynamic-pressure drift: every moment x (1 + q_drift (t - t_0))"},
          // A yaw-plane stiffness of the flow, no roll torque (outside
          // diagnose's catalog).
          {0,
           "Cn_beta_flow",
           "",
           "1/rad",
           S::kPitchStatic,
           "flow's yaw-plane stiffness: M_z += Cn_beta_flow beta, non-rolling "
           "frame, no roll torque"},
          // A lag of the readings (outside diagnose's catalog).
          {0,
           "theta_lag",
           "",
           "s",
           S::kSecond,
           "reading lag: pitch read through a first-order filter of this time "
           "constant"},
          {0,
           "psi_lag",
           "",
           "s",
           S::kSecond,
           "reading lag: yaw read through a first-order filter of this time "
           "constant"},
          // A pitch reading's gain error (outside diagnose's catalog).
          {0,
           "theta_gain",
           "",
           "-",
           S::kRatio,
           "reading gain: theta_m += theta_gain theta (against the yaw "
           "reading's)"},
          // Dry friction of the bearing (outside diagnose's catalog).
          {0,
           "Cm_friction",
           "",
           "-",
           S::kPitchStatic,
           "bearing friction: a moment of this size against the pitch-yaw "
           "rate"},
          // Dry friction about each of the pitch and yaw axes alone (outside
          // diagnose's catalog).
          {0,
           "Cm_axis_friction",
           "",
           "-",
           S::kPitchStatic,
           "axis friction: a moment of this size about each of the pitch "
           "and yaw axes against that axis's rate"},
          // Dry friction about the pitch axis alone, and the yaw axis
          // alone (outside diagnose's catalog).
          {0,
           "Cm_pitch_friction",
           "",
           "-",
           S::kPitchStatic,
           "pitch friction: a moment of this size about the pitch axis "
           "alone against its rate"},
          {0,
           "Cn_yaw_friction",
           "",
           "-",
           S::kPitchStatic,
           "yaw friction: a moment of this size about the yaw axis alone "
           "against its rate"},
          // A reading error at the second harmonic of roll (outside
          // diagnose's catalog): Section 5.2 found the reading error varying
          // with roll "with no apparent symmetry".
          {0,
           "theta_cos_2phi",
           "",
           "deg",
           S::kAngle,
           "second roll harmonic: pitch reading error, cos(2 phi)"},
          {0,
           "theta_sin_2phi",
           "",
           "deg",
           S::kAngle,
           "second roll harmonic: pitch reading error, sin(2 phi)"},
          {0,
           "psi_cos_2phi",
           "",
           "deg",
           S::kAngle,
           "second roll harmonic: yaw reading error, cos(2 phi)"},
          {0,
           "psi_sin_2phi",
           "",
           "deg",
           S::kAngle,
           "second roll harmonic: yaw reading error, sin(2 phi)"},
          // The calibration nonlinearity's signed square (diagnose frees it
          // beside the cube: another form of Section 5.2's error).
          {0,
           "theta_cal2",
           "",
           "deg",
           S::kAngle,
           "calibration nonlinearity: pitch reading error at 5 deg, signed "
           "square"},
          {0,
           "psi_cal2",
           "",
           "deg",
           S::kAngle,
           "calibration nonlinearity: yaw reading error at 5 deg, signed "
           "square"},
          // The range of the linear calibration fit that took a straight
          // line out of the signed square (diagnose's other form of the
          // calibration nonlinearity); 0: none taken.
          {0,
           "cal_range",
           "",
           "deg",
           S::kAngle,
           "calibration nonlinearity: the signed square less its straight "
           "line over +-cal_range"},
      });
}

void Append(const std::vector<ParameterInfo>& more,
            std::vector<ParameterInfo>* table) {
  table->insert(table->end(), more.begin(), more.end());
}

std::vector<ParameterInfo> MakeSymmetricTable() {
  // Symmetric REG: indices 1, 3, 5, 21, 22 divide by IPRM = I/(q S d);
  // the other aerodynamic indices up to 22 divide by MPRM = IPRM 2U/d;
  // 10, 11, 13, 14 also divide by RATIO = I_x/I (they act on the roll
  // axis); 23-30 are angles and rates in degrees.
  std::vector<ParameterInfo> table = {
      {1, "Cm_alpha", "", "1/rad", S::kPitchStatic, "dCm/d(alpha)"},
      {2, "Cm_q", "", "1/rad", S::kPitchRate, "dCm/d(q d/2U)"},
      {3,
       "Cm_alpha_delta",
       "",
       "1/rad^2",
       S::kPitchStatic,
       "dCm/d(alpha delta)"},
      {4,
       "Cm_p_alpha",
       "",
       "1/rad^2",
       S::kPitchRate,
       "dCm/d(p alpha d/2U) (Magnus)"},
      {5,
       "Cm_alpha_delta2",
       "",
       "1/rad^3",
       S::kPitchStatic,
       "dCm/d(alpha delta^2)"},
      {6, "Cm_q_delta2", "", "1/rad^3", S::kPitchRate, "dCm/d(q delta^2 d/2U)"},
      {7, "Cm_q_beta2", "", "1/rad^3", S::kPitchRate, "dCm/d(q beta^2 d/2U)"},
      {8,
       "Cm_r_alpha_beta",
       "",
       "1/rad^3",
       S::kPitchRate,
       "dCm/d(r alpha beta d/2U)"},
      {9, "Cm_q_delta", "", "1/rad^2", S::kPitchRate, "dCm/d(q delta d/2U)"},
      {10, "Cl_0", "", "-", S::kRollStatic, "roll torque (gas bearing)"},
      {11, "Cl_p_delta", "", "1/rad^2", S::kRollRate, "dCl/d(p delta d/2U)"},
      {12,
       "Cm_p_alpha_delta2",
       "",
       "1/rad^4",
       S::kPitchRate,
       "dCm/d(p alpha delta^2 d/2U)"},
      {13, "Cl_p", "", "1/rad", S::kRollRate, "dCl/d(p d/2U)"},
      {14, "Cl_p_delta2", "", "1/rad^3", S::kRollRate, "dCl/d(p delta^2 d/2U)"},
      {15,
       "Cm_alphadot",
       "",
       "1/rad",
       S::kPitchRate,
       "dCm/d(alphadot d/2U) (Section 5.1 experiment only)"},
      {16, "spare16", "", "-", S::kUnused, "unused"},
      {17, "spare17", "", "-", S::kUnused, "unused"},
      {18, "spare18", "", "-", S::kUnused, "unused"},
      {19,
       "tunnel_Cn_psidot",
       "t4",
       "1/rad",
       S::kYawRate,
       "dCn/d(psidot d/2U), tunnel-fixed"},
      {20,
       "tunnel_Cm_thetadot",
       "t2",
       "1/rad",
       S::kPitchRate,
       "dCm/d(thetadot d/2U), tunnel-fixed"},
      {21,
       "tunnel_Cm_theta",
       "t1",
       "1/rad",
       S::kPitchStatic,
       "dCm/d(theta), tunnel-fixed"},
      {22,
       "tunnel_Cn_psi",
       "t3",
       "1/rad",
       S::kYawStatic,
       "dCn/d(psi), tunnel-fixed"},
      {23,
       "theta_T",
       "",
       "deg",
       S::kAngle,
       "flow angularity / zero offset in pitch"},
      {24,
       "psi_T",
       "",
       "deg",
       S::kAngle,
       "flow angularity / zero offset in yaw"},
      {25, "phi0", "", "deg", S::kAngle, "initial roll angle"},
      {26, "phidot0", "", "deg/s", S::kAngleRate, "initial roll rate (Euler)"},
      {27, "theta0", "", "deg", S::kAngle, "initial pitch angle"},
      {28, "thetadot0", "", "deg/s", S::kAngleRate, "initial pitch rate"},
      {29, "psi0", "", "deg", S::kAngle, "initial yaw angle"},
      {30, "psidot0", "", "deg/s", S::kAngleRate, "initial yaw rate"},
  };
  Append(RollInteraction(31), &table);
  // A body-fixed trim moment (rolls with the body; the asymmetric
  // program's Cm_0 and Cn_0).
  table.push_back(
      {35, "Cm_0", "", "-", S::kPitchStatic, "body-fixed trim moment, pitch"});
  table.push_back(
      {36, "Cn_0", "", "-", S::kYawStatic, "body-fixed trim moment, yaw"});
  Append(BearingAndFaults(37), &table);
  return table;
}

std::vector<ParameterInfo> MakeAsymmetricTable() {
  // Asymmetric REG: 1-16 and 63 multiply by MY1 = q S d / I_y, 17-27 and 62
  // by MY2 = MY1 d/2U, 28-35 and 64 by MZ1, 36-46 and 61 by MZ2, 47-52 by
  // MX1, 53-57 by MX2; 60 (I_zx) as is; 65-72 are angles and rates.
  std::vector<ParameterInfo> table = {
      {1, "Cm_0", "", "-", S::kPitchStatic, "Cm at zero incidence"},
      {2, "Cm_alpha", "", "1/rad", S::kPitchStatic, "dCm/d(alpha)"},
      {3, "Cm_absalpha", "", "1/rad", S::kPitchStatic, "dCm/d(|alpha|)"},
      {4, "Cm_alpha2", "", "1/rad^2", S::kPitchStatic, "dCm/d(alpha^2)"},
      {5,
       "Cm_alpha_absalpha",
       "",
       "1/rad^2",
       S::kPitchStatic,
       "dCm/d(alpha |alpha|)"},
      {6, "Cm_alpha3", "", "1/rad^3", S::kPitchStatic, "dCm/d(alpha^3)"},
      {7,
       "Cm_alpha2_absalpha",
       "",
       "1/rad^3",
       S::kPitchStatic,
       "dCm/d(alpha^2 |alpha|)"},
      {8, "Cm_absbeta", "", "1/rad", S::kPitchStatic, "dCm/d(|beta|)"},
      {9, "Cm_beta2", "", "1/rad^2", S::kPitchStatic, "dCm/d(beta^2)"},
      {10,
       "Cm_beta2_absbeta",
       "",
       "1/rad^3",
       S::kPitchStatic,
       "dCm/d(beta^2 |beta|)"},
      {11,
       "Cm_alpha_absbeta",
       "",
       "1/rad^2",
       S::kPitchStatic,
       "dCm/d(alpha |beta|)"},
      {12,
       "Cm_absalphabeta",
       "",
       "1/rad^2",
       S::kPitchStatic,
       "dCm/d(|alpha beta|)"},
      {13,
       "Cm_alpha2_absbeta",
       "",
       "1/rad^3",
       S::kPitchStatic,
       "dCm/d(alpha^2 |beta|)"},
      {14,
       "Cm_alpha_absalphabeta",
       "",
       "1/rad^3",
       S::kPitchStatic,
       "dCm/d(alpha |alpha beta|)"},
      {15,
       "Cm_alpha_beta2",
       "",
       "1/rad^3",
       S::kPitchStatic,
       "dCm/d(alpha beta^2)"},
      {16,
       "Cm_absalpha_beta2",
       "",
       "1/rad^3",
       S::kPitchStatic,
       "dCm/d(|alpha| beta^2)"},
      {17, "Cm_q", "", "1/rad", S::kPitchRate, "dCm/d(q d/2U)"},
      {18, "Cm_q_alpha", "", "1/rad^2", S::kPitchRate, "dCm/d(q alpha d/2U)"},
      {19,
       "Cm_q_absalpha",
       "",
       "1/rad^2",
       S::kPitchRate,
       "dCm/d(q |alpha| d/2U)"},
      {20,
       "Cm_q_alpha2",
       "",
       "1/rad^3",
       S::kPitchRate,
       "dCm/d(q alpha^2 d/2U)"},
      {21,
       "Cm_q_alpha_absalpha",
       "",
       "1/rad^3",
       S::kPitchRate,
       "dCm/d(q alpha |alpha| d/2U)"},
      {22,
       "Cm_q_absbeta",
       "",
       "1/rad^2",
       S::kPitchRate,
       "dCm/d(q |beta| d/2U)"},
      {23, "Cm_q_beta2", "", "1/rad^3", S::kPitchRate, "dCm/d(q beta^2 d/2U)"},
      {24,
       "Cm_q_alpha_absbeta",
       "",
       "1/rad^3",
       S::kPitchRate,
       "dCm/d(q alpha |beta| d/2U)"},
      {25,
       "Cm_q_absalphabeta",
       "",
       "1/rad^3",
       S::kPitchRate,
       "dCm/d(q |alpha beta| d/2U)"},
      {26, "Cm_r_beta", "", "1/rad^2", S::kPitchRate, "dCm/d(r beta d/2U)"},
      {27,
       "Cm_p_beta",
       "",
       "1/rad^2",
       S::kPitchRate,
       "dCm/d(p beta d/2U) (Magnus)"},
      {28, "Cn_0", "", "-", S::kYawStatic, "Cn at zero incidence"},
      {29, "Cn_beta", "", "1/rad", S::kYawStatic, "dCn/d(beta)"},
      {30, "Cn_alpha_beta", "", "1/rad^2", S::kYawStatic, "dCn/d(alpha beta)"},
      {31,
       "Cn_absalpha_beta",
       "",
       "1/rad^2",
       S::kYawStatic,
       "dCn/d(|alpha| beta)"},
      {32, "Cn_beta3", "", "1/rad^3", S::kYawStatic, "dCn/d(beta^3)"},
      {33,
       "Cn_alpha2_beta",
       "",
       "1/rad^3",
       S::kYawStatic,
       "dCn/d(alpha^2 beta)"},
      {34,
       "Cn_beta_absbeta",
       "",
       "1/rad^2",
       S::kYawStatic,
       "dCn/d(beta |beta|)"},
      {35,
       "Cn_beta_absalphabeta",
       "",
       "1/rad^3",
       S::kYawStatic,
       "dCn/d(beta |alpha beta|)"},
      {36, "Cn_r", "", "1/rad", S::kYawRate, "dCn/d(r d/2U)"},
      {37, "Cn_r_alpha", "", "1/rad^2", S::kYawRate, "dCn/d(r alpha d/2U)"},
      {38,
       "Cn_r_absalpha",
       "",
       "1/rad^2",
       S::kYawRate,
       "dCn/d(r |alpha| d/2U)"},
      {39, "Cn_r_alpha2", "", "1/rad^3", S::kYawRate, "dCn/d(r alpha^2 d/2U)"},
      {40, "Cn_r_absbeta", "", "1/rad^2", S::kYawRate, "dCn/d(r |beta| d/2U)"},
      {41, "Cn_r_beta2", "", "1/rad^3", S::kYawRate, "dCn/d(r beta^2 d/2U)"},
      {42,
       "Cn_r_alpha_absalpha",
       "",
       "1/rad^3",
       S::kYawRate,
       "dCn/d(r alpha |alpha| d/2U)"},
      {43,
       "Cn_r_alpha_absbeta",
       "",
       "1/rad^3",
       S::kYawRate,
       "dCn/d(r alpha |beta| d/2U)"},
      {44,
       "Cn_r_absalphabeta",
       "",
       "1/rad^3",
       S::kYawRate,
       "dCn/d(r |alpha beta| d/2U)"},
      {45, "Cn_q_beta", "", "1/rad^2", S::kYawRate, "dCn/d(q beta d/2U)"},
      {46,
       "Cn_p_alpha",
       "",
       "1/rad^2",
       S::kYawRate,
       "dCn/d(p alpha d/2U) (Magnus)"},
      {47, "Cl_0", "", "-", S::kRollStatic, "roll torque at zero incidence"},
      {48, "Cl_alpha", "", "1/rad", S::kRollStatic, "dCl/d(alpha)"},
      {49, "Cl_beta", "", "1/rad", S::kRollStatic, "dCl/d(beta)"},
      {50, "Cl_alpha_beta", "", "1/rad^2", S::kRollStatic, "dCl/d(alpha beta)"},
      {51,
       "Cl_absalpha_beta",
       "",
       "1/rad^2",
       S::kRollStatic,
       "dCl/d(|alpha| beta)"},
      {52,
       "Cl_beta_absbeta",
       "",
       "1/rad^2",
       S::kRollStatic,
       "dCl/d(beta |beta|)"},
      {53, "Cl_p", "", "1/rad", S::kRollRate, "dCl/d(p d/2U)"},
      {54,
       "Cl_p_absalpha",
       "",
       "1/rad^2",
       S::kRollRate,
       "dCl/d(p |alpha| d/2U)"},
      {55, "Cl_p_absbeta", "", "1/rad^2", S::kRollRate, "dCl/d(p |beta| d/2U)"},
      {56, "Cl_p_alpha2", "", "1/rad^3", S::kRollRate, "dCl/d(p alpha^2 d/2U)"},
      {57, "Cl_p_beta2", "", "1/rad^3", S::kRollRate, "dCl/d(p beta^2 d/2U)"},
      {58, "spare58", "", "-", S::kUnused, "unused"},
      {59, "spare59", "", "-", S::kUnused, "unused"},
      {60,
       "Izx",
       "",
       "slug ft^2",
       S::kInertia,
       "product of inertia (h_x = I_x p - I_zx r, Eq. 2)"},
      {61,
       "tunnel_Cn_psidot",
       "t4",
       "1/rad",
       S::kYawRate,
       "dCn/d(psidot d/2U), tunnel-fixed"},
      {62,
       "tunnel_Cm_thetadot",
       "t2",
       "1/rad",
       S::kPitchRate,
       "dCm/d(thetadot d/2U), tunnel-fixed"},
      {63,
       "tunnel_Cm_theta",
       "t1",
       "1/rad",
       S::kPitchStatic,
       "dCm/d(theta), tunnel-fixed"},
      {64,
       "tunnel_Cn_psi",
       "t3",
       "1/rad",
       S::kYawStatic,
       "dCn/d(psi), tunnel-fixed"},
      {65,
       "theta_T",
       "",
       "deg",
       S::kAngle,
       "flow angularity / zero offset in pitch"},
      {66,
       "psi_T",
       "",
       "deg",
       S::kAngle,
       "flow angularity / zero offset in yaw"},
      {67, "phi0", "", "deg", S::kAngle, "initial roll angle"},
      {68, "theta0", "", "deg", S::kAngle, "initial pitch angle"},
      {69, "psi0", "", "deg", S::kAngle, "initial yaw angle"},
      {70, "p0", "", "deg/s", S::kAngleRate, "initial body roll rate"},
      {71, "q0", "", "deg/s", S::kAngleRate, "initial body pitch rate"},
      {72, "r0", "", "deg/s", S::kAngleRate, "initial body yaw rate"},
  };
  Append(RollInteraction(73), &table);
  Append(BearingAndFaults(77), &table);
  return table;
}

// Levenshtein distance, for suggestions.
int EditDistance(std::string_view a, std::string_view b) {
  std::vector<int> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    int diagonal = row[0];
    row[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j) {
      const int above = row[j];
      const int cost = a[i - 1] == b[j - 1] ? 0 : 1;
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + cost});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

const char* ModelName(ModelKind model) {
  return model == ModelKind::kSymmetric ? "symmetric" : "asymmetric";
}

const char* IncidenceName(Incidence incidence) {
  return incidence == Incidence::kVelocityRatio ? "velocity_ratio"
                                                : "angle_of_attack";
}

const std::vector<ParameterInfo>& ParameterTable(ModelKind model) {
  static const std::vector<ParameterInfo> symmetric = MakeSymmetricTable();
  static const std::vector<ParameterInfo> asymmetric = MakeAsymmetricTable();
  return model == ModelKind::kSymmetric ? symmetric : asymmetric;
}

int FindParameter(ModelKind model, std::string_view name) {
  const auto& table = ParameterTable(model);
  for (size_t i = 0; i < table.size(); ++i) {
    if (table[i].name == name ||
        (!table[i].alias.empty() && table[i].alias == name)) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

std::string SuggestParameter(ModelKind model, std::string_view name) {
  std::string best;
  int best_distance = 4;
  for (const ParameterInfo& info : ParameterTable(model)) {
    const int d = EditDistance(name, info.name);
    if (d < best_distance) {
      best_distance = d;
      best = info.name;
    }
  }
  return best;
}

const ParameterLayout& Layout(ModelKind model) {
  static const ParameterLayout symmetric{
      22, 23, 24, -1, 30, 36, 38, 40, 42, 43, 44, 46, 51, 55, 57};
  static const ParameterLayout asymmetric{
      64, 65, 66, 59, 72, 76, 78, 80, 82, 83, 84, 86, 91, 95, 97};
  return model == ModelKind::kSymmetric ? symmetric : asymmetric;
}

bool IsInitialCondition(ModelKind model, int position) {
  const int first = Layout(model).first_initial;
  return position >= first && position < first + 6;
}

}  // namespace fit3dof
