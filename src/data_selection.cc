// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/data_selection.h"

#include <cmath>

namespace fit3dof {

TimeHistory SelectSamples(const TimeHistory& record,
                          const DataSelection& selection) {
  TimeHistory window;
  for (int i = 0; i < record.size(); ++i) {
    if (record.t[i] >= selection.t_start && record.t[i] <= selection.t_end) {
      window.Append(record.t[i], record.phi[i], record.theta[i], record.psi[i]);
    }
  }
  TimeHistory selected;
  const int first = selection.start - 1;
  if (first >= window.size()) return selected;
  const double t0 = window.t[first];
  const double limit = selection.fraction * (window.t.back() - t0);
  for (int i = first; i < window.size(); i += selection.every) {
    if (window.t[i] - t0 > limit * (1.0 + 1e-12)) break;
    selected.Append(window.t[i], window.phi[i], window.theta[i], window.psi[i]);
  }
  return selected;
}

std::vector<double> UnwrapDegrees(const std::vector<double>& angles) {
  std::vector<double> out = angles;
  double shift = 0.0;
  for (size_t i = 1; i < angles.size(); ++i) {
    const double step = angles[i] - angles[i - 1];
    shift -= 360.0 * std::round(step / 360.0);
    out[i] = angles[i] + shift;
  }
  return out;
}

}  // namespace fit3dof
