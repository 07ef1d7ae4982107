// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Small JSON helpers shared by the writers (and readers) of report.json,
// summary.json and diagnosis.json.

#ifndef FIT3DOF_SRC_JSON_VALUES_H_
#define FIT3DOF_SRC_JSON_VALUES_H_

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "fit3dof/case.h"
#include "fit3dof/fit.h"
#include "fit3dof/time_history.h"

namespace fit3dof {

// JSON has no NaN or infinity: undetermined numbers are written as null.
inline nlohmann::json JsonNumber(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
}

// The reverse of JsonNumber, for report.json and summary.json read back: a
// null, or anything else not a number, is NaN.
template <typename Json>
double NumberFromJson(const Json& x) {
  return x.is_number() ? x.template get<double>()
                       : std::numeric_limits<double>::quiet_NaN();
}

inline nlohmann::json JsonChannels(const ChannelValues& v) {
  return {{"phi", JsonNumber(v.phi)},
          {"theta", JsonNumber(v.theta)},
          {"psi", JsonNumber(v.psi)}};
}

// A fit's wild points (report.json's and diagnosis.json's `outliers`).
inline nlohmann::json OutliersJson(const std::vector<Outlier>& outliers) {
  static const char* const kTests[] = {"reach", "jump", "residual"};
  nlohmann::json out = nlohmann::json::array();
  for (const Outlier& o : outliers) {
    out.push_back({{"segment", o.segment},
                   {"t", o.point.t},
                   {"channel", ChannelName(o.point.channel)},
                   {"value", JsonNumber(o.point.value)},
                   {"deviation", JsonNumber(o.point.deviation)},
                   {"robust_sigmas", JsonNumber(o.point.sigmas)},
                   {"test", kTests[static_cast<int>(o.point.test)]},
                   {"action", o.dropped ? "dropped" : "kept"},
                   {"reason", o.point.Describe()}});
  }
  return out;
}

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_JSON_VALUES_H_
