// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The verdict of a diagnosis (diagnose.h) and the words that give it:
// what the search found (diagnose.cc) told as `ambiguous`, `explained`,
// `noise_level` or `not_explained`, with the effects' descriptions.

#include <glog/logging.h>

#include <algorithm>
#include <string>
#include <vector>

#include "diagnose_internal.h"
#include "diagnose_search.h"
#include "fit3dof/diagnose.h"
#include "format.h"

namespace fit3dof {

std::string Joined(const std::vector<std::string>& items, const char* last) {
  std::string text;
  for (size_t i = 0; i < items.size(); ++i) {
    text += (i == 0 ? "" : i + 1 == items.size() ? last : ", ") + items[i];
  }
  return text;
}

namespace {

// "A, B or C" for the tie's effects, and "x, y and z", their BIC drops; for
// a step that a set replaces alike (Diagnosis::stood_in), "A, or B and C
// together".
void TieWords(const Diagnosis& d,
              const std::vector<CandidateFit>& tie,
              std::string* effects,
              std::string* drops) {
  std::vector<std::string> names, bic;
  for (const CandidateFit& k : tie) {
    names.push_back(Describe(k.effect));
    bic.push_back(k.effect == kDriftInTime ? "not fitted"
                                           : FormatNumber("%.1f", k.bic_drop));
  }
  *drops = Joined(bic, " and ");
  const bool set = std::any_of(
      d.stood_in.begin(), d.stood_in.end(), [&](const DiagnosisStep& s) {
        return s.effect == tie[0].effect;
      });
  // A set of one (FindSingleReplacement) ties as a swap's rival does.
  if (!set || names.size() < 3) {
    *effects = Joined(names, " or ");
    return;
  }
  *effects = names[0] + ", or " +
             Joined({names.begin() + 1, names.end()}, " and ") + " together";
}

// "a, b and c": the alternatives' probable errors.
std::string ProbableErrors(const std::vector<AlternativeModel>& models) {
  std::vector<std::string> values;
  for (const AlternativeModel& m : models) {
    values.push_back(FormatNumber("%.3g", m.check.probable_error));
  }
  return Joined(values, " and ");
}

// "; the final model holds A in the place of B and C together" for each
// step that a set of effects replaces alike (Diagnosis::stood_in).
std::string StoodIn(const Diagnosis& d) {
  std::string text;
  for (size_t i = 0; i < d.stood_in.size(); ++i) {
    std::vector<std::string> names;
    for (const std::string& id : d.stood_in_for[i]) {
      names.push_back(Describe(id));
    }
    text += "; the final model holds " + d.stood_in[i].effect +
            "'s terms in the place of " + Joined(names, " and ") +
            " (not claimed)";
  }
  return text;
}

// "; ..." when `d`'s tie holds a flow angularity and a roll-locked effect
// of more terms on records whose roll does not separate them, which tie by
// their fits alone (TieGap): why BIC drops apart by more than
// ambiguity_bic are alike.
std::string OffsetTwinWords(const Diagnosis& d) {
  const std::vector<CandidateFit>& tie = d.ambiguous;
  if (d.fits.empty() || RollSeparates(FittedData(d.FinalFit()))) return "";
  const CandidateFit* angularity = FindFit(tie, "flow_angularity");
  if (angularity == nullptr) return "";
  for (const CandidateFit& k : tie) {
    const Effect* e = FindEffect(k.effect);
    if (e != nullptr && e->roll_locked &&
        k.parameters.size() > angularity->parameters.size()) {
      return "; over less than a revolution of roll a first harmonic of roll "
             "holds an offset: their BIC drops differ by about the penalty "
             "of " +
             k.effect + "'s " +
             std::to_string(k.parameters.size() -
                            angularity->parameters.size()) +
             " more terms";
    }
  }
  return "";
}

// The partial steps of `d`, an ambiguous answer, after its first, the
// tie's followed effect; where steps before the tie that go with it came
// first (WithoutPrunedBeforeTie), every one but the followed effect. On
// draw 166's cone "with the first in the model, <the tied tunnel damping>
// explains the rest" had come of a Magnus moment that goes with it.
std::vector<DiagnosisStep> Beside(const Diagnosis& d) {
  const auto followed =
      std::find_if(d.partial.begin(), d.partial.end(), [&](const auto& s) {
        return s.effect == d.ambiguous[0].effect;
      });
  if (followed == d.partial.begin() || followed == d.partial.end()) {
    return {d.partial.begin() + 1, d.partial.end()};
  }
  std::vector<DiagnosisStep> beside(d.partial.begin(), followed);
  beside.insert(beside.end(), followed + 1, d.partial.end());
  return beside;
}

// The verdict text of an open tie (d->ambiguous): the tied effects, what
// separates them, the later ties and what was added beside them.
std::string AmbiguousText(const Diagnosis& d) {
  const CandidateFit& a = d.ambiguous[0];
  const CandidateFit& b = d.ambiguous[1];
  const size_t n = d.ambiguous.size();
  std::string effects, drops;
  TieWords(d, d.ambiguous, &effects, &drops);
  std::string later;
  for (size_t i = 0; i < d.later_ties.size(); ++i) {
    std::string words, bic;
    TieWords(d, d.later_ties[i], &words, &bic);
    later += "; also ambiguous: " + words + " (BIC lower by " + bic + ")";
    if (i < d.later_separated_by.size()) {
      later += ", " + d.later_separated_by[i] + " would separate them";
    }
  }
  return "ambiguous: " + effects +
         (b.effect == kDriftInTime
              ? " (the first lowers BIC by " +
                    FormatNumber("%.1f", a.bic_drop) +
                    "; over this record's roll its signature is a slow "
                    "change in time)"
              : " explain the record alike (BIC lower by " + drops +
                    " where the first was added, and alike swapped for each "
                    "other with the other effects in" +
                    OffsetTwinWords(d) + ")") +
         (n > 2 ? "; none added; " : "; neither added; ") + d.separated_by +
         " would separate them" + later +
         (d.steps.empty() ? "" : "; added: " + Described(d.steps)) +
         (d.alternatives.empty()
              ? ""
              : " (needed with each of the tied effects; the complete model "
                "with each: probable error " +
                    ProbableErrors(d.alternatives) + ")") +
         (d.stand_in.empty() ? ""
                             : "; the final model holds " + d.stand_in +
                                   " in the tie's place (the effects added "
                                   "need one of them)") +
         StoodIn(d) +
         (d.partial.size() > 1
              ? "; with the first in the model, " + Described(Beside(d)) +
                    " explains the rest (not adopted either)"
              : "");
}

// White residuals larger than sigma: their size is all that is wrong, and
// noise larger than configured makes that as well as a missing effect (a
// clean record with 0.015-deg noise fitted with sigma 0.01 had been called
// structured). "White" is the test's word, and its limit is said with it:
// on a short record noise reaches a lag-1 autocorrelation that reads as
// structure (draw 136's 34-sample run: psi 0.46 against a limit of 0.53).
std::string LargerThanSigma(const ResidualCheck& check) {
  return "the residuals pass the whiteness test (lag-1 autocorrelation "
         "phi " +
         FormatNumber("%.2f", check.lag1.phi) + " theta " +
         FormatNumber("%.2f", check.lag1.theta) + " psi " +
         FormatNumber("%.2f", check.lag1.psi) + ", each below the limit " +
         FormatNumber("%.2f", check.whiteness_limit) +
         " set for noise on this many samples; no spectral line) but " +
         FormatNumber("%.3g", check.probable_error) +
         " times the configured sigma (rms theta " +
         FormatNumber("%.3g", check.rms_deg.theta) + ", psi " +
         FormatNumber("%.3g", check.rms_deg.psi) +
         " deg): the noise may be larger than configured (a record of the "
         "model at rest, or sigma set to these or to auto, tells) or an "
         "effect is missing that this record cannot confirm";
}

// sigma: auto (DiagnoseOptions::noise_held): the noise the search held,
// and what its level could not tell.
std::string HeldNoise(const Diagnosis& d) {
  if (!d.noise_held) return "";
  const ChannelValues s = DiagnosedNoise(d, ChannelValues{});
  return "; sigma: auto, the noise held at the record's own estimate (phi " +
         FormatNumber("%.3g", s.phi) + ", theta " +
         FormatNumber("%.3g", s.theta) + ", psi " +
         FormatNumber("%.3g", s.psi) +
         " deg): an effect is found by its own fit (BIC, the held-out part) "
         "more than by the residuals' size, which that estimate's own spread "
         "blurs; one that raises them less than " +
         FormatNumber("%.2g", d.final.noise_limit) +
         "-fold may pass unseen (give the bench's sigma for a sharper test)";
}

// At the noise level, but further below sigma than noise goes by chance:
// sigma is larger than the noise, and the limits are loose by as much.
std::string SmallerThanSigma(const ResidualCheck& check) {
  if (!check.below_sigma) return "";
  return "; but the residuals are " +
         FormatNumber("%.2g", check.probable_error) +
         " of the configured sigma (rms theta " +
         FormatNumber("%.3g", check.rms_deg.theta) + ", psi " +
         FormatNumber("%.3g", check.rms_deg.psi) +
         " deg): sigma is larger than the noise, and an effect that raises "
         "them " +
         FormatNumber("%.2g", check.noise_limit / check.probable_error) +
         "-fold passes unseen (set sigma to the residuals' rms)";
}

// The verdict's opening when the final model reaches the noise level but
// a probe outside the catalog outdid every catalog effect that earned its
// place (Diagnosis::outside_catalog): the level passes what effects that
// earn their place by BIC and out of sample show is structure. On draw
// 92's pair of runs with a pitch and yaw reading error at the second
// harmonic of roll (sigma: auto), the nominal fit's probable error was
// 1.37 of the held level, a trim moment lowered BIC by 71 and that probe
// by 97: the answer had been `noise_level`.
std::string AtTheNoiseYetStructured(const ResidualCheck& check) {
  return "the residuals are within the noise level's limit (probable error " +
         FormatNumber("%.3g", check.probable_error) +
         "), yet effects earn their place in them";
}

// What `fit`'s residuals at the noise level depend on (Explains), `whose`
// ("its", "the") they are: "its residuals, within the noise level's limit
// (probable error 1.36), still show pitch: a dependence on the pitch angle
// (73%) ...".
std::string DependentResiduals(const FitResult& fit, const char* whose) {
  std::string shown = DescribeResiduals(fit);
  const std::string prefix = "the residuals show ";
  if (shown.rfind(prefix, 0) == 0) shown.erase(0, prefix.size());
  return std::string(whose) +
         " residuals, within the noise level's limit (probable error " +
         FormatNumber("%.3g", fit.probable_error) + "), still show " + shown +
         ": structure that noise does not leave";
}

// What the partial steps' model leaves (Diagnosis::partial, not adopted:
// the final model is the one before them). White residuals past the noise
// level's limit are the noise's size, not a structure, and the words had
// called them structured: on a 3-s run with a body yaw asymmetry (suite
// draw 115, 35 samples, sigma given) the asymmetry lowered the probable
// error from 1.81 to 1.21, white, against a limit of 1.20, where the true
// model's own fit reached 1.1996 (its noise drew 1.2 times sigma); with
// sigma: auto the record is diagnosed `ambiguous`, the asymmetry or a
// Magnus moment.
// At the noise level the steps were not adopted for another reason: on
// draw 127's 3-s run with a roll reading error (sigma: auto) the reading
// error took the probable error to 1.12 (limit 1.51) and a probe outside
// the catalog outdid the catalog past the held level; the words had said
// 1.12 was past the limit.
std::string PartialLeaves(const Diagnosis& d) {
  const ResidualCheck& after = d.partial.back().after;
  const std::string final_model =
      ": not adopted, the final model is the one before it";
  if (!after.white) return " but leaves the residuals structured" + final_model;
  if (after.at_noise_level && !after.independent) {
    return " but " + DependentResiduals(d.fits[d.partial_fit], "its") +
           final_model;
  }
  if (after.at_noise_level) {
    return " and leaves the residuals at the noise level's limit (" +
           FormatNumber("%.3g", after.noise_limit) + ") or below" +
           (d.outside_catalog.effect.empty()
                ? std::string()
                : ", but past it an effect outside the catalog outdid "
                  "the catalog's") +
           final_model;
  }
  return " and leaves white residuals, past the noise level's limit (" +
         FormatNumber("%.3g", after.noise_limit) + ")" + final_model +
         "; white, they say the noise may be larger than " +
         (d.noise_held ? std::string("the level held")
                       : std::string("configured (sigma: auto, or a record "
                                     "of the model at rest, tells)"));
}

// The BIC drop in sample from which a roll-locked contender refused out of
// sample is named (RollLockedUnconfirmed): strong evidence on BIC's scale.
constexpr double kUnconfirmedBicDrop = 10.0;

// Roll-locked contenders of the last round that lowered BIC by
// kUnconfirmedBicDrop or more but were refused for the held-out part, on
// a record whose roll does not tell them from a drift: named with what
// would confirm them. Over part of a revolution a first harmonic of roll
// is part offset, part drift, and fitted to part of the record it
// extrapolates poorly: on draw 136's 34-sample run over 109 deg of roll
// with a roll reading error at 1.5 times the noise, the reading error and
// a trim moment lowered BIC by 36 and 40 and each predicted the held-out
// half worse, and the verdict had only said the noise may be larger than
// configured. Empty otherwise.
std::string RollLockedUnconfirmed(const Diagnosis& d) {
  if (d.fits.empty()) return "";
  const std::vector<TimeHistory> data = FittedData(d.FinalFit());
  if (RollSeparates(data)) return "";
  std::vector<std::string> drops;
  for (const CandidateFit& k : d.rejected) {
    const Effect* e = FindEffect(k.effect);
    if (e == nullptr || !e->roll_locked ||
        !(k.bic_drop >= kUnconfirmedBicDrop) ||
        k.rejected.rfind(kHeldOutRefusal, 0) != 0) {
      continue;
    }
    drops.push_back(k.effect + " by " + FormatNumber("%.1f", k.bic_drop));
  }
  if (drops.empty()) return "";
  return "; roll-locked effects lower BIC (" + Joined(drops, ", ") +
         ") but do not predict the held-out samples better over this "
         "record's " +
         FormatNumber("%.0f", RollSpan(data)) +
         " deg of roll: a record spanning a revolution of roll, or a run at "
         "another spin rate, would confirm or rule them out";
}

// The catalog effects a probe outdid (Diagnosis::outdone_by_probe), each
// with its BIC drop from `rejected`: the nearest catalog explanation, for
// the engineer to weigh (draw 128's cone with a bearing moment: a pressure
// drift outdid it by 17.7, and the verdict had named the drift alone).
// Empty when there are none.
std::string OutdoneByTheProbe(const Diagnosis& d) {
  std::vector<std::string> outdone;
  for (const std::string& id : d.outdone_by_probe) {
    const CandidateFit* k = FindFit(d.rejected, id);
    outdone.push_back(id + (k == nullptr
                                ? ""
                                : " (BIC lower by " +
                                      FormatNumber("%.1f", k->bic_drop) + ")"));
  }
  return outdone.empty()
             ? ""
             : "; outdone by it, not added: " + Joined(outdone, ", ");
}

// The verdict text when the final model leaves the residuals structured:
// what it holds, what was tried and not adopted, and the probe outside
// the catalog that explains more, if one does.
std::string NotExplainedText(const Diagnosis& d) {
  const ResidualCheck& check = d.final;
  // Roll too: its residual alone may be what fails the test (a roll read in
  // counts leaves their rounding's sawtooth there).
  const std::string lag1 =
      "lag-1 autocorrelation phi " + FormatNumber("%.2f", check.lag1.phi) +
      " theta " + FormatNumber("%.2f", check.lag1.theta) + " psi " +
      FormatNumber("%.2f", check.lag1.psi) + " against a limit of " +
      FormatNumber("%.2f", check.whiteness_limit);
  return "not explained by the catalog: " +
         (check.at_noise_level && !check.independent
              ? DependentResiduals(d.FinalFit(), "the")
          : check.at_noise_level ? AtTheNoiseYetStructured(check)
          : check.white          ? LargerThanSigma(check)
                                 : "the residuals remain structured (probable "
                                   "error " +
                              FormatNumber("%.3g", check.probable_error) +
                              ", " + lag1 + ")") +
         (d.steps.empty() ? "" : " after adding " + Described(d.steps)) +
         (d.partial.empty()
              ? (d.outside_catalog.effect.empty()
                     ? " and no further effect earns its place"
                     : "")
              : "; " + Described(d.partial) + " lowers the probable error to " +
                    FormatNumber("%.3g", d.fits[d.partial_fit].probable_error) +
                    PartialLeaves(d)) +
         RollLockedUnconfirmed(d) +
         (d.outside_catalog.effect.empty()
              ? ""
              : "; " + Describe(d.outside_catalog.effect) +
                    " explains more than any catalog effect (BIC lower by " +
                    FormatNumber("%.1f", d.outside_catalog.bic_drop) +
                    (d.outside_at_noise_level
                         ? "; with it the residuals are at the noise level"
                         : "") +
                    ")" + OutdoneByTheProbe(d));
}

}  // namespace

std::string Described(const std::vector<DiagnosisStep>& steps) {
  std::string text;
  for (const DiagnosisStep& s : steps) {
    text += (text.empty() ? "" : ", ") + s.description;
  }
  return text;
}

std::string Describe(const std::string& id) {
  if (id == kDriftInTime) {
    return "a slow drift of the readings or of the flow in time (outside "
           "the catalog)";
  }
  const Effect* e = FindProbe(id);
  if (e == nullptr) e = FindOpenForm(id);
  if (e == nullptr) e = FindEffect(id);
  CHECK(e != nullptr) << "no effect " << id;
  return e->description;
}

// "; alike: P in place of E (BIC +x against it: no evidence either way);
// what would separate them", for each step's probe that explains the
// record alike (DiagnosisStep::outside_alike).
std::string OutsideAlike(const std::vector<DiagnosisStep>& steps) {
  std::string text;
  for (const DiagnosisStep& s : steps) {
    if (s.outside_alike.effect.empty()) continue;
    const Effect* probe = FindProbe(s.outside_alike.effect);
    CHECK(probe != nullptr) << s.outside_alike.effect;
    text += "; alike: " + probe->description + " in place of " + s.description +
            " (BIC " + FormatNumber("%+.1f", s.outside_alike_bic) +
            " against it: no evidence either way)";
    if (!probe->separated_by.empty()) {
      text += "; " + probe->separated_by + " would separate them";
    }
  }
  return text;
}

void Conclude(Diagnosis* d) {
  if (!d->ambiguous.empty()) {
    d->verdict = Verdict::kAmbiguous;
    d->verdict_text = AmbiguousText(*d);
  } else if (Explains(d->final) && d->outside_catalog.effect.empty()) {
    d->verdict = d->steps.empty() ? Verdict::kNoiseLevel : Verdict::kExplained;
    d->verdict_text = (d->steps.empty() ? "residuals at noise level"
                                        : "explained: " + Described(d->steps) +
                                              "; residuals at noise level") +
                      (d->noise_held ? "" : SmallerThanSigma(d->final));
  } else {
    d->verdict = Verdict::kNotExplained;
    d->verdict_text = NotExplainedText(*d);
  }
  if (d->verdict != Verdict::kNotExplained) {
    d->verdict_text += OutsideAlike(d->steps);
  }
  d->verdict_text += HeldNoise(*d);
  if (d->verdict != Verdict::kNoiseLevel && d->verdict != Verdict::kExplained) {
    d->residual_description = DescribeResiduals(d->FinalFit());
  }
}

}  // namespace fit3dof
