// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Reading a case's data once and laying out its free coordinates
// (fit_problem.h).

#include "fit_problem.h"

#include <glog/logging.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

#include "fit3dof/data_selection.h"
#include "fit3dof/fit.h"
#include "fit3dof/initial_conditions.h"
#include "fit3dof/input_error.h"
#include "fit3dof/noise.h"
#include "fit3dof/parameters.h"
#include "fit3dof/runge_kutta.h"
#include "fit3dof/wild_points.h"

namespace fit3dof {
namespace {

// The segment's samples as fitted: read, selected, noise added.
TimeHistory LoadSegment(const Case& c, const Segment& s, int index) {
  // Only the selected samples are kept: a 4-million-row record fitted
  // every 1000th sample costs 4000 samples of memory.
  SampleSelector selector(s.selection);
  int rows = 0;
  try {
    rows = ForEachSample(s.data_file,
                         [&](double t, double phi, double theta, double psi) {
                           selector.Add(t, phi, theta, psi);
                         });
  } catch (const InputError& e) {
    throw InputError(c.source + ": segment '" + s.name +
                     "' data.file: " + e.what());
  }
  TimeHistory data = selector.Finish();
  if (data.size() < 2) {
    throw InputError(c.source + ": segment '" + s.name +
                     "': the data selection (start, fraction, every, "
                     "t_start, t_end) leaves " +
                     std::to_string(data.size()) + " samples of " +
                     std::to_string(rows) + "; need at least 2");
  }
  NoiseOptions noise = c.noise;
  noise.seed += static_cast<std::uint64_t>(index);
  AddNoise(noise, &data);
  return data;
}

PreparedSegment PrepareSegment(const Case& c,
                               const Segment& s,
                               TimeHistory data) {
  PreparedSegment p;
  p.name = s.name;
  p.data = std::move(data);
  p.base = c.Values();
  const ParameterLayout& layout = Layout(c.model);
  p.from_data = s.initial_conditions == InitialConditionMode::kFromData;
  p.sigma = c.sigma;
  std::array<double, 6> initial;
  for (int j = 0; j < 6; ++j) initial[j] = s.initial[j].value;
  bool any_auto = false;
  for (int j = 0; j < 6; ++j) any_auto |= s.initial[j].auto_start;
  if (p.from_data || any_auto) {
    const std::array<double, 6> estimate =
        EstimateInitialConditions(c.model,
                                  p.data,
                                  p.base[layout.theta_offset],
                                  p.base[layout.psi_offset]);
    for (int j = 0; j < 6; ++j) {
      if (p.from_data || s.initial[j].auto_start) initial[j] = estimate[j];
    }
  }
  for (int j = 0; j < 6; ++j) {
    p.base[layout.first_initial + j] = initial[j];
    if (s.initial[j].free) p.own.push_back(layout.first_initial + j);
  }
  return p;
}

// Free-coordinate names: report names, qualified by segment when several
// segments carry their own initial conditions.
std::vector<std::string> FreeNames(const Case& c,
                                   const FreeLayout& free,
                                   const std::vector<PreparedSegment>& segs) {
  const auto& table = ParameterTable(c.model);
  std::vector<std::string> names;
  for (int g = 0; g < free.size(); ++g) {
    std::string name = table[free.position[g]].name;
    if (free.segment[g] >= 0 && segs.size() > 1) {
      name = segs[free.segment[g]].name + "." + name;
    }
    names.push_back(name);
  }
  return names;
}

// Shared free parameters first, then each segment's own initial conditions.
FreeLayout LayOut(const Case& c, const std::vector<PreparedSegment>& segs) {
  FreeLayout free;
  free.ties = c.Ties();
  for (int i = 0; i < NumParameters(c.model); ++i) {
    if (c.parameters[i].free && !IsInitialCondition(c.model, i)) {
      free.shared.push_back(i);
      free.position.push_back(i);
      free.segment.push_back(-1);
    }
  }
  for (size_t s = 0; s < segs.size(); ++s) {
    free.own_offset.push_back(free.size());
    for (int position : segs[s].own) {
      free.position.push_back(position);
      free.segment.push_back(static_cast<int>(s));
    }
  }
  return free;
}

}  // namespace

std::vector<TimeHistory> ReadSegmentData(const Case& c,
                                         std::vector<Outlier>* outliers) {
  std::vector<TimeHistory> data;
  for (size_t s = 0; s < c.segments.size(); ++s) {
    const Segment& segment = c.segments[s];
    data.push_back(LoadSegment(c, segment, static_cast<int>(s)));
    std::vector<int> drop;
    for (const WildPoint& w : ScreenData(data.back())) {
      const bool reject = segment.outliers == OutlierPolicy::kReject;
      outliers->push_back({segment.name, w, reject, false});
      if (reject) drop.push_back(w.sample);
    }
    if (!drop.empty()) data.back() = DropSamples(data.back(), drop);
  }
  return data;
}

int FreeShared(const Case& c, const FreeLayout& free, const std::string& name) {
  const auto& table = ParameterTable(c.model);
  for (int g = 0; g < free.size(); ++g) {
    if (free.segment[g] < 0 && table[free.position[g]].name == name) return g;
  }
  return -1;
}

int CountPoints(const std::vector<PreparedSegment>& segments) {
  int points = 0;
  for (const PreparedSegment& p : segments) points += p.data.size();
  return points;
}

double LargestAngle(const FitProblem& problem) {
  double largest = 0.0;
  for (const PreparedSegment& p : problem.segments) {
    largest = std::max(largest, LargestTotalAngle(p.data));
  }
  return largest;
}

FitProblem PrepareProblem(const Case& c, const std::vector<TimeHistory>& data) {
  CHECK_EQ(data.size(), c.segments.size());
  double steps = 0.0, span = 0.0;
  for (const TimeHistory& d : data) {
    steps += TotalSubsteps(d.t.data(), d.size(), c.solver.step);
    span += d.t.back() - d.t.front();
  }
  CheckIntegrationSteps(steps, span, c.solver.step, c.source);
  FitProblem p;
  for (size_t s = 0; s < c.segments.size(); ++s) {
    p.segments.push_back(PrepareSegment(c, c.segments[s], data[s]));
  }
  p.free = LayOut(c, p.segments);
  p.points = CountPoints(p.segments);
  p.values.resize(p.free.size());
  for (int g = 0; g < p.free.size(); ++g) {
    p.values[g] = p.free.segment[g] < 0
                      ? c.parameters[p.free.position[g]].value
                      : p.segments[p.free.segment[g]].base[p.free.position[g]];
  }
  p.names = FreeNames(c, p.free, p.segments);
  p.model = std::make_shared<const MotionModel>(
      c.Spec(), ActiveParameters(c.Values(), c.VaryingFlags()));
  return p;
}

}  // namespace fit3dof
