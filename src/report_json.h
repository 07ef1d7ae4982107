// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// report.json as a JSON object (ReportJson in fit_report.h is its text), for
// writers that add their own keys: the batch adds the run's config hash,
// resume key, start_from and diagnosis.

#ifndef FIT3DOF_SRC_REPORT_JSON_H_
#define FIT3DOF_SRC_REPORT_JSON_H_

#include <nlohmann/json.hpp>

#include "fit3dof/fit.h"

namespace fit3dof {

// Keys in the order written (nlohmann::ordered_json): the parameters in
// the fit's order, the table's then each segment's own initial conditions.
nlohmann::ordered_json ReportObject(const FitResult& result);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_REPORT_JSON_H_
