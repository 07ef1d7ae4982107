// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Which samples of a record a fit uses: the report's PART subroutine
// (NSTART, SAMPLE, NDELTA) after an optional time window.

#ifndef FIT3DOF_DATA_SELECTION_H_
#define FIT3DOF_DATA_SELECTION_H_

#include "fit3dof/case.h"
#include "fit3dof/time_history.h"

namespace fit3dof {

// Applies, in order: the time window [t_start, t_end]; the first sample
// `start` (1-based); every `every`-th sample from there; and only samples
// whose time after the first is at most `fraction` of the remaining record.
TimeHistory SelectSamples(const TimeHistory& record,
                          const DataSelection& selection);

// The same selection applied to samples one at a time (in time order), so
// that reading a long record holds only the samples used: the fraction
// cut-off depends on the record's last time, so Finish() applies it.
class SampleSelector {
 public:
  explicit SampleSelector(const DataSelection& selection)
      : selection_(selection) {}

  void Add(double t, double phi, double theta, double psi);
  TimeHistory Finish();

 private:
  DataSelection selection_;
  TimeHistory kept_;      // every `every`-th from `start`, no cut-off yet
  long in_window_ = 0;    // samples seen inside [t_start, t_end]
  double t_first_ = 0.0;  // time of sample `start` of the window
  double t_last_ = 0.0;   // latest time inside the window
};

// Roll angles made continuous (no jumps of more than 180 deg between
// samples), for records that wrap phi into [0, 360). Samples marked in
// `skip` (if given; one entry per angle) keep their value and are not
// anyone's predecessor: a wild sample does not shift the rest.
std::vector<double> UnwrapDegrees(const std::vector<double>& angles,
                                  const std::vector<char>& skip = {});

}  // namespace fit3dof

#endif  // FIT3DOF_DATA_SELECTION_H_
