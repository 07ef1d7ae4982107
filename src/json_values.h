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

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_JSON_VALUES_H_
