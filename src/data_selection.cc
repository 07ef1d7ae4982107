// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Which samples of a record a segment uses (data_selection.h): the time
// window, NSTART, SAMPLE and NDELTA, applied while the CSV is read.

#include "fit3dof/data_selection.h"

#include <glog/logging.h>

#include <cmath>
#include <utility>

#include "fit3dof/angles.h"

namespace fit3dof {

void SampleSelector::Add(double t, double phi, double theta, double psi) {
  if (!(t >= selection_.t_start && t <= selection_.t_end)) return;
  const long index = in_window_++ - (selection_.start - 1);
  t_last_ = t;
  if (index < 0) return;
  if (index == 0) t_first_ = t;
  if (index % selection_.every == 0) kept_.Append(t, phi, theta, psi);
}

TimeHistory SampleSelector::Finish() {
  const double limit = selection_.fraction * (t_last_ - t_first_);
  int n = 0;
  while (n < kept_.size() && kept_.t[n] - t_first_ <= limit * (1.0 + 1e-12)) {
    ++n;
  }
  for (std::vector<double>* v :
       {&kept_.t, &kept_.phi, &kept_.theta, &kept_.psi}) {
    v->resize(n);
    v->shrink_to_fit();
  }
  return std::move(kept_);
}

TimeHistory SelectSamples(const TimeHistory& record,
                          const DataSelection& selection) {
  SampleSelector selector(selection);
  for (int i = 0; i < record.size(); ++i) {
    selector.Add(record.t[i], record.phi[i], record.theta[i], record.psi[i]);
  }
  return selector.Finish();
}

std::vector<double> UnwrapDegrees(const std::vector<double>& angles,
                                  const std::vector<char>& skip) {
  CHECK(skip.empty() || skip.size() == angles.size());
  std::vector<double> out = angles;
  double shift = 0.0;
  int last = -1;
  for (size_t i = 0; i < angles.size(); ++i) {
    if (!skip.empty() && skip[i]) continue;
    if (last >= 0) {
      const double step = angles[i] - angles[last];
      shift -= WholeTurns(step);
    }
    out[i] = angles[i] + shift;
    last = static_cast<int>(i);
  }
  return out;
}

}  // namespace fit3dof
