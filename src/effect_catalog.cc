// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The effects diagnose can add (diagnose.h), and the candidate case of
// each.

#include <algorithm>

#include "diagnose_internal.h"
#include "fit3dof/config.h"
#include "fit3dof/input_error.h"
#include "fit3dof/model_conversion.h"
#include "fit3dof/parameters.h"

namespace fit3dof {

const std::vector<Effect>& EffectCatalog() {
  static const std::vector<Effect> catalog = {
      {"tunnel_stiffness",
       "tunnel-fixed pitch and yaw stiffness (Eq. 39)",
       {"tunnel_Cm_theta", "tunnel_Cn_psi"},
       {"tunnel_Cm_theta", "tunnel_Cn_psi"},
       false,
       {},
       "amplitude",
       "|t1|, |t3| up to half of the pitch and yaw stiffness, |Cm_alpha + t1| "
       "and |Cm_alpha + t3|",
       false,
       false,
       true},
      {"tunnel_damping",
       "tunnel-fixed pitch and yaw damping (Eq. 39)",
       {"tunnel_Cm_thetadot", "tunnel_Cn_psidot"},
       {"tunnel_Cm_thetadot", "tunnel_Cn_psidot"},
       false,
       {},
       "amplitude",
       "|t2|, |t4| up to twice the pitch and yaw damping, |Cm_q + t2| and "
       "|Cm_q + t4|",
       false,
       false,
       true},
      {"flow_angularity",
       "flow angularity / zero offsets in pitch and yaw",
       {"theta_T", "psi_T"},
       {"theta_T", "psi_T"},
       false,
       {},
       "spin rate",
       "|theta_T|, |psi_T| up to 1 deg"},
      {"product_of_inertia",
       "a product of inertia I_zx (asymmetric program)",
       {},
       {"Izx"},
       true,
       {},
       "spin rate",
       "|I_zx| up to 5% of I_y"},
      {"asymmetric_body",
       "a yaw stiffness and damping of the body's own (Cn_beta, Cn_r apart "
       "from -Cm_alpha, Cm_q; asymmetric program)",
       {},
       {"Cn_beta", "Cn_r"},
       true,
       {},
       "spin rate",
       "|Cn_beta + Cm_alpha| up to 20% of |Cm_alpha|, |Cn_r - Cm_q| up to "
       "|Cm_q|"},
      {"roll_torque",
       "a roll torque from the gas bearing (Cl_0)",
       {"Cl_0"},
       {"Cl_0"},
       false,
       {},
       "spin rate",
       "none"},
      {"magnus",
       "a Magnus moment",
       {"Cm_p_alpha"},
       {"Cm_p_beta", "Cn_p_alpha"},
       false,
       {},
       "spin rate",
       "none"},
      {"nonlinear_stiffness",
       "nonlinear (cubic) static stiffness (Eq. 16's delta^2 term)",
       {"Cm_alpha_delta2"},
       {"Cm_alpha3", "Cn_beta3"},
       false,
       {},
       "amplitude",
       "changes the linear stiffness by at most 4 times its size over the "
       "record's angles"},
      {"nonlinear_damping",
       "nonlinear pitch and yaw damping (Eq. 16's delta^2 term)",
       {"Cm_q_delta2"},
       {"Cm_q_alpha2", "Cn_r_beta2"},
       false,
       {},
       "amplitude",
       "changes the linear damping by at most 4 times its size over the "
       "record's angles",
       false,
       false,
       true},
      {"roll_damping",
       "roll damping (Cl_p)",
       {"Cl_p"},
       {"Cl_p"},
       false,
       {},
       "spin rate",
       "Cl_p negative (or within 2 standard errors of zero)"},
      {"trim_moment",
       "a body-fixed trim moment in pitch and yaw (Cm_0, Cn_0)",
       {"Cm_0", "Cn_0"},
       {"Cm_0", "Cn_0"},
       false,
       {},
       "spin rate",
       "a trim angle |(Cm_0, Cn_0)| / |Cm_alpha| up to 2 deg",
       true},
      {"roll_interaction",
       "a pitch and yaw reading error that varies with roll (Section 5.2)",
       {"theta_cos_phi", "theta_sin_phi", "psi_cos_phi", "psi_sin_phi"},
       {"theta_cos_phi", "theta_sin_phi", "psi_cos_phi", "psi_sin_phi"},
       false,
       {},
       "spin rate",
       "up to 0.2 deg in each channel (the report's bench test: 0.1)",
       true},
      {"bearing_moment",
       "a gas-bearing moment near zero angle (Section 5.2)",
       {"Cm_bearing", "bearing_angle"},
       {"Cm_bearing", "bearing_angle"},
       false,
       {{"bearing_angle", 1.0}},
       "bearing pressure",
       "|Cm_bearing| up to |Cm_alpha|, bearing_angle within the record's "
       "angles",
       false,
       false,
       true},
      {"calibration_nonlinearity",
       "a pitch and yaw calibration nonlinearity (Section 5.2)",
       {"theta_cal3", "psi_cal3"},
       {"theta_cal3", "psi_cal3"},
       false,
       {},
       "amplitude",
       "up to 0.2 deg, or 3% of the angle if more, at each channel's "
       "largest angle; a term determined (over 2 standard errors) up to 3% "
       "of the angle or 3 noise sigmas where 0.2 deg is more",
       false,
       false,
       false,
       {"reading_gain", "calibration_square"},
       "calibration_signed_square"},
  };
  return catalog;
}

// A calibration error may grow as the angle's signed square rather than
// its cube (the suite's other simulator writes it so): the cube named in
// its place had left Cm_alpha 3.5-9.6 of its errors off on 3-s runs.
const std::vector<Effect>& OpenForms() {
  static const std::vector<Effect> forms = {
      {"calibration_square",
       "the calibration nonlinearity as the angle's signed square (another "
       "form of Section 5.2's)",
       {"theta_cal2", "psi_cal2"},
       {"theta_cal2", "psi_cal2"},
       false,
       {},
       "",
       ""},
      // The report's calibration factors come from a linear least-squares
      // fit, which takes a straight line's worth of any error into each
      // reading's gain: what is left of a signed square is the square less
      // its line over the calibration's range (Effect::other_form), the
      // config's or else the range the readings span (HoldCalibrationRange
      // sets cal_range, held). Freed, the range made the line a gain of any
      // size, which stood in for a bearing moment's stiffness on a pair of runs
      // (suite draw 59: a range of 17.5 +- 106 deg, Cm_alpha 34 of its errors
      // off).
      {"calibration_signed_square",
       "the calibration nonlinearity as the angle's signed square less the "
       "straight line a linear calibration over the readings' range took "
       "of it (another form of Section 5.2's)",
       {"theta_cal2", "psi_cal2"},
       {"theta_cal2", "psi_cal2"},
       false,
       {},
       "",
       ""},
  };
  return forms;
}

// The probes outside the catalog (diagnose.h): fitted and compared, never
// adopted; separated_by, when given, is the whole phrase of what would
// tell the probe from a catalog effect. A drift in time of the readings or
// of the dynamic pressure is what a short run most often shows that the
// catalog does not hold, and what a catalog effect that follows the
// amplitude (which decays in time) or the roll angle (which grows in time)
// imitates on one run. A lag of the readings (a filter's) shifts the
// phase of pitch against yaw as a tunnel damping does (one 3-s coning run
// had been called tunnel damping), and a pitch reading's gain error the
// stiffness of a bearing moment. A flow stiffer in one of the tunnel's
// planes is the simplest flow nonuniformity Eq. 39 misses (its tunnel
// moments carry a roll torque a normal force has not), and a Magnus moment
// imitates it. Dry friction in the bearing damps a small motion more than
// a large one, as a nonlinear damping with a positive Cm_q_delta2 does (one
// 3-s run had been called that); a second amplitude tells them apart. Dry
// friction about each axis alone damps the small yaw rate of a run
// pitching in one plane hard, as a tunnel damping in yaw does (3-s runs
// had been called that, the pitch term a tenth of the yaw one); about the
// pitch axis alone, on a circular cone, it is a damping of that axis alone,
// which Eq. 39's tunnel damping gives with Cm_q moved (a coning run had
// been called that on every draw of the suite). Section 5.2 found the
// reading error varying with roll "with no apparent symmetry"; the
// catalog's roll interaction keeps its first harmonics, and a reading
// error twice a revolution had been named that with a flow angularity
// beside it (two runs at 30 and 60 deg/s, on every draw of the suite).
const std::vector<Effect>& Probes() {
  static const std::vector<Effect> probes = {
      {"reading_drift",
       "a drift of the pitch and yaw readings in time (outside the catalog)",
       {"theta_drift", "psi_drift"},
       {"theta_drift", "psi_drift"},
       false,
       {},
       "",
       "",
       false,
       true},
      {"pressure_drift",
       "a dynamic pressure drifting during the run (outside the catalog)",
       {"q_drift"},
       {"q_drift"},
       false,
       {},
       "",
       "",
       false,
       true},
      {"reading_lag",
       "a lag of the pitch and yaw readings (a filter in the signal "
       "conditioning; outside the catalog)",
       {"theta_lag", "psi_lag"},
       {"theta_lag", "psi_lag"},
       false,
       {},
       "a bench test of the readings' lag (a known motion through the "
       "signal conditioning)",
       ""},
      {"reading_gain",
       "a pitch reading whose gain is off the yaw reading's (a calibration "
       "slope; outside the catalog)",
       {"theta_gain"},
       {"theta_gain"},
       false,
       {},
       "a bench calibration of the pitch and yaw readings",
       ""},
      {"flow_yaw_stiffness",
       "a flow whose stiffness differs between the tunnel's pitch and yaw "
       "planes, without Eq. 39's roll torque (outside the catalog)",
       {"Cn_beta_flow"},
       {"Cn_beta_flow"},
       false,
       {},
       "a run pitching in one plane (Eq. 39's tunnel moments drive the "
       "roll there, a normal force does not)",
       ""},
      {"bearing_friction",
       "dry (Coulomb) friction of the bearing against the pitch-yaw motion "
       "(outside the catalog)",
       {"Cm_friction"},
       {"Cm_friction"},
       false,
       {},
       "a run at another amplitude (dry friction damps a small motion more "
       "than a large one, a viscous damping does not)",
       ""},
      {"axis_friction",
       "dry (Coulomb) friction about each of the pitch and yaw axes alone "
       "(pivots turning about fixed axes, lead wires across the bearing; "
       "outside the catalog)",
       {"Cm_axis_friction"},
       {"Cm_axis_friction"},
       false,
       {},
       "a run at another amplitude (dry friction damps a small motion more "
       "than a large one, a viscous damping does not)",
       ""},
      {"pitch_friction",
       "dry (Coulomb) friction about the pitch axis alone (a gimbal's pitch "
       "pivot, lead wires rubbing as the model pitches; outside the "
       "catalog)",
       {"Cm_pitch_friction"},
       {"Cm_pitch_friction"},
       false,
       {},
       "a run at another amplitude (dry friction damps a small motion more "
       "than a large one, a viscous damping does not)",
       ""},
      {"yaw_friction",
       "dry (Coulomb) friction about the yaw axis alone (a gimbal's yaw "
       "pivot; outside the catalog)",
       {"Cn_yaw_friction"},
       {"Cn_yaw_friction"},
       false,
       {},
       "a run at another amplitude (dry friction damps a small motion more "
       "than a large one, a viscous damping does not)",
       ""},
      {"second_roll_harmonic",
       "a pitch and yaw reading error at the second harmonic of roll (twice "
       "a revolution; outside the catalog, whose roll interaction keeps the "
       "first harmonics)",
       {"theta_cos_2phi", "theta_sin_2phi", "psi_cos_2phi", "psi_sin_2phi"},
       {"theta_cos_2phi", "theta_sin_2phi", "psi_cos_2phi", "psi_sin_2phi"},
       false,
       {},
       "a bench test of the readings against roll (the model turned "
       "through a revolution at fixed pitch and yaw)",
       ""},
  };
  return probes;
}

namespace {

const Effect* FindIn(const std::vector<Effect>& effects,
                     const std::string& id) {
  for (const Effect& e : effects) {
    if (e.id == id) return &e;
  }
  return nullptr;
}

}  // namespace

const Effect* FindEffect(const std::string& id) {
  return FindIn(EffectCatalog(), id);
}

const Effect* FindProbe(const std::string& id) { return FindIn(Probes(), id); }

const Effect* FindOpenForm(const std::string& id) {
  return FindIn(OpenForms(), id);
}

const Effect* OtherForm(const Effect& effect) {
  return effect.other_form.empty() ? nullptr : FindOpenForm(effect.other_form);
}

bool OutsideCatalog(const std::string& id) {
  return id == kDriftInTime || FindProbe(id) != nullptr;
}

void RefitFromSolution(Case* c, double probable_error) {
  // Far above the noise (the fit without the effect lost the motion: a
  // missing roll damping over 48 s) the refit needs the growing windows;
  // near it, the start is close enough to trust Gauss-Newton steps.
  c->solver.continuation = probable_error > kNearSolution;
  c->solver.multi_start = false;
  c->solver.max_probable_error = 0.0;
  c->solver.from_solution = !c->solver.continuation;
  c->solver.far_start = c->solver.from_solution ? kFarStart : 0.0;
  c->solver.bic_tolerance = kSearchBicTolerance;
}

bool IsCompanion(const Effect& effect, const std::string& name) {
  return std::any_of(effect.companions.begin(),
                     effect.companions.end(),
                     [&](const auto& c) { return c.first == name; });
}

bool CandidateCase(const Case& at,
                   const Effect& effect,
                   Case* out,
                   std::vector<std::string>* added) {
  Case candidate = at;
  if (effect.to_asymmetric && at.model == ModelKind::kSymmetric) {
    try {
      candidate = ToAsymmetric(at);
    } catch (const InputError&) {
      return false;
    }
  }
  const auto& names = effect.Terms(candidate.model);
  const auto& table = ParameterTable(candidate.model);
  added->clear();
  for (const std::string& name : names) {
    const int position = FindParameter(candidate.model, name);
    if (position < 0) continue;
    ParameterSetting& p = candidate.parameters[position];
    if (p.tied()) {
      // An image whose source the effect names too keeps following it (a
      // Magnus moment in the asymmetric program frees Cm_p_beta, Cn_p_alpha
      // follows); otherwise the effect is the asymmetry itself and frees
      // the image on its own.
      const std::string& source = table[p.tied_to].name;
      if (std::find(names.begin(), names.end(), source) != names.end())
        continue;
      p.tied_to = -1;
      p.free = true;
      added->push_back(table[position].name);
      continue;
    }
    double start = 0.0;
    for (const auto& [companion, value] : effect.companions) {
      if (companion == name) start = value;
    }
    // A companion the user already set keeps its value (freed with the
    // effect); the effect's own terms must not be in the model yet.
    if (p.free || (p.value != 0.0 && start == 0.0)) continue;
    p.free = true;
    if (p.value == 0.0) p.value = start;
    p.auto_start = false;
    added->push_back(table[position].name);
  }
  // Companions alone (the effect's own terms already in the model) are no
  // candidate.
  const bool own =
      std::any_of(added->begin(), added->end(), [&](const std::string& name) {
        return !IsCompanion(effect, name);
      });
  if (!own) return false;
  *out = candidate;
  return true;
}

}  // namespace fit3dof
