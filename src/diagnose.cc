// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/diagnose.h"

#include <glog/logging.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "fit3dof/config.h"
#include "fit3dof/input_error.h"
#include "json_values.h"

namespace fit3dof {
namespace {

using nlohmann::json;

// Pseudo-inverse of a symmetric positive semi-definite matrix, dropping
// directions below `relative` of the largest eigenvalue; `rank` receives
// the number kept.
Eigen::MatrixXd PseudoInverse(const Eigen::MatrixXd& m,
                              double relative,
                              int* rank) {
  if (m.rows() == 0) {
    if (rank) *rank = 0;
    return m;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(m);
  const Eigen::VectorXd lambda = eigen.eigenvalues();
  const double limit = relative * std::max(lambda.maxCoeff(), 0.0);
  Eigen::MatrixXd inverse = Eigen::MatrixXd::Zero(m.rows(), m.cols());
  int kept = 0;
  for (int j = 0; j < lambda.size(); ++j) {
    if (lambda(j) > limit && lambda(j) > 0.0) {
      const Eigen::VectorXd v = eigen.eigenvectors().col(j);
      inverse += v * v.transpose() / lambda(j);
      ++kept;
    }
  }
  if (rank) *rank = kept;
  return inverse;
}

// The case with the effect's parameters free at zero; false when the
// effect does not apply or is already in the model.
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

// The score (Lagrange-multiplier) statistic of the candidate's added
// parameters at the current solution.
CandidateScore Score(const Case& candidate,
                     const std::vector<std::string>& added,
                     const std::string& id,
                     const std::vector<TimeHistory>& data) {
  CandidateScore score;
  score.effect = id;
  Linearization l;
  if (!Linearize(candidate, data, &l)) return score;
  std::vector<int> c_index, f_index;
  const auto& table = ParameterTable(candidate.model);
  for (size_t g = 0; g < l.names.size(); ++g) {
    const bool is_added =
        l.segments[g] < 0 &&
        std::find(added.begin(), added.end(), table[l.positions[g]].name) !=
            added.end();
    (is_added ? c_index : f_index).push_back(static_cast<int>(g));
  }
  auto block = [&](const std::vector<int>& rows, const std::vector<int>& cols) {
    Eigen::MatrixXd m(rows.size(), cols.size());
    for (size_t i = 0; i < rows.size(); ++i) {
      for (size_t j = 0; j < cols.size(); ++j)
        m(i, j) = l.jtj(rows[i], cols[j]);
    }
    return m;
  };
  auto part = [&](const std::vector<int>& rows) {
    Eigen::VectorXd v(rows.size());
    for (size_t i = 0; i < rows.size(); ++i) v(i) = l.jtr(rows[i]);
    return v;
  };
  if (c_index.empty()) return score;
  const Eigen::MatrixXd iff = block(f_index, f_index);
  const Eigen::MatrixXd icf = block(c_index, f_index);
  const Eigen::MatrixXd icc = block(c_index, c_index);
  const Eigen::MatrixXd iff_inverse = PseudoInverse(iff, 1e-14, nullptr);
  const Eigen::MatrixXd schur = icc - icf * iff_inverse * icf.transpose();
  const Eigen::VectorXd g = part(c_index) - icf * iff_inverse * part(f_index);
  int rank = 0;
  // Directions the parameters already free span (Eq. 43) carry no new
  // information: they drop out here.
  const double own = icc.diagonal().maxCoeff();
  Eigen::MatrixXd schur_scaled = schur / std::max(own, 1e-300);
  const Eigen::MatrixXd inverse =
      PseudoInverse(schur_scaled, 1e-6, &rank) / std::max(own, 1e-300);
  const int dof = 3 * l.points - static_cast<int>(f_index.size());
  const double variance = l.ressum / std::max(dof, 1);
  score.score = g.dot(inverse * g) / variance;
  score.dof = rank;
  return score;
}

double Bic(const FitResult& r) {
  const double n = 3.0 * r.points;
  const double rss = std::max(r.sum_of_residuals * r.sum_of_residuals, 1e-300);
  return n * std::log(rss / n) + r.free_parameters * std::log(n);
}

json Check(const ResidualCheck& r) {
  return {{"probable_error", r.probable_error},
          {"rms_residual_deg", JsonChannels(r.rms_deg)},
          {"lag1_autocorrelation", JsonChannels(r.lag1)},
          {"spectrum",
           {{"peak_over_mean", r.peak_ratio},
            {"peak_frequency_hz", r.peak_frequency_hz}}},
          {"at_noise_level", r.at_noise_level}};
}

}  // namespace

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

ResidualCheck CheckResiduals(const FitResult& fit,
                             const DiagnoseOptions& options) {
  ResidualCheck check;
  check.probable_error = fit.probable_error;
  check.rms_deg = fit.rms_residual_deg;
  double lag[3] = {0, 0, 0};
  for (int ch = 0; ch < 3; ++ch) {
    double num = 0.0, den = 0.0;
    for (const SegmentFit& s : fit.segments) {
      const std::vector<double>* measured[3] = {
          &s.data.phi, &s.data.theta, &s.data.psi};
      std::vector<double> r(s.data.size());
      double mean = 0.0;
      for (int i = 0; i < s.data.size(); ++i) {
        r[i] = s.computed[3 * i + ch] - (*measured[ch])[i];
        mean += r[i] / s.data.size();
      }
      for (int i = 0; i + 1 < s.data.size(); ++i)
        num += (r[i] - mean) * (r[i + 1] - mean);
      for (int i = 0; i < s.data.size(); ++i)
        den += (r[i] - mean) * (r[i] - mean);
    }
    lag[ch] = den > 0.0 ? num / den : 0.0;
  }
  check.lag1 = {lag[0], lag[1], lag[2]};
  // Periodogram of theta + i psi residuals over the first segment.
  double spectral_limit = 1e300;
  if (!fit.segments.empty() && fit.segments[0].data.size() >= 16) {
    const SegmentFit& s = fit.segments[0];
    const int n = s.data.size();
    std::vector<std::complex<double>> z(n);
    std::complex<double> mean(0.0, 0.0);
    for (int i = 0; i < n; ++i) {
      z[i] = {s.computed[3 * i + 1] - s.data.theta[i],
              s.computed[3 * i + 2] - s.data.psi[i]};
      mean += z[i] / static_cast<double>(n);
    }
    double total = 0.0, peak = 0.0;
    int peak_k = 0;
    for (int k = 1; k < n; ++k) {  // the mean (k = 0) is not a line
      std::complex<double> sum(0.0, 0.0);
      for (int i = 0; i < n; ++i) {
        sum += (z[i] - mean) * std::polar(1.0, -2.0 * M_PI * k * i / n);
      }
      const double power = std::norm(sum);
      total += power;
      if (power > peak) {
        peak = power;
        peak_k = k;
      }
    }
    check.peak_ratio = total > 0.0 ? peak / (total / (n - 1)) : 0.0;
    const double duration = s.data.t.back() - s.data.t.front();
    const int signed_k = peak_k <= n / 2 ? peak_k : peak_k - n;
    check.peak_frequency_hz = signed_k * (n - 1) / (n * duration);
    spectral_limit = options.spectral_factor * std::log(static_cast<double>(n));
  }
  const double worst =
      std::max({std::abs(lag[0]), std::abs(lag[1]), std::abs(lag[2])});
  check.at_noise_level = fit.probable_error < options.noise_limit &&
                         worst < options.whiteness_limit &&
                         check.peak_ratio < spectral_limit;
  return check;
}

Diagnosis Diagnose(const Case& c, const DiagnoseOptions& options) {
  Diagnosis d;
  Case current = c;
  FitResult fit = Fit(current);
  d.fits.push_back(fit);
  d.initial = CheckResiduals(fit, options);
  ResidualCheck check = d.initial;
  for (int step = 0; step < options.max_steps && !check.at_noise_level;
       ++step) {
    const Case at = CaseAtSolution(current, fit);
    // The samples the fit used (selected, noise added, wild points
    // screened): read once, not once per candidate.
    std::vector<TimeHistory> data;
    for (const SegmentFit& segment : fit.segments) data.push_back(segment.data);
    struct Candidate {
      const Effect* effect;
      Case c;
      std::vector<std::string> added;
      CandidateScore score;
    };
    std::vector<Candidate> candidates;
    for (const Effect& e : EffectCatalog()) {
      if (!options.effects.empty() &&
          std::find(options.effects.begin(), options.effects.end(), e.id) ==
              options.effects.end()) {
        continue;
      }
      Candidate k{&e, Case(), {}, {}};
      if (!CandidateCase(at, e, &k.c, &k.added)) continue;
      k.score = Score(k.c, k.added, e.id, data);
      if (k.score.dof > 0) candidates.push_back(std::move(k));
    }
    std::sort(candidates.begin(),
              candidates.end(),
              [](const Candidate& a, const Candidate& b) {
                return a.score.score > b.score.score;
              });
    DiagnosisStep record;
    for (const Candidate& k : candidates) record.ranking.push_back(k.score);
    const double bic_now = Bic(fit);
    int best = -1;
    double best_bic = bic_now;
    FitResult best_fit;
    for (int i = 0; i < std::min<int>(options.refit, candidates.size()); ++i) {
      FitResult r;
      try {
        r = Fit(candidates[i].c);
      } catch (const std::exception& e) {
        LOG(WARNING) << c.name << ": refit with " << candidates[i].effect->id
                     << " failed: " << e.what();
        continue;
      }
      const double bic = Bic(r);
      VLOG(1) << c.name << ": " << candidates[i].effect->id << " score "
              << candidates[i].score.score << ", BIC " << bic_now << " -> "
              << bic;
      if (bic < best_bic) {
        best_bic = bic;
        best = i;
        best_fit = r;
      }
    }
    if (best < 0 || bic_now - best_bic < options.min_bic_drop) break;
    const Candidate& chosen = candidates[best];
    record.effect = chosen.effect->id;
    record.description = chosen.effect->description;
    record.score = chosen.score.score;
    record.bic_drop = bic_now - best_bic;
    for (const ParameterEstimate& e : best_fit.parameters) {
      if (std::find(chosen.added.begin(), chosen.added.end(), e.name) !=
          chosen.added.end()) {
        record.parameters.push_back(e);
      }
    }
    current = chosen.c;
    fit = best_fit;
    d.fits.push_back(fit);
    check = CheckResiduals(fit, options);
    record.after = check;
    d.steps.push_back(record);
  }
  d.final = check;
  d.final_case = CaseAtSolution(current, fit);
  // final.yaml reruns the fit: keep the user's solver settings and IC mode.
  d.final_case.solver = c.solver;
  for (size_t s = 0; s < d.final_case.segments.size() && s < c.segments.size();
       ++s) {
    d.final_case.segments[s].initial_conditions =
        c.segments[s].initial_conditions;
  }
  char verdict[256];
  if (check.at_noise_level) {
    std::snprintf(verdict, sizeof(verdict), "residuals at noise level");
  } else {
    std::snprintf(
        verdict,
        sizeof(verdict),
        "residuals remain above the noise level (probable error %.3g, "
        "lag-1 autocorrelation theta %.2f psi %.2f) and no catalog "
        "effect explains them significantly",
        check.probable_error,
        check.lag1.theta,
        check.lag1.psi);
  }
  d.verdict = verdict;
  return d;
}

std::string DiagnosisJson(const Diagnosis& d, const Case& c) {
  json out;
  out["name"] = c.name;
  out["initial_rms_residual_deg"] = JsonChannels(d.initial.rms_deg);
  out["final_rms_residual_deg"] = JsonChannels(d.final.rms_deg);
  out["noise_sigma_deg"] = JsonChannels(c.sigma);
  out["initial"] = Check(d.initial);
  out["final"] = Check(d.final);
  out["steps"] = json::array();
  for (const DiagnosisStep& s : d.steps) {
    json parameters = json::object();
    for (const ParameterEstimate& e : s.parameters) {
      parameters[e.name] = {{"value", e.value},
                            {"rms_error", JsonNumber(e.rms_error)},
                            {"units", e.units}};
    }
    json ranking = json::array();
    for (const CandidateScore& k : s.ranking) {
      ranking.push_back(
          {{"effect", k.effect}, {"score", k.score}, {"dof", k.dof}});
    }
    out["steps"].push_back(
        {{"effect", s.effect},
         {"description", s.description},
         {"parameters", parameters},
         {"statistic",
          {{"score", s.score}, {"bic_drop", s.bic_drop}, {"ranking", ranking}}},
         {"rms_residual_deg", JsonChannels(s.after.rms_deg)},
         {"probable_error", s.after.probable_error}});
  }
  out["verdict"] = d.verdict;
  return out.dump(2) + "\n";
}

std::string FormatDiagnosis(const Diagnosis& d, const ChannelValues& sigma) {
  std::string out;
  char line[512];
  ResidualCheck before = d.initial;
  for (const DiagnosisStep& s : d.steps) {
    std::string values;
    for (const ParameterEstimate& e : s.parameters) {
      char v[128];
      std::snprintf(v,
                    sizeof(v),
                    "%s%s = %.4g +- %.2g %s",
                    values.empty() ? "" : ", ",
                    e.name.c_str(),
                    e.value,
                    e.rms_error,
                    e.units.c_str());
      values += v;
    }
    std::snprintf(
        line,
        sizeof(line),
        "missing effect: %s (%s); theta residual %.3g deg -> %.3g deg, psi "
        "%.3g -> %.3g deg (noise %.3g, %.3g deg)\n",
        s.description.c_str(),
        values.c_str(),
        before.rms_deg.theta,
        s.after.rms_deg.theta,
        before.rms_deg.psi,
        s.after.rms_deg.psi,
        sigma.theta,
        sigma.psi);
    out += line;
    before = s.after;
  }
  out += "verdict: " + d.verdict + "\n";
  return out;
}

}  // namespace fit3dof
