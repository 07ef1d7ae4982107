// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The effects diagnose can add (diagnose.h), and the candidate case of
// each.

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
       {"t1", "t3"},
       {"t1", "t3"},
       false},
      {"tunnel_damping",
       "tunnel-fixed pitch and yaw damping (Eq. 39)",
       {"t2", "t4"},
       {"t2", "t4"},
       false},
      {"flow_angularity",
       "flow angularity / zero offsets in pitch and yaw",
       {"theta_T", "psi_T"},
       {"theta_T", "psi_T"},
       false},
      {"product_of_inertia",
       "a product of inertia I_zx (asymmetric program)",
       {},
       {"Izx"},
       true},
      {"roll_torque",
       "a roll torque from the gas bearing (Cl_0)",
       {"Cl_0"},
       {"Cl_0"},
       false},
      {"magnus",
       "a Magnus moment",
       {"Cm_p_alpha"},
       {"Cm_p_beta", "Cn_p_alpha"},
       false},
      {"nonlinear_stiffness",
       "nonlinear (cubic) static stiffness",
       {"Cm_alpha_delta", "Cm_alpha_delta2"},
       {"Cm_alpha3", "Cn_beta3"},
       false},
      {"nonlinear_damping",
       "nonlinear pitch and yaw damping",
       {"Cm_q_delta", "Cm_q_delta2"},
       {"Cm_q_alpha2", "Cn_r_beta2"},
       false},
      {"roll_damping", "roll damping (Cl_p)", {"Cl_p"}, {"Cl_p"}, false},
      {"trim_moment",
       "trim moments in pitch and yaw (Cm_0, Cn_0)",
       {},
       {"Cm_0", "Cn_0"},
       false},
      {"roll_interaction",
       "a pitch and yaw reading error that varies with roll (Section 5.2)",
       {"theta_cos_phi", "theta_sin_phi", "psi_cos_phi", "psi_sin_phi"},
       {"theta_cos_phi", "theta_sin_phi", "psi_cos_phi", "psi_sin_phi"},
       false},
  };
  return catalog;
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
  const auto& names = candidate.model == ModelKind::kSymmetric
                          ? effect.symmetric
                          : effect.asymmetric;
  added->clear();
  for (const std::string& name : names) {
    const int position = FindParameter(candidate.model, name);
    if (position < 0) continue;
    ParameterSetting& p = candidate.parameters[position];
    if (p.free || p.value != 0.0) continue;
    p.free = true;
    p.value = 0.0;
    p.auto_start = false;
    added->push_back(ParameterTable(candidate.model)[position].name);
  }
  if (added->empty()) return false;
  // Refits start at the current solution: no multi-start, and the
  // diagnosis judges the residual level itself.
  candidate.solver.multi_start = false;
  candidate.solver.max_probable_error = 0.0;
  *out = candidate;
  return true;
}

}  // namespace fit3dof
