// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A diagnosis written out (diagnose.h): diagnosis.json and the lines
// printed by `fit3dof diagnose`.

#include <cstdio>
#include <nlohmann/json.hpp>

#include "fit3dof/diagnose.h"
#include "json_values.h"

namespace fit3dof {
namespace {

using nlohmann::json;

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
