// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The parameter lists of the two programs of AEDC-TR-78-10: Table 4b (the
// symmetric program, 30 parameters, aeroballistic axes) and Table 4c (the
// asymmetric program, 72 parameters, body axes). Configs, reports and tests
// name parameters by these names (see docs/parameters.md); the
// 1-based report index is what a legacy NAMELIST deck (AACON, NCON) uses.
//
// After the report's lists come fit3dof extensions, none with a NAMELIST
// equivalent:
//   - the roll-interaction measurement error of Section 5.2 (symmetric
//     31-34, asymmetric 73-76): theta_m = theta + theta_cos_phi cos(phi) +
//     theta_sin_phi sin(phi), and the same for psi (degrees);
//   - a body-fixed trim moment in the symmetric program (35-36, Cm_0 and
//     Cn_0: the asymmetric program's 1 and 28, turning with the body);
//   - the gas bearing's moment (symmetric 37-38, asymmetric 77-78): a
//     stiffness Cm_bearing near zero angle that fades beyond bearing_angle,
//     the form of the pendulum study of Section 5.2 (bearing_moment.h);
//   - the calibration nonlinearity of Section 5.2 (symmetric 39-40,
//     asymmetric 79-80): theta_m += theta_cal3 (theta / 5 deg)^3, the
//     same for psi (the reading error at 5 deg);
//   - a drift of the readings in time (symmetric 41-42, asymmetric 81-82):
//     theta_m += theta_drift (t - t_0), the same for psi (deg/s, t_0 the
//     segment's first sample);
//   - a dynamic pressure drifting in time (symmetric 43, asymmetric 83):
//     every moment coefficient acts times 1 + q_drift (t - t_0) (1/s), as
//     each is a coefficient of q S d;
//   - a yaw-plane stiffness of the flow (symmetric 44, asymmetric 84):
//     M_z / (q S d) += Cn_beta_flow beta in the non-rolling frame, whose
//     y and z axes stay in the tunnel's pitch and yaw planes. A flow whose
//     stiffness differs between the tunnel's planes acts through the
//     model's normal force, so unlike Eq. 39's tunnel moments it has no
//     roll torque (outside diagnose's catalog);
//   - a lag of the readings (symmetric 45-46, asymmetric 85-86):
//     theta_m -= theta_lag dtheta/dt, the same for psi (s): a first-order
//     filter of time constant tau in the signal conditioning, to first
//     order in omega tau (outside diagnose's catalog);
//   - a pitch reading's gain off the yaw reading's (symmetric 47,
//     asymmetric 87): theta_m += theta_gain theta, a calibration slope
//     error (outside diagnose's catalog; a gain common to both readings
//     scales a linear motion, which the initial conditions absorb);
//   - dry friction of the bearing (symmetric 48, asymmetric 88): a moment
//     Cm_friction q S d against the pitch-yaw rate, of constant size
//     (bearing_friction.h; outside diagnose's catalog);
//   - dry friction about each of the pitch and yaw axes alone (symmetric
//     49, asymmetric 89): Cm_axis_friction q S d against each axis's own
//     rate (bearing_friction.h; outside diagnose's catalog);
//   - dry friction about the pitch axis alone and about the yaw axis alone
//     (symmetric 50-51, asymmetric 90-91): Cm_pitch_friction,
//     Cn_yaw_friction (bearing_friction.h; outside diagnose's catalog);
//   - a reading error at the second harmonic of roll (symmetric 52-55,
//     asymmetric 92-95): theta_m += theta_cos_2phi cos(2 phi) +
//     theta_sin_2phi sin(2 phi), the same for psi (degrees; Section 5.2's
//     reading error varies with roll "with no apparent symmetry", the
//     roll interaction above keeps its first harmonics; outside
//     diagnose's catalog);
//   - the calibration nonlinearity's signed square (symmetric 56-57,
//     asymmetric 96-97): theta_m += theta_cal2 (theta / 5 deg) |theta /
//     5 deg|, the same for psi (another form of Section 5.2's error,
//     which diagnose frees beside the cube);
//   - the range of the calibration fit (symmetric 58, asymmetric 98):
//     with cal_range R > 0 the signed square is taken less the straight
//     line a linear least-squares calibration over -R to R deg took of it,
//     theta_m += theta_cal2 (u |u| - 3 R / (4 x 5 deg) u), u = theta / 5
//     deg, the same for psi (diagnose's other form of the calibration
//     nonlinearity; 0 takes none).
//
// Every parameter is given and reported in the report's units (degrees,
// deg/s, derivatives per radian). Inside the equations of motion the
// coefficients are scaled the way the listings' REG subroutine does it; the
// Scaling of each parameter says how (see scaling.h).

#ifndef FIT3DOF_PARAMETERS_H_
#define FIT3DOF_PARAMETERS_H_

#include <string>
#include <string_view>
#include <vector>

namespace fit3dof {

// Upper bound on the number of parameters of any model; sizes fixed arrays.
inline constexpr int kMaxParameters = 98;
// The report's own lists: 30 (symmetric) and 72 (asymmetric) entries, the
// indices a NAMELIST deck may use.
inline constexpr int kReportParameters[2] = {30, 72};

enum class ModelKind {
  kSymmetric,   // axial symmetry, aeroballistic axes (Table 1, Eq. 6)
  kAsymmetric,  // mirror symmetry in x-z, body axes (Table 2, Appendix A)
};

// The report's IANGLE switch.
enum class Incidence {
  kVelocityRatio,  // IANGLE = 0: alpha = w/U, beta = v/U (Tobak, Eq. 33)
  kAngleOfAttack,  // IANGLE != 0: alpha = atan(w/u), beta = atan(v/u) (Eq. 34)
};

// How a parameter goes from the report's units to the listing's internal
// units (REG). "Pitch" uses q S d / I_y, "yaw" q S d / I_z, "roll"
// q S d / I_x; "rate" adds the factor d / (2 U).
enum class Scaling {
  kPitchStatic,
  kPitchRate,
  kYawStatic,
  kYawRate,
  kRollStatic,
  kRollRate,
  kAngle,      // degrees -> radians
  kAngleRate,  // deg/s -> rad/s
  kInertia,    // slug ft^2, used as is (the product of inertia I_zx)
  kPerSecond,  // 1/s, used as is (the dynamic pressure's drift)
  kSecond,     // s, used as is (the readings' lag)
  kRatio,      // dimensionless, used as is (a reading's gain error)
  kUnused,     // spare slots of the report's lists
};

struct ParameterInfo {
  int index;          // 1-based index in Table 4b / 4c
  std::string name;   // the name configs and reports use
  std::string alias;  // optional second name (t1..t4), may be empty
  std::string units;
  Scaling scaling;
  std::string description;
};

const char* ModelName(ModelKind model);          // "symmetric" | "asymmetric"
const char* IncidenceName(Incidence incidence);  // "velocity_ratio" | ...

// The parameter list of a model, ordered by report index (entry i has
// index i + 1).
const std::vector<ParameterInfo>& ParameterTable(ModelKind model);

inline int NumParameters(ModelKind model) {
  return static_cast<int>(ParameterTable(model).size());
}

// Returns the 0-based position of the parameter called `name` (or its alias)
// in ParameterTable(model), or -1.
int FindParameter(ModelKind model, std::string_view name);

// The closest parameter name to `name`, for "did you mean" messages; empty
// when nothing is close.
std::string SuggestParameter(ModelKind model, std::string_view name);

// 0-based positions of the special parameters of each model.
struct ParameterLayout {
  int theta_offset;        // theta_T (flow angularity / zero offset), degrees
  int psi_offset;          // psi_T
  int first_initial;       // first of the six initial-condition parameters
  int product_of_inertia;  // I_zx, or -1 for the symmetric model
  int roll_interaction;    // first of theta_cos_phi, theta_sin_phi,
                           // psi_cos_phi, psi_sin_phi
  int bearing;             // Cm_bearing, then bearing_angle
  int calibration;         // theta_cal3, then psi_cal3
  int drift;               // theta_drift, then psi_drift
  int q_drift;             // the dynamic pressure's drift (1/s)
  int flow_yaw_stiffness;  // Cn_beta_flow
  int lag;                 // theta_lag, then psi_lag (s)
  int gain;                // theta_gain
  int roll_harmonic2;      // first of theta_cos_2phi, theta_sin_2phi,
                           // psi_cos_2phi, psi_sin_2phi
  int calibration_square;  // theta_cal2, then psi_cal2
  int cal_range;           // cal_range
};
const ParameterLayout& Layout(ModelKind model);

// True for the six initial-condition parameters of the model.
bool IsInitialCondition(ModelKind model, int position);

}  // namespace fit3dof

#endif  // FIT3DOF_PARAMETERS_H_
