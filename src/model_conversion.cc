// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The symmetric program's case as the asymmetric program's
// (model_conversion.h).

#include "fit3dof/model_conversion.h"

#include <array>
#include <cmath>
#include <string>

#include "fit3dof/input_error.h"
#include "fit3dof/parameters.h"

namespace fit3dof {

const std::vector<CoefficientImage>& SymmetricImages() {
  // alpha (C1 + C5 delta^2) -> Cm_alpha alpha + C5 (alpha^3 + alpha beta^2);
  // -beta (C1 + C5 delta^2) -> Cn_beta beta + Cn_beta3 beta^3 + ...;
  // q (C2 + C6 delta^2), r (C2 + C6 delta^2); Magnus p beta C4 in pitch,
  // p alpha C4 in yaw.
  static const std::vector<CoefficientImage> images = {
      {"Cm_alpha", "Cm_alpha", 1.0},
      {"Cm_alpha", "Cn_beta", -1.0},
      {"Cm_alpha_delta2", "Cm_alpha3", 1.0},
      {"Cm_alpha_delta2", "Cm_alpha_beta2", 1.0},
      {"Cm_alpha_delta2", "Cn_beta3", -1.0},
      {"Cm_alpha_delta2", "Cn_alpha2_beta", -1.0},
      {"Cm_q", "Cm_q", 1.0},
      {"Cm_q", "Cn_r", 1.0},
      {"Cm_q_delta2", "Cm_q_alpha2", 1.0},
      {"Cm_q_delta2", "Cm_q_beta2", 1.0},
      {"Cm_q_delta2", "Cn_r_alpha2", 1.0},
      {"Cm_q_delta2", "Cn_r_beta2", 1.0},
      {"Cm_p_alpha", "Cm_p_beta", 1.0},
      {"Cm_p_alpha", "Cn_p_alpha", 1.0},
      {"Cl_0", "Cl_0", 1.0},
      {"Cl_p", "Cl_p", 1.0},
      {"Cl_p_delta2", "Cl_p_alpha2", 1.0},
      {"Cl_p_delta2", "Cl_p_beta2", 1.0},
      {"t1", "t1", 1.0},
      {"t2", "t2", 1.0},
      {"t3", "t3", 1.0},
      {"t4", "t4", 1.0},
      {"theta_T", "theta_T", 1.0},
      {"psi_T", "psi_T", 1.0},
      {"theta_cos_phi", "theta_cos_phi", 1.0},
      {"theta_sin_phi", "theta_sin_phi", 1.0},
      {"psi_cos_phi", "psi_cos_phi", 1.0},
      {"psi_sin_phi", "psi_sin_phi", 1.0},
      {"Cm_0", "Cm_0", 1.0},
      {"Cn_0", "Cn_0", 1.0},
      {"Cm_bearing", "Cm_bearing", 1.0},
      {"bearing_angle", "bearing_angle", 1.0},
      {"theta_cal3", "theta_cal3", 1.0},
      {"psi_cal3", "psi_cal3", 1.0},
      {"theta_drift", "theta_drift", 1.0},
      {"psi_drift", "psi_drift", 1.0},
      {"q_drift", "q_drift", 1.0},
      {"Cn_beta_flow", "Cn_beta_flow", 1.0},
      {"theta_lag", "theta_lag", 1.0},
      {"psi_lag", "psi_lag", 1.0},
      {"theta_gain", "theta_gain", 1.0},
      {"Cm_friction", "Cm_friction", 1.0},
      {"Cm_axis_friction", "Cm_axis_friction", 1.0},
      {"Cm_pitch_friction", "Cm_pitch_friction", 1.0},
      {"Cn_yaw_friction", "Cn_yaw_friction", 1.0},
      {"theta_cos_2phi", "theta_cos_2phi", 1.0},
      {"theta_sin_2phi", "theta_sin_2phi", 1.0},
      {"psi_cos_2phi", "psi_cos_2phi", 1.0},
      {"psi_sin_2phi", "psi_sin_2phi", 1.0},
      {"theta_cal2", "theta_cal2", 1.0},
      {"psi_cal2", "psi_cal2", 1.0},
      {"cal_range", "cal_range", 1.0},
  };
  return images;
}

const std::vector<const char*>& SymmetricWithoutImage() {
  static const std::vector<const char*> names = {"Cm_alpha_delta",
                                                 "Cm_q_beta2",
                                                 "Cm_r_alpha_beta",
                                                 "Cm_q_delta",
                                                 "Cl_p_delta",
                                                 "Cm_p_alpha_delta2",
                                                 "Cm_alphadot"};
  return names;
}

namespace {

// Initial conditions in the symmetric order (phi, phidot, theta, thetadot,
// psi, psidot) as the asymmetric program's (phi, theta, psi, p, q, r), each
// with the flags of the symmetric entry it comes from.
std::array<ParameterSetting, 6> ToBodyRates(
    const std::array<ParameterSetting, 6>& in) {
  const double phi = in[0].value, phidot = in[1].value, theta = in[2].value,
               thetadot = in[3].value, psi = in[4].value, psidot = in[5].value;
  double values[6] = {phi, theta, psi, 0.0, 0.0, 0.0};
  EulerToBodyRates(std::sin(phi * kDegree),
                   std::cos(phi * kDegree),
                   std::sin(theta * kDegree),
                   std::cos(theta * kDegree),
                   phidot,
                   thetadot,
                   psidot,
                   &values[3],
                   &values[4],
                   &values[5]);
  const int order[6] = {0, 2, 4, 1, 3, 5};
  std::array<ParameterSetting, 6> out;
  for (int j = 0; j < 6; ++j) {
    out[j] = in[order[j]];
    out[j].value = values[j];
  }
  return out;
}

// The inverse of ToBodyRates: the asymmetric program's (phi, theta, psi,
// p, q, r) in the symmetric order with Euler rates, each with the flags
// of the asymmetric entry it comes from.
std::array<ParameterSetting, 6> ToEulerRates(
    const std::array<ParameterSetting, 6>& in) {
  const double phi = in[0].value, theta = in[1].value, psi = in[2].value;
  double values[6] = {phi, 0.0, theta, 0.0, psi, 0.0};
  BodyToEulerRates(std::sin(phi * kDegree),
                   std::cos(phi * kDegree),
                   std::sin(theta * kDegree),
                   std::cos(theta * kDegree),
                   in[3].value,
                   in[4].value,
                   in[5].value,
                   &values[1],
                   &values[3],
                   &values[5]);
  const int order[6] = {0, 2, 4, 1, 3, 5};
  std::array<ParameterSetting, 6> out;
  for (int j = 0; j < 6; ++j) {
    out[order[j]] = in[j];
    out[order[j]].value = values[order[j]];
  }
  return out;
}

// Throws unless the asymmetric case `a`'s coefficient at `position` is
// what ToAsymmetric makes of an axisymmetric body's: `expected` (Tied to
// the first image, the first image's own setting, or zero and fixed), as
// `what` says.
void CheckAxisymmetric(const Case& a,
                       int position,
                       bool expected,
                       const std::string& what) {
  if (expected) return;
  throw InputError(a.source + ": " +
                   ParameterTable(ModelKind::kAsymmetric)[position].name +
                   " is not an axisymmetric body's (expected " + what +
                   "): no case of the symmetric program");
}

}  // namespace

const CoefficientImage* FirstImage(const std::string& symmetric) {
  for (const CoefficientImage& image : SymmetricImages()) {
    if (symmetric == image.symmetric) return &image;
  }
  return nullptr;
}

std::vector<ImagePosition> ImagesIn(ModelKind to,
                                    ModelKind from,
                                    const std::string& name) {
  // By position: a name may be an alias (t1 for tunnel_Cm_theta).
  const int position = FindParameter(from, name);
  if (position < 0) return {};
  if (to == from) return {{position, 1.0}};
  const bool symmetric = from == ModelKind::kSymmetric;
  std::vector<ImagePosition> images;
  for (const CoefficientImage& image : SymmetricImages()) {
    if (symmetric && FindParameter(from, image.symmetric) == position) {
      images.push_back({FindParameter(to, image.asymmetric), image.sign});
    } else if (!symmetric &&
               FindParameter(from, image.asymmetric) == position &&
               FirstImage(image.symmetric) == &image) {
      images.push_back({FindParameter(to, image.symmetric), 1.0 / image.sign});
    }
  }
  return images;
}

bool SymmetricTie(const std::string& name, ParameterTie* tie) {
  for (const CoefficientImage& image : SymmetricImages()) {
    if (name != image.asymmetric) continue;
    const CoefficientImage* first = FirstImage(image.symmetric);
    if (first == &image) return false;
    tie->image = FindParameter(ModelKind::kAsymmetric, image.asymmetric);
    tie->source = FindParameter(ModelKind::kAsymmetric, first->asymmetric);
    tie->factor = image.sign / first->sign;
    return true;
  }
  return false;
}

Case ToAsymmetric(const Case& c) {
  if (c.model == ModelKind::kAsymmetric) return c;
  Case a = c;
  a.model = ModelKind::kAsymmetric;
  a.body.Iz = c.body.Iy;
  a.parameters.assign(NumParameters(ModelKind::kAsymmetric),
                      ParameterSetting{});
  auto from = [&](const char* name) -> const ParameterSetting& {
    return c.parameters[FindParameter(ModelKind::kSymmetric, name)];
  };
  for (const char* name : SymmetricWithoutImage()) {
    const ParameterSetting& p = from(name);
    if (p.value != 0.0 || p.free) {
      throw InputError(c.source + ": " + name +
                       " has no image in the asymmetric program");
    }
  }
  // The first image of each symmetric term takes its setting; the others
  // are tied to it, so the asymmetric case fits no more parameters than
  // the symmetric one and keeps the body axisymmetric.
  for (const CoefficientImage& image : SymmetricImages()) {
    ParameterSetting q = from(image.symmetric);
    q.value = image.sign * q.value;
    ParameterTie tie;
    if (SymmetricTie(image.asymmetric, &tie)) q = ParameterSetting::Tied(tie);
    a.parameters[FindParameter(ModelKind::kAsymmetric, image.asymmetric)] = q;
  }
  a.SettleTies();
  const int sym_first = Layout(ModelKind::kSymmetric).first_initial;
  const int asym_first = Layout(ModelKind::kAsymmetric).first_initial;
  std::array<ParameterSetting, 6> defaults;
  for (int j = 0; j < 6; ++j) defaults[j] = c.parameters[sym_first + j];
  const auto converted = ToBodyRates(defaults);
  for (int j = 0; j < 6; ++j) a.parameters[asym_first + j] = converted[j];
  for (Segment& s : a.segments) s.initial = ToBodyRates(s.initial);
  return a;
}

Case ToSymmetric(const Case& a) {
  if (a.model == ModelKind::kSymmetric) return a;
  if (a.body.Iz != a.body.Iy) {
    throw InputError(a.source +
                     ": I_z differs from I_y: not an axisymmetric "
                     "body, no case of the symmetric program");
  }
  Case s = a;
  s.model = ModelKind::kSymmetric;
  s.parameters.assign(NumParameters(ModelKind::kSymmetric), ParameterSetting{});
  const int asym_first = Layout(ModelKind::kAsymmetric).first_initial;
  std::vector<bool> imaged(a.parameters.size(), false);
  for (const CoefficientImage& image : SymmetricImages()) {
    const int position =
        FindParameter(ModelKind::kAsymmetric, image.asymmetric);
    const ParameterSetting& p = a.parameters[position];
    imaged[position] = true;
    ParameterTie tie;
    if (SymmetricTie(image.asymmetric, &tie)) {
      CheckAxisymmetric(
          a,
          position,
          p.tied_to == tie.source && p.tie_factor == tie.factor,
          "tied to " + ParameterTable(ModelKind::kAsymmetric)[tie.source].name);
      continue;
    }
    CheckAxisymmetric(a, position, !p.tied(), "untied, as a first image");
    ParameterSetting q = p;
    q.value = p.value / image.sign;
    s.parameters[FindParameter(ModelKind::kSymmetric, image.symmetric)] = q;
  }
  for (int i = 0; i < static_cast<int>(a.parameters.size()); ++i) {
    const ParameterSetting& p = a.parameters[i];
    const bool initial = i >= asym_first && i < asym_first + 6;
    CheckAxisymmetric(
        a,
        i,
        initial || imaged[i] || (!p.free && !p.tied() && p.value == 0.0),
        "zero and fixed");
  }
  const int sym_first = Layout(ModelKind::kSymmetric).first_initial;
  std::array<ParameterSetting, 6> defaults;
  for (int j = 0; j < 6; ++j) defaults[j] = a.parameters[asym_first + j];
  const auto converted = ToEulerRates(defaults);
  for (int j = 0; j < 6; ++j) s.parameters[sym_first + j] = converted[j];
  for (Segment& segment : s.segments) {
    segment.initial = ToEulerRates(segment.initial);
  }
  s.SettleTies();
  return s;
}

}  // namespace fit3dof
