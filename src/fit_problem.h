// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A case made ready to fit from its segments' samples (read once, before
// any fitting, by ReadSegmentData in fit.h): the layout of the free
// coordinates over the segments and their starting values. Nothing here or
// below reads a file.

#ifndef FIT3DOF_SRC_FIT_PROBLEM_H_
#define FIT3DOF_SRC_FIT_PROBLEM_H_

#include <memory>
#include <string>
#include <vector>

#include "fit3dof/case.h"
#include "fit3dof/motion_model.h"
#include "fit3dof/segment_cost_function.h"
#include "fit3dof/time_history.h"

namespace fit3dof {

// A segment ready to fit: its samples and its full parameter vector.
struct PreparedSegment {
  std::string name;
  TimeHistory data;
  std::vector<double> base;  // frozen values and this segment's ICs
  std::vector<int> own;      // positions of its free initial conditions
  bool from_data = false;    // initial conditions estimated from the data
  // Residual weights (deg): the config's sigma, or the segment's own noise
  // levels once estimated (sigma: auto).
  ChannelValues sigma;
  // The filter-error fit's (filter_error.h): residuals are then the
  // innovations of a filter with these gains; null for output error.
  std::shared_ptr<const InnovationWeights> innovation_weights;
  // The least lag window of the error bars' residual correlation
  // (colored_covariance.h); the filter-error fit sets it.
  int min_lag_window = 0;
};

// The free coordinates of the whole fit: shared ones, then each segment's
// own, in that order (global index g).
struct FreeLayout {
  std::vector<int> shared;      // positions in ParameterTable
  std::vector<int> own_offset;  // first global index of each segment
  std::vector<int> position;    // position of global index g
  std::vector<int> segment;     // -1 for shared
  // Parameters that follow others (case.h), free sources or not: every
  // evaluation applies them.
  std::vector<ParameterTie> ties;
  int size() const { return static_cast<int>(position.size()); }
};

struct FitProblem {
  std::vector<PreparedSegment> segments;
  FreeLayout free;
  std::vector<double> values;      // starting values, global order
  std::vector<std::string> names;  // of the free coordinates (FreeNames)
  int points = 0;                  // samples in all segments
  std::shared_ptr<const MotionModel> model;
};

// The problem for `data` (one record per segment of `c`, as
// ReadSegmentData returns them): initial conditions estimated where the
// config asks, the free layout, the model. Throws InputError when an
// evaluation would need more integration steps than motion_model.h allows.
FitProblem PrepareProblem(const Case& c, const std::vector<TimeHistory>& data);

// The position in the global free order of `c`'s shared free parameter
// `name`, or -1.
int FreeShared(const Case& c, const FreeLayout& free, const std::string& name);

// Samples in all segments.
int CountPoints(const std::vector<PreparedSegment>& segments);

// The largest total angle (deg) of the record's readings, sqrt(theta^2 +
// psi^2) at the small angles a bearing moment fades over.
double LargestAngle(const FitProblem& problem);

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_FIT_PROBLEM_H_
