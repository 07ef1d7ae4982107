// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A diagnosis written out (diagnose.h): diagnosis.json (docs/formats.md)
// and the lines printed by `fit3dof diagnose`.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

#include "diagnose_internal.h"
#include "fit3dof/diagnose.h"
#include "fit3dof/parameters.h"
#include "format.h"
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
            {"peak_over_neighbours", r.line_ratio},
            {"peak_frequency_hz", r.peak_frequency_hz}}},
          {"noise_limit", r.noise_limit},
          {"whiteness_limit", r.whiteness_limit},
          {"at_noise_level", r.at_noise_level},
          {"white", r.white},
          {"below_sigma", r.below_sigma},
          {"independent", r.independent}};
}

// name -> {value, standard_error, rms_error, units}.
json Estimates(const std::vector<ParameterEstimate>& estimates) {
  json out = json::object();
  for (const ParameterEstimate& e : estimates) {
    if (!e.segment.empty()) continue;
    out[e.name] = {{"value", e.value},
                   {"standard_error", JsonNumber(e.standard_error)},
                   {"rms_error", JsonNumber(e.rms_error)},
                   {"units", e.units},
                   {"free", e.free}};
    if (!e.tied_to.empty()) {
      out[e.name]["tied_to"] = e.tied_to;
      out[e.name]["tie_factor"] = e.tie_factor;
    }
  }
  return out;
}

json Contender(const CandidateFit& c) {
  json out = {{"effect", c.effect},
              {"parameters", Estimates(c.parameters)},
              {"bic_drop", c.bic_drop},
              {"prediction_gain", JsonNumber(c.prediction_gain)},
              {"earned_its_place", c.rejected.empty()}};
  if (!c.rejected.empty()) out["rejected"] = c.rejected;
  return out;
}

// diagnosis.json's outside_catalog_alike: the probe explaining the
// record alike beside the catalog's effects (AlikeBeside), else the first
// probe a step's effect names alike (DiagnosisStep::outside_alike) with
// the other steps' effects, which its model holds beside it.
std::vector<std::string> OutsideCatalogAlike(const Diagnosis& d) {
  if (!d.outside_catalog_alike.empty()) return d.outside_catalog_alike;
  for (const DiagnosisStep& s : d.steps) {
    if (s.outside_alike.effect.empty()) continue;
    std::vector<std::string> ids = {s.outside_alike.effect};
    for (const DiagnosisStep& other : d.steps) {
      if (&other != &s) ids.push_back(other.effect);
    }
    return ids;
  }
  return {};
}

json Contenders(const std::vector<CandidateFit>& contenders) {
  json out = json::array();
  for (const CandidateFit& c : contenders) out.push_back(Contender(c));
  return out;
}

json Step(const DiagnosisStep& s) {
  json ranking = json::array();
  for (const CandidateScore& k : s.ranking) {
    ranking.push_back(
        {{"effect", k.effect}, {"score", k.score}, {"dof", k.dof}});
  }
  json step = {{"effect", s.effect},
               {"description", s.description},
               {"parameters", Estimates(s.parameters)},
               {"step_parameters", Estimates(s.step_parameters)},
               {"statistic",
                {{"score", s.score},
                 {"bic_drop", s.bic_drop},
                 {"prediction_gain", JsonNumber(s.prediction_gain)},
                 {"ranking", ranking}}},
               {"contenders", Contenders(s.contenders)},
               {"rms_residual_deg", JsonChannels(s.after.rms_deg)},
               {"probable_error", s.after.probable_error}};
  if (!s.note.empty()) step["note"] = s.note;
  if (!s.outside_alike.effect.empty()) {
    step["outside_alike"] = Contender(s.outside_alike);
    step["outside_alike"]["bic_above_step"] = s.outside_alike_bic;
  }
  // The stepN/ directories of the fits before and after it.
  step["fits"] = {s.fit_before, s.fit_after};
  return step;
}

// "name = value +- se units, ...", a term held "name = value units (held)"
// (a probe's term held at its physical sign's bound).
std::string Values(const std::vector<ParameterEstimate>& estimates) {
  std::string values;
  for (const ParameterEstimate& e : estimates) {
    values += (values.empty() ? "" : ", ") + e.name + " = " +
              FormatNumber("%.4g", e.value) +
              (e.free ? " +- " + FormatNumber("%.2g", e.standard_error) : "") +
              " " + e.units + (e.free ? "" : " (held)");
  }
  return values;
}

// The coefficients' error bars the models the record cannot exclude (a
// tie, an effect not excluded, a term left open, a probe alike) widened at
// least twice, each with the final model's own: along Eq. 43's ridge a tunnel
// term not excluded widens Cm_alpha's or Cm_q's a hundred-fold (only their sums
// with t1, t2 are determined), which is honest but should not surprise
// the reader. Empty when none did.
std::string Widened(const Diagnosis& d) {
  constexpr double kWorthSaying = 2.0;
  const ModelKind model = d.FinalFit().model;
  std::string list;
  for (const ParameterEstimate& e : d.final_parameters) {
    const auto it = d.model_standard_errors.find(e.name);
    if (!e.segment.empty() || IsInitialCondition(model, e.position) ||
        it == d.model_standard_errors.end() ||
        !(e.standard_error >= kWorthSaying * it->second)) {
      continue;
    }
    list += std::string(list.empty() ? "" : ", ") + e.name + " +- " +
            FormatNumber("%.2g", e.standard_error) +
            " (the final model's own +- " + FormatNumber("%.2g", it->second) +
            ")";
  }
  if (list.empty()) return "";
  return "  error bars widened by the models the record cannot exclude: " +
         list +
         "; diagnosis.json's model_standard_error keeps the final model's "
         "own, to quote where those effects are known absent\n";
}

// What each coefficient a twin moves (CoefficientTwin::shifts) stands for,
// in words: "; the fitted Cm_q stands for Cm_q + 0.0325 Cm_p_alpha".
std::string Stands(const CoefficientTwin& t) {
  std::vector<std::string> order;
  std::map<std::string, std::string> sums;
  for (const TwinShift& s : t.shifts) {
    if (!sums.count(s.parameter)) {
      order.push_back(s.parameter);
      sums[s.parameter] = s.parameter;
    }
    sums[s.parameter] += (s.per_unit < 0.0 ? " - " : " + ") +
                         FormatNumber("%.3g", std::abs(s.per_unit)) + " " +
                         s.term;
  }
  std::string out;
  for (const std::string& p : order) {
    out +=
        (out.empty() ? "; the fitted " : ", ") + p + " stands for " + sums[p];
  }
  if (!out.empty() && !t.in_final_model) out += " (in the search's model)";
  return out;
}

}  // namespace

std::vector<std::vector<CandidateFit>> Ties(const Diagnosis& d) {
  std::vector<std::vector<CandidateFit>> ties;
  if (!d.ambiguous.empty()) ties.push_back(d.ambiguous);
  ties.insert(ties.end(), d.later_ties.begin(), d.later_ties.end());
  return ties;
}

std::vector<CandidateFit> Tied(const Diagnosis& d) {
  std::vector<CandidateFit> tied;
  for (const std::vector<CandidateFit>& tie : Ties(d)) {
    tied.insert(tied.end(), tie.begin(), tie.end());
  }
  return tied;
}

const CandidateFit* FindFit(const std::vector<CandidateFit>& fits,
                            const std::string& id) {
  const auto k =
      std::find_if(fits.begin(), fits.end(), [&](const CandidateFit& f) {
        return f.effect == id;
      });
  return k == fits.end() ? nullptr : &*k;
}

// Without Tied's copy: called per contender where the final error bars
// are weighed.
const std::vector<CandidateFit>* TieOf(const Diagnosis& d,
                                       const std::string& id) {
  const auto holds = [&](const std::vector<CandidateFit>& tie) {
    return FindFit(tie, id) != nullptr;
  };
  if (holds(d.ambiguous)) return &d.ambiguous;
  for (const std::vector<CandidateFit>& tie : d.later_ties) {
    if (holds(tie)) return &tie;
  }
  return nullptr;
}

bool InTie(const Diagnosis& d, const std::string& id) {
  return TieOf(d, id) != nullptr;
}

namespace {

// The nominal fit's wild points, one line each (at most kShown, then how
// many more): the search fits the samples that fit kept, so a wild point
// kept under `outliers: warn` is in every candidate's residuals, and a
// dropped one in none.
std::string WildPointLines(const Diagnosis& d) {
  constexpr size_t kShown = 5;
  if (d.fits.empty()) return "";
  const std::vector<Outlier>& outliers = d.fits[0].outliers;
  std::string out;
  for (size_t i = 0; i < outliers.size() && i < kShown; ++i) {
    const Outlier& o = outliers[i];
    out += "wild point" +
           (d.fits[0].segments.size() > 1 ? " in segment '" + o.segment + "'"
                                          : std::string()) +
           ": " + o.point.Describe() +
           (o.dropped ? "; dropped, the search fits the rest"
                      : "; kept in every fit of the search (data: {outliers: "
                        "reject} leaves it out)") +
           "\n";
  }
  if (outliers.size() > kShown) {
    out += std::to_string(outliers.size() - kShown) +
           " more wild points (diagnosis.json's outliers)\n";
  }
  return out;
}

// An added effect whose form (Effect::other_form) in the final model
// differs from its form in the model the partial steps were fitted in.
struct FormApart {
  std::string effect;
  std::string final_form;    // the effect's id or its other form's
  std::string partial_form;  // the same, in d.fits[d.partial_fit]
};

// The steps of `d` whose effect the final model holds in one form and the
// search's model with the partial steps (the tied effects, those not
// adopted) in the other: without those effects the form takes up part of
// them (on draw 95's pair of runs with a bearing moment, a cubic
// calibration error and a roll torque, the signed square before the
// bearing moment, tied with a reading-gain error, and the cube beside it).
std::vector<FormApart> FormsApart(const Diagnosis& d) {
  std::vector<FormApart> apart;
  if (d.partial.empty() || d.partial_fit >= d.fits.size()) return apart;
  const FitResult& partial = d.fits[d.partial_fit];
  for (const DiagnosisStep& s : d.steps) {
    const Effect* effect = FindEffect(s.effect);
    if (effect == nullptr || OtherForm(*effect) == nullptr) continue;
    const bool final_other = InOtherFormIn(*effect, d.FinalFit());
    if (final_other == InOtherFormIn(*effect, partial)) continue;
    const std::string& other = OtherForm(*effect)->id;
    apart.push_back({s.effect,
                     final_other ? other : s.effect,
                     final_other ? s.effect : other});
  }
  return apart;
}

// diagnosis.json's ties: ambiguous_between and its groups, what would
// separate them, the alternatives and the tie models.
void AddTies(const Diagnosis& d, json* into) {
  json& out = *into;
  // Every effect in doubt, the first tie's first, each once (a probe can
  // tie in two groups); each tie on its own in ambiguous_groups.
  const std::vector<CandidateFit> tied = Tied(d);
  std::vector<std::string> ids;
  for (const CandidateFit& a : tied) {
    if (std::find(ids.begin(), ids.end(), a.effect) == ids.end()) {
      ids.push_back(a.effect);
    }
  }
  out["ambiguous_between"] = ids;
  // The tied explanations outside the catalog: a fault to look for at the
  // bench (or in the flow), not a coefficient.
  out["ambiguous_outside_catalog"] = json::array();
  for (const std::string& effect : ids) {
    if (OutsideCatalog(effect)) {
      out["ambiguous_outside_catalog"].push_back(effect);
    }
  }
  out["ambiguous_groups"] = json::array();
  for (const std::vector<CandidateFit>& tie : Ties(d)) {
    json group = json::array();
    for (const CandidateFit& a : tie) group.push_back(a.effect);
    out["ambiguous_groups"].push_back(group);
  }
  if (!d.ambiguous.empty()) {
    out["ambiguous"] = Contenders(tied);
    out["separated_by"] = d.separated_by;
    // What would separate each group of ambiguous_groups, in its order.
    json each = json::array({d.separated_by});
    for (size_t i = 0; i < d.later_ties.size(); ++i) {
      each.push_back(i < d.later_separated_by.size() ? d.later_separated_by[i]
                                                     : std::string());
    }
    out["groups_separated_by"] = each;
  }
  out["alternatives"] = json::array();
  for (const AlternativeModel& a : d.alternatives) {
    out["alternatives"].push_back({{"effect", a.effect},
                                   {"check", Check(a.check)},
                                   {"parameters", Estimates(a.parameters)}});
  }
  out["tie_models"] = json::array();
  const auto optional = [](const std::string& s) {
    return s.empty() ? json(nullptr) : json(s);
  };
  for (const Diagnosis::TieModel* m : d.AllTieModels()) {
    out["tie_models"].push_back(
        {{"effects", m->effects},
         {"effect", m->effect},
         {"in_place_of", m->in_place_of},
         {"also_effect", optional(m->also_effect)},
         {"also_in_place_of", optional(m->also_in_place_of)},
         {"held", optional(m->held)},
         {"bic_rise", m->rise},
         {"check", Check(m->check)},
         {"parameters", Estimates(m->parameters)}});
  }
  out["tie_stand_in"] = d.stand_in.empty() ? json(nullptr) : json(d.stand_in);
  out["stood_in"] = json::array();
  for (size_t i = 0; i < d.stood_in.size(); ++i) {
    out["stood_in"].push_back(
        {{"effect", d.stood_in[i].effect}, {"for", d.stood_in_for[i]}});
  }
}

// diagnosis.json's effects in doubt beside the final model: not excluded,
// near twins, coefficient twins, outdone by a probe, refused for drag,
// open terms.
void AddDoubts(const Diagnosis& d, json* into) {
  json& out = *into;
  out["not_excluded"] = Contenders(d.not_excluded);
  out["near_twins"] = d.near_twins;
  out["coefficient_twins"] = json::array();
  for (const CoefficientTwin& t : d.coefficient_twins) {
    json moves = json::array();
    for (const TwinShift& s : t.shifts) {
      moves.push_back({{"term", s.term},
                       {"parameter", s.parameter},
                       {"per_unit", s.per_unit}});
    }
    out["coefficient_twins"].push_back({{"effect", t.score.effect},
                                        {"novelty", t.score.novelty},
                                        {"moves", moves},
                                        {"in_final_model", t.in_final_model}});
  }
  out["outdone_by_probe"] = d.outdone_by_probe;
  out["refused_for_drag"] = d.refused_for_drag;
  out["open_terms"] = Contenders(d.open_terms);
}

// diagnosis.json's explanations outside the catalog and its look-alikes.
void AddOutside(const Diagnosis& d, json* into) {
  json& out = *into;
  out["outside_catalog"] = d.outside_catalog.effect.empty()
                               ? json(nullptr)
                               : Contender(d.outside_catalog);
  out["outside_catalog_at_noise_level"] = d.outside_at_noise_level;
  out["outside_catalog_beside"] = d.outside_catalog_beside;
  out["outside_catalog_alike"] = OutsideCatalogAlike(d);
  out["catalog_alike"] = d.catalog_alike;
  out["catalog_alike_bic"] =
      d.catalog_alike.empty() ? json(nullptr) : json(d.catalog_alike_bic);
}

// diagnosis.json's models: the final parameters (with the final model's
// own errors where a tie or an effect not excluded widened them), the
// residuals before and after, the steps, partial and pruned.
void AddModels(const Diagnosis& d, const Case& c, json* into) {
  json& out = *into;
  out["final_parameters"] = Estimates(d.final_parameters);
  // Where a tie or an effect not excluded widened an error bar, the final
  // model's own error too: the one to quote if that effect is known absent
  // (a tunnel calibration, say).
  // A step's parameters are the final model's values of its terms: the
  // same widened errors, the same own error beside them.
  auto own_errors = [&](json* estimates) {
    for (const auto& [name, error] : d.model_standard_errors) {
      auto e = estimates->find(name);
      if (e != estimates->end()) {
        (*e)["model_standard_error"] = JsonNumber(error);
      }
    }
  };
  own_errors(&out["final_parameters"]);
  out["initial_rms_residual_deg"] = JsonChannels(d.initial.rms_deg);
  out["final_rms_residual_deg"] = JsonChannels(d.final.rms_deg);
  out["noise_sigma_deg"] = JsonChannels(DiagnosedNoise(d, c.sigma));
  out["initial"] = Check(d.initial);
  out["final"] = Check(d.final);
  out["steps"] = json::array();
  for (const DiagnosisStep& s : d.steps) {
    out["steps"].push_back(Step(s));
    own_errors(&out["steps"].back()["parameters"]);
  }
  out["partial"] = json::array();
  for (const DiagnosisStep& s : d.partial) out["partial"].push_back(Step(s));
  out["forms_apart"] = json::array();
  for (const FormApart& f : FormsApart(d)) {
    out["forms_apart"].push_back({{"effect", f.effect},
                                  {"final_form", f.final_form},
                                  {"partial_form", f.partial_form}});
  }
  out["pruned"] = json::array();
  for (const DiagnosisStep& s : d.pruned) out["pruned"].push_back(Step(s));
}

}  // namespace

std::string DiagnosisJson(const Diagnosis& d, const Case& c) {
  json out;
  out["name"] = c.name;
  out["verdict"] = VerdictToString(d.verdict);
  out["verdict_text"] = d.verdict_text;
  out["noise_held"] = d.noise_held;
  out["search_step"] = d.search_step;
  out["effects_known_absent"] = d.absent;
  out["effects_added"] = json::array();
  for (const DiagnosisStep& s : d.steps)
    out["effects_added"].push_back(s.effect);
  AddTies(d, &out);
  AddDoubts(d, &out);
  if (!d.residual_description.empty()) {
    out["residual_description"] = d.residual_description;
  }
  out["rejected"] = Contenders(d.rejected);
  // What the verdict reads of the record's roll (RollLockedUnconfirmed).
  const std::vector<TimeHistory> fitted =
      d.fits.empty() ? std::vector<TimeHistory>() : FittedData(d.FinalFit());
  out["roll_span_deg"] = RollSpan(fitted);
  out["roll_separates"] = RollSeparates(fitted);
  // The nominal fit's wild points: the search saw the samples it kept.
  out["outliers"] = OutliersJson(d.fits.empty() ? std::vector<Outlier>()
                                                : d.fits[0].outliers);
  AddOutside(d, &out);
  AddModels(d, c, &out);
  return out.dump(2) + "\n";
}

ChannelValues DiagnosedNoise(const Diagnosis& d, const ChannelValues& stated) {
  if (!d.noise_held || d.fits.empty() || d.fits[0].segments.empty()) {
    return stated;
  }
  return d.fits[0].segments[0].sigma_deg;  // one level for every segment
}

namespace {

// The report's lines for the effects known absent and for each step
// (added, not adopted, dropped again; forms apart), with the residual
// before and after against the noise `sigma`.
std::string StepLines(const Diagnosis& d, const ChannelValues& sigma) {
  std::string out;
  if (!d.absent.empty()) {
    std::string ids;
    for (const std::string& id : d.absent)
      ids += (ids.empty() ? "" : ", ") + id;
    out += "known absent, not tried: " + ids + "\n";
  }
  ResidualCheck before = d.initial;
  for (const DiagnosisStep& s : d.steps) {
    // The final model's values: a later step may move an earlier effect's.
    out += "missing effect: " + s.description + " (" + Values(s.parameters) +
           "); theta residual " + FormatNumber("%.3g", before.rms_deg.theta) +
           " deg -> " + FormatNumber("%.3g", s.after.rms_deg.theta) +
           " deg, psi " + FormatNumber("%.3g", before.rms_deg.psi) + " -> " +
           FormatNumber("%.3g", s.after.rms_deg.psi) + " deg (noise " +
           FormatNumber("%.3g", sigma.theta) + ", " +
           FormatNumber("%.3g", sigma.psi) + " deg)\n";
    if (!s.note.empty()) out += "  " + s.note + "\n";
    before = s.after;
  }
  for (const DiagnosisStep& s : d.partial) {
    out += "  explains part, not adopted: " + s.description + " (" +
           Values(s.parameters) + "); probable error " +
           FormatNumber("%.3g", s.after.probable_error) + "\n";
  }
  for (const DiagnosisStep& s : d.pruned) {
    out += "  dropped again: " + s.description + ": " + s.note + "\n";
  }
  std::vector<std::string> partial;  // the effects not adopted
  for (const DiagnosisStep& s : d.partial) partial.push_back(s.effect);
  for (const FormApart& f : FormsApart(d)) {
    const auto form = [&](const std::string& id) {
      return id == f.effect ? std::string("in its own form") : "as " + id;
    };
    out += "  form: " + f.effect + " " + form(f.final_form) +
           " in the final model, " + form(f.partial_form) + " beside " +
           Joined(partial, " and ") +
           " (not adopted): in the final model its form takes up part of "
           "what the effects not adopted explain\n";
  }
  return out;
}

// The report's lines for the tied candidates, the stand-ins, the
// complete models and the models that keep a tie open.
std::string TieLines(const Diagnosis& d) {
  std::string out;
  for (const CandidateFit& a : Tied(d)) {
    // drift_in_time, a roll-locked effect's rival, has no fit to quote.
    out += "  candidate: " + a.effect +
           (a.parameters.empty()
                ? std::string(" (outside the catalog, not fitted)")
                : " (" + Values(a.parameters) + "), BIC lower by " +
                      FormatNumber("%.1f", a.bic_drop)) +
           "\n";
  }
  if (!d.stand_in.empty()) {
    out += "  the final model holds " + d.stand_in +
           " in the tie's place (the effects added need one of the tied "
           "effects); its error bars cover each complete model\n";
  }
  for (size_t i = 0; i < d.stood_in.size(); ++i) {
    std::string set;
    for (const std::string& id : d.stood_in_for[i]) {
      set += (set.empty() ? "" : " + ") + id;
    }
    out += "  the final model holds " + d.stood_in[i].effect +
           " in the place of " + set +
           (d.stood_in_for[i].size() > 1 ? " together" : "") +
           " (not claimed); its error bars cover that model\n";
  }
  for (const AlternativeModel& a : d.alternatives) {
    out += "  complete model with " + a.effect + ": probable error " +
           FormatNumber("%.3g", a.check.probable_error) +
           (a.check.at_noise_level ? ", at the noise level\n"
                                   : ", residuals structured\n");
  }
  for (const Diagnosis::TieModel* m : d.AllTieModels()) {
    const std::string swapped =
        (m->also_effect.empty()
             ? ""
             : m->also_effect + " in place of " + m->also_in_place_of + ", ") +
        m->effect + " in place of " + m->in_place_of;
    out += std::string(m->also_effect.empty() ? "  model that keeps a tie"
                                              : "  model that keeps two ties") +
           " open: " + Joined(m->effects, " and ") + " (" + swapped +
           "): BIC " + FormatNumber("%+.1f", m->rise) + ", probable error " +
           FormatNumber("%.3g", m->check.probable_error) + "\n";
  }
  return out;
}

// The report's lines for the explanation outside the catalog and those
// beside it.
std::string OutsideLines(const Diagnosis& d) {
  std::string out;
  if (!d.outside_catalog.effect.empty()) {
    out += "  outside the catalog, not adopted: " + d.outside_catalog.effect +
           " (" + Values(d.outside_catalog.parameters) + "), BIC lower by " +
           FormatNumber("%.1f", d.outside_catalog.bic_drop) +
           (d.outside_at_noise_level ? "; residuals at the noise level with it"
                                     : "") +
           "\n";
  }
  if (!d.outside_catalog_beside.empty()) {
    std::string beside;
    for (const std::string& id : d.outside_catalog_beside) {
      beside += (beside.empty() ? "" : ", ") + id;
    }
    out +=
        "  beside it, these explain the record (not adopted): " + beside + "\n";
  }
  return out;
}

// The report's lines for the effects not excluded, the terms left open,
// the coefficients' twins and the effects not added.
std::string DoubtLines(const Diagnosis& d) {
  std::string out;
  for (const CandidateFit& k : d.not_excluded) {
    out += "  not excluded, the final error bars cover it: " + k.effect + " (" +
           Values(k.parameters) + "): " + k.rejected + "\n";
  }
  for (const CandidateFit& k : d.open_terms) {
    out += "  left open, the final error bars cover it: " + k.effect + " (" +
           Values(k.parameters) + "): " + k.rejected + "\n";
  }
  for (const CoefficientTwin& t : d.coefficient_twins) {
    out += "  not seen apart from the fitted coefficients: " + t.score.effect +
           " (" + FormatNumber("%.2g", 100.0 * t.score.novelty) +
           "% of its information its own on this record): had it been "
           "present, the coefficients carry it and their error bars do not "
           "cover it" +
           Stands(t) + "\n";
  }
  for (const CandidateFit& r : d.rejected) {
    out += "  not added: " + r.effect + " (" + Values(r.parameters) +
           "): " + r.rejected + "\n";
  }
  return out;
}

}  // namespace

std::string FormatDiagnosis(const Diagnosis& d, const ChannelValues& sigma) {
  std::string out = WildPointLines(d);
  out += StepLines(d, sigma);
  out += TieLines(d);
  out += OutsideLines(d);
  out += DoubtLines(d);
  out += "verdict: " + d.verdict_text + "\n";
  out += Widened(d);
  if (!d.residual_description.empty()) {
    out += "  " + d.residual_description + "\n";
  }
  return out;
}

}  // namespace fit3dof
