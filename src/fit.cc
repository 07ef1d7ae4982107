// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit3dof/fit.h"

#include <glog/logging.h>

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <sstream>

#include "ceres/ceres.h"
#include "fit3dof/data_selection.h"
#include "fit3dof/initial_conditions.h"
#include "fit3dof/input_error.h"
#include "fit3dof/interrupt.h"
#include "fit3dof/noise.h"
#include "fit3dof/progress.h"
#include "fit3dof/segment_cost_function.h"
#include "fit3dof/start_values.h"
#include "fit3dof/thread_budget.h"
#include "fit3dof/wild_points.h"

namespace fit3dof {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// A segment ready to fit: its samples and its full parameter vector.
struct PreparedSegment {
  std::string name;
  TimeHistory data;
  std::vector<double> base;  // frozen values and this segment's ICs
  std::vector<int> own;      // positions of its free initial conditions
  bool from_data = false;
};

// The free coordinates of the whole fit: shared ones, then each segment's
// own, in that order (global index g).
struct FreeLayout {
  std::vector<int> shared;      // positions
  std::vector<int> own_offset;  // first global index of each segment
  std::vector<int> position;    // position of global index g
  std::vector<int> segment;     // -1 for shared
  int size() const { return static_cast<int>(position.size()); }
};

struct Assembly {
  std::unique_ptr<ceres::Problem> problem;
  std::vector<SegmentCostFunction*> costs;
  std::vector<double> shared_u;
  std::vector<std::vector<double>> own_u;
  std::vector<double*> blocks;  // in global order, non-empty ones only
};

std::string Fmt(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, value);
  return buffer;
}

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

// The full parameter vector segment `s` sees in the assembly.
std::vector<double> SegmentFullValues(const Assembly& a, size_t s) {
  std::vector<const double*> blocks;
  if (!a.shared_u.empty()) blocks.push_back(a.shared_u.data());
  if (!a.own_u[s].empty()) blocks.push_back(a.own_u[s].data());
  return a.costs[s]->FullValues(blocks.data());
}

// Samples in all segments.
int CountPoints(const std::vector<PreparedSegment>& segments) {
  int points = 0;
  for (const PreparedSegment& p : segments) points += p.data.size();
  return points;
}

// Builds the problem for physical values `values` (global free order) in
// scaled coordinates u = value / scale.
Assembly Assemble(const std::vector<PreparedSegment>& segments,
                  const FreeLayout& free,
                  const std::shared_ptr<const MotionModel>& model,
                  const ChannelValues& sigma,
                  const std::vector<double>& values,
                  const std::vector<double>& scale) {
  Assembly a;
  ceres::Problem::Options options;
  a.problem = std::make_unique<ceres::Problem>(options);
  const int ks = static_cast<int>(free.shared.size());
  a.shared_u.resize(ks);
  for (int g = 0; g < ks; ++g) a.shared_u[g] = values[g] / scale[g];
  a.own_u.resize(segments.size());
  for (size_t s = 0; s < segments.size(); ++s) {
    const int first = free.own_offset[s];
    const int count = static_cast<int>(segments[s].own.size());
    a.own_u[s].resize(count);
    for (int j = 0; j < count; ++j) {
      a.own_u[s][j] = values[first + j] / scale[first + j];
    }
  }
  if (ks > 0) a.blocks.push_back(a.shared_u.data());
  for (size_t s = 0; s < segments.size(); ++s) {
    if (!a.own_u[s].empty()) a.blocks.push_back(a.own_u[s].data());
  }
  for (size_t s = 0; s < segments.size(); ++s) {
    const PreparedSegment& p = segments[s];
    std::vector<int> positions = free.shared;
    std::vector<double> segment_scale(scale.begin(), scale.begin() + ks);
    std::vector<double> base = p.base;
    for (int g = 0; g < ks; ++g) base[free.shared[g]] = values[g];
    for (size_t j = 0; j < p.own.size(); ++j) {
      positions.push_back(p.own[j]);
      segment_scale.push_back(scale[free.own_offset[s] + j]);
    }
    auto* cost = new SegmentCostFunction(
        model, base, positions, ks, segment_scale, p.data, sigma);
    std::vector<double*> blocks;
    if (ks > 0) blocks.push_back(a.shared_u.data());
    if (!a.own_u[s].empty()) blocks.push_back(a.own_u[s].data());
    a.problem->AddResidualBlock(cost, nullptr, blocks);
    a.costs.push_back(cost);
  }
  return a;
}

// Physical values of the free coordinates (global order) from the blocks.
std::vector<double> FreeValues(const Assembly& a,
                               const FreeLayout& free,
                               const std::vector<double>& scale) {
  std::vector<double> values(free.size());
  const int ks = static_cast<int>(a.shared_u.size());
  for (int g = 0; g < ks; ++g) values[g] = scale[g] * a.shared_u[g];
  for (size_t s = 0; s < a.own_u.size(); ++s) {
    for (size_t j = 0; j < a.own_u[s].size(); ++j) {
      const int g = free.own_offset[s] + static_cast<int>(j);
      values[g] = scale[g] * a.own_u[s][j];
    }
  }
  return values;
}

// J^T J of the weighted residuals (columns in global free order) and the
// residual sum of squares; false if the motion cannot be integrated.
bool Information(const Assembly& a,
                 Eigen::MatrixXd* jtj,
                 double* ressum,
                 Eigen::VectorXd* jtr = nullptr) {
  ceres::Problem::EvaluateOptions options;
  options.parameter_blocks = a.blocks;
  double cost = 0.0;
  ceres::CRSMatrix crs;
  std::vector<double> residuals;
  if (!a.problem->Evaluate(
          options, &cost, jtr ? &residuals : nullptr, nullptr, &crs)) {
    return false;
  }
  *ressum = 2.0 * cost;
  // Columns in global free order need every coordinate in the Jacobian: an
  // assembly with held coordinates (SubsetManifold) has fewer columns.
  int ambient = 0;
  for (double* block : a.blocks)
    ambient += a.problem->ParameterBlockSize(block);
  CHECK_EQ(crs.num_cols, ambient)
      << "Information() needs an assembly without held coordinates";
  // J^T J and J^T r row by row from the CRS form: no second copy of a
  // Jacobian that has 3 rows per sample.
  const int k = crs.num_cols;
  jtj->setZero(k, k);
  if (jtr != nullptr) jtr->setZero(k);
  for (int r = 0; r < crs.num_rows; ++r) {
    const int begin = crs.rows[r], end = crs.rows[r + 1];
    for (int a = begin; a < end; ++a) {
      const double va = crs.values[a];
      for (int b = a; b < end; ++b) {
        const int i = std::min(crs.cols[a], crs.cols[b]);
        const int j = std::max(crs.cols[a], crs.cols[b]);
        (*jtj)(i, j) += va * crs.values[b];
      }
      if (jtr != nullptr) (*jtr)(crs.cols[a]) += va * residuals[r];
    }
  }
  const Eigen::MatrixXd upper = *jtj;
  *jtj = upper.selfadjointView<Eigen::Upper>();
  return true;
}

// Scales that make every Jacobian column of unit length (columns that are
// exactly zero keep their scale).
std::vector<double> ColumnScales(const Eigen::MatrixXd& jtj_unscaled,
                                 const std::vector<double>& old_scale) {
  std::vector<double> scale(old_scale.size());
  for (size_t g = 0; g < scale.size(); ++g) {
    const double norm = std::sqrt(jtj_unscaled(g, g));
    scale[g] = (norm > 0.0 && std::isfinite(norm)) ? old_scale[g] / norm
                                                   : old_scale[g];
  }
  return scale;
}

// Logs each iteration the way the report's listing prints it and applies its
// convergence rule: stop when the probable error changes by less than BOUND.
class ReportIterationCallback : public ceres::IterationCallback {
 public:
  ReportIterationCallback(const Assembly* assembly,
                          const FreeLayout* free,
                          const std::vector<double>* scale,
                          const std::vector<std::string>* names,
                          int degrees_of_freedom,
                          double tolerance,
                          double relative_tolerance)
      : assembly_(assembly),
        free_(free),
        scale_(scale),
        names_(names),
        dof_(degrees_of_freedom),
        tolerance_(tolerance),
        relative_tolerance_(relative_tolerance) {}

  ceres::CallbackReturnType operator()(
      const ceres::IterationSummary& summary) override {
    if (StopRequested()) return ceres::SOLVER_ABORT;  // Ctrl-C in a batch
    const double ressum = 2.0 * summary.cost;
    const double e = std::sqrt(ressum / dof_);
    std::vector<double> values = FreeValues(*assembly_, *free_, *scale_);
    if (summary.iteration == 0) {
      old_e_ = e;
      previous_ = values;
      VLOG(1) << "start: sum of residuals " << std::sqrt(ressum)
              << "  probable error " << e;
      return ceres::SOLVER_CONTINUE;
    }
    CountIteration(e);
    if (!summary.step_is_successful) return ceres::SOLVER_CONTINUE;
    std::ostringstream log;
    log << "ITERATION NO " << summary.iteration << "\n"
        << "                      CON        DELTA CON\n";
    for (size_t g = 0; g < values.size(); ++g) {
      char line[128];
      std::snprintf(line,
                    sizeof(line),
                    "  %-18s %14.6e %14.6e\n",
                    (*names_)[g].c_str(),
                    values[g],
                    values[g] - previous_[g]);
      log << line;
    }
    log << "  SUM OF RESIDUALS " << std::sqrt(ressum)
        << "   NEW PROBABLE ERROR = " << e
        << "   OLD PROBABLE ERROR = " << old_e_;
    VLOG(1) << log.str();
    const double change = std::abs(e - old_e_);
    old_e_ = e;
    previous_ = values;
    if (change < std::max(tolerance_, relative_tolerance_ * e)) {
      return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    }
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const Assembly* assembly_;
  const FreeLayout* free_;
  const std::vector<double>* scale_;
  const std::vector<std::string>* names_;
  int dof_;
  double tolerance_;
  double relative_tolerance_;
  double old_e_ = 0.0;
  std::vector<double> previous_;
};

// A correlation as a percentage with enough digits to tell it from 100%.
std::string Percent(double r) {
  int digits = 2;
  while (digits < 6 && 1.0 - r < std::pow(10.0, -digits - 1)) ++digits;
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.*f%%", digits, 100.0 * r);
  return buffer;
}

// "only their sum", "only their difference" or the explicit combination
// a + c b, for a determined direction w = (w_a, w_b).
std::string Combination(const std::string& a,
                        const std::string& b,
                        double w_a,
                        double w_b) {
  const double c = w_b / w_a;
  if (std::abs(c - 1.0) < 0.15) return "only their sum is determined";
  if (std::abs(c + 1.0) < 0.15) return "only their difference is determined";
  return "only the combination " + a + (c >= 0 ? " + " : " - ") +
         Fmt("%.3g", std::abs(c)) + " " + b + " is determined";
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " and " : ", ";
    out += names[i];
  }
  return out;
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

// Free coordinates (global order) whose Jacobian column is zero for all
// practical purposes (1e10 times weaker than the strongest, in physical
// units): parameters the data cannot see at the current values, like a
// Magnus term without spin. Real columns span about 1e-1 (deg per unit of a
// cubic damping term) to 1e8 (deg per unit of Cl_0).
std::vector<bool> NullColumns(const Eigen::MatrixXd& jtj) {
  const double largest = jtj.diagonal().maxCoeff();
  std::vector<bool> null(jtj.rows());
  for (int g = 0; g < jtj.rows(); ++g) {
    null[g] = !(jtj(g, g) > 1e-20 * largest);
  }
  return null;
}

// Holds the given free coordinates constant in the assembled problem.
void HoldCoordinates(const std::vector<bool>& hold, Assembly* a) {
  int offset = 0;
  for (double* block : a->blocks) {
    const int size = a->problem->ParameterBlockSize(block);
    std::vector<int> constant;
    for (int j = 0; j < size; ++j) {
      if (hold[offset + j]) constant.push_back(j);
    }
    if (static_cast<int>(constant.size()) == size) {
      a->problem->SetParameterBlockConstant(block);
    } else if (!constant.empty()) {
      a->problem->SetManifold(block, new ceres::SubsetManifold(size, constant));
    }
    offset += size;
  }
}

// A rough period of the angular motion from the zero crossings of theta and
// psi about their means; 0 when the record holds too few of them.
double EstimatePeriod(const TimeHistory& data) {
  double crossings = 0.0;
  for (const std::vector<double>* channel : {&data.theta, &data.psi}) {
    double mean = 0.0;
    for (double x : *channel) mean += x;
    mean /= channel->size();
    for (size_t i = 1; i < channel->size(); ++i) {
      if (((*channel)[i] - mean) * ((*channel)[i - 1] - mean) < 0.0) {
        crossings += 0.5;  // averaged over the two channels
      }
    }
  }
  if (crossings < 8.0) return 0.0;
  return 2.0 * (data.t.back() - data.t.front()) / crossings;
}

// The windows (seconds after each segment's first sample) of the
// continuation: about two periods of the motion first, doubling until the
// whole record is in. A fit that starts far off in frequency is not convex
// over 40 cycles; over two it is, and each longer window starts from the
// last one's answer.
std::vector<double> ContinuationWindows(
    const std::vector<PreparedSegment>& segments, int num_free) {
  double longest = 0.0;
  double period = 0.0;
  for (const PreparedSegment& p : segments) {
    longest = std::max(longest, p.data.t.back() - p.data.t.front());
    period = std::max(period, EstimatePeriod(p.data));
  }
  std::vector<double> windows;
  if (period > 0.0) {
    for (double w = 2.0 * period; w < 0.75 * longest; w *= 2.0) {
      // Enough residuals for the free parameters in the window.
      int points = 0;
      for (const PreparedSegment& p : segments) {
        for (double t : p.data.t) points += (t - p.data.t.front() <= w);
      }
      if (3 * points >= 4 * num_free + 30) windows.push_back(w);
    }
  }
  windows.push_back(std::numeric_limits<double>::infinity());
  return windows;
}

std::vector<PreparedSegment> Window(const std::vector<PreparedSegment>& all,
                                    double window) {
  std::vector<PreparedSegment> out = all;
  for (PreparedSegment& p : out) {
    TimeHistory cut;
    for (int i = 0; i < p.data.size(); ++i) {
      if (p.data.t[i] - p.data.t[0] > window) break;
      cut.Append(p.data.t[i], p.data.phi[i], p.data.theta[i], p.data.psi[i]);
    }
    p.data = cut;
  }
  return out;
}

struct StageOutcome {
  bool integrable = true;  // false: the motion blew up at the start values
  bool converged = false;
  int iterations = 0;
  int failed_evaluations = 0;  // rejected trial steps that blew up
  double ressum = 0.0;         // weighted residual sum of squares at the end
  std::string termination;
  std::string failure;  // why the start values could not be integrated
};

// One Levenberg-Marquardt run from `values` (updated in place).
StageOutcome SolveStage(const std::vector<PreparedSegment>& segments,
                        const FreeLayout& free,
                        const std::shared_ptr<const MotionModel>& model,
                        const ChannelValues& sigma,
                        const std::vector<std::string>& names,
                        double tolerance,
                        double relative_tolerance,
                        int max_iterations,
                        std::vector<double>* values) {
  StageOutcome outcome;
  const int k = free.size();
  const int points = CountPoints(segments);
  std::vector<double> scale(k, 1.0);
  std::vector<bool> null_columns;
  {
    // Scale the free coordinates by the Jacobian at the start.
    Assembly probe = Assemble(segments, free, model, sigma, *values, scale);
    Eigen::MatrixXd jtj;
    double ressum;
    if (!Information(probe, &jtj, &ressum)) {
      outcome.integrable = false;
      outcome.failure = "the motion blows up";
      for (size_t s = 0; s < probe.costs.size(); ++s) {
        IntegrationFailure failure;
        std::vector<double> angles;
        if (!probe.costs[s]->ComputeAngles(
                SegmentFullValues(probe, s), &angles, &failure)) {
          outcome.failure = failure.reason +
                            Fmt(" at t = %.4g s", failure.time) +
                            " in segment '" + segments[s].name + "'";
          break;
        }
      }
      return outcome;
    }
    scale = ColumnScales(jtj, scale);
    null_columns = NullColumns(jtj);
  }
  Assembly assembly = Assemble(segments, free, model, sigma, *values, scale);
  // A coordinate without any effect on the residuals would let
  // Levenberg-Marquardt step without bound along it (the cost never
  // objects); hold it where it is. The covariance names it afterwards.
  HoldCoordinates(null_columns, &assembly);
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = max_iterations;
  // The report's rule (the callback) decides convergence; Ceres' own
  // tolerances only stop a fit that cannot move at all.
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-16;
  options.parameter_tolerance = 1e-14;
  // SILENT also keeps Ceres from logging every rejected trial step.
  options.logging_type = ceres::SILENT;
  options.update_state_every_iteration = true;
  ReportIterationCallback callback(&assembly,
                                   &free,
                                   &scale,
                                   &names,
                                   3 * points - k,
                                   tolerance,
                                   relative_tolerance);
  options.callbacks.push_back(&callback);
  ceres::Solver::Summary summary;
  ceres::Solve(options, assembly.problem.get(), &summary);
  outcome.iterations = static_cast<int>(summary.iterations.size()) - 1;
  for (const SegmentCostFunction* cost : assembly.costs) {
    outcome.failed_evaluations += cost->failed_evaluations();
  }
  outcome.converged = summary.termination_type == ceres::USER_SUCCESS ||
                      summary.termination_type == ceres::CONVERGENCE;
  if (summary.termination_type == ceres::USER_SUCCESS) {
    outcome.termination = "probable error changed by less than " +
                          Fmt("%g", std::max(tolerance, relative_tolerance));
  } else if (summary.termination_type == ceres::NO_CONVERGENCE) {
    outcome.termination = "CONVERGENCE CRITERIA NOT SATISFIED AFTER " +
                          std::to_string(outcome.iterations) + " ITERATIONS";
  } else {
    outcome.termination = summary.message;
  }
  *values = FreeValues(assembly, free, scale);
  outcome.ressum = 2.0 * summary.final_cost;
  return outcome;
}

// The 1978 program's iteration: the full Gauss-Newton step, no damping, no
// step rejection, stopped by the same probable-error rule.
StageOutcome SolveGaussNewton(const std::vector<PreparedSegment>& segments,
                              const FreeLayout& free,
                              const std::shared_ptr<const MotionModel>& model,
                              const ChannelValues& sigma,
                              double tolerance,
                              int max_iterations,
                              std::vector<double>* values) {
  StageOutcome outcome;
  const int k = free.size();
  const int points = CountPoints(segments);
  const int dof = 3 * points - k;
  std::vector<double> scale(k, 1.0);
  double old_e = -1.0;
  std::vector<double> last_good = *values;
  for (int iteration = 0; !StopRequested(); ++iteration) {
    Assembly a = Assemble(segments, free, model, sigma, *values, scale);
    Eigen::MatrixXd jtj;
    Eigen::VectorXd jtr;
    double ressum;
    if (!Information(a, &jtj, &ressum, &jtr)) {
      if (iteration == 0) {
        outcome.integrable = false;
        outcome.failure = "the motion blows up";
      } else {
        outcome.termination =
            "the Gauss-Newton iteration diverged (the motion blew up)";
        ++outcome.failed_evaluations;
        *values = last_good;  // the last iterate that still integrates
      }
      return outcome;
    }
    if (iteration == 0) {
      // Unit columns, as for Levenberg-Marquardt; then re-evaluate.
      scale = ColumnScales(jtj, scale);
      a = Assemble(segments, free, model, sigma, *values, scale);
      Information(a, &jtj, &ressum, &jtr);
    }
    outcome.ressum = ressum;
    last_good = *values;
    const double e = std::sqrt(ressum / dof);
    if (old_e >= 0.0 && std::abs(e - old_e) < tolerance) {
      outcome.converged = true;
      outcome.termination =
          "probable error changed by less than " + Fmt("%g", tolerance);
      return outcome;
    }
    if (iteration == max_iterations) {
      outcome.termination = "CONVERGENCE CRITERIA NOT SATISFIED AFTER " +
                            std::to_string(iteration) + " ITERATIONS";
      return outcome;
    }
    old_e = e;
    // Solve J^T J du = -J^T r (pseudo-inverse: a singular direction gets no
    // correction, as the listing's INV would divide by zero instead).
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(jtj);
    const Eigen::VectorXd lambda = eigen.eigenvalues();
    Eigen::VectorXd du = Eigen::VectorXd::Zero(k);
    for (int j = 0; j < k; ++j) {
      if (lambda(j) > 1e-14 * lambda.maxCoeff()) {
        const Eigen::VectorXd v = eigen.eigenvectors().col(j);
        du -= v * (v.dot(jtr) / lambda(j));
      }
    }
    const std::vector<double> u =
        FreeValues(a, free, std::vector<double>(k, 1.0));
    for (int g = 0; g < k; ++g) (*values)[g] = scale[g] * (u[g] + du(g));
    outcome.iterations = iteration + 1;
  }
  return outcome;  // stopped on request; Fit throws Interrupted
}

struct PipelineOutcome {
  bool integrable = true;
  std::string failure;
  bool converged = false;
  std::string termination;
  int iterations = 0;
  int failed_evaluations = 0;
  double probable_error = 0.0;
  std::vector<FitResult::Stage> stages;
};

// One attempt from `values` (updated in place): the continuation stages,
// then the whole record under the report's rule, by the configured method.
PipelineOutcome RunPipeline(const Case& c,
                            const std::vector<PreparedSegment>& segments,
                            const FreeLayout& free,
                            const std::shared_ptr<const MotionModel>& model,
                            const std::vector<std::string>& names,
                            std::vector<double>* values) {
  PipelineOutcome result;
  const int k = free.size();
  const bool gauss_newton = c.solver.method == "gauss_newton";
  // The report's plain method fits the whole record at once.
  const std::vector<double> windows =
      c.solver.continuation && !gauss_newton
          ? ContinuationWindows(segments, k)
          : std::vector<double>{std::numeric_limits<double>::infinity()};
  const std::vector<double> start = *values;
  for (size_t w = 0; w < windows.size(); ++w) {
    const bool last = w + 1 == windows.size();
    const std::vector<PreparedSegment> stage =
        last ? segments : Window(segments, windows[w]);
    auto solve = [&](std::vector<double>* trial) {
      if (gauss_newton) {
        return SolveGaussNewton(stage,
                                free,
                                model,
                                c.sigma,
                                c.solver.tolerance,
                                c.solver.max_iterations,
                                trial);
      }
      return SolveStage(stage,
                        free,
                        model,
                        c.sigma,
                        names,
                        last ? c.solver.tolerance : 0.0,
                        last ? 0.0 : 1e-4,
                        last ? c.solver.max_iterations : 50,
                        trial);
    };
    std::vector<double> trial = *values;
    StageOutcome outcome = solve(&trial);
    if (!outcome.integrable && w > 0) {
      // The shorter window's answer blows up over this longer one: start
      // this window again from the original values.
      VLOG(1) << c.name << ": stage " << w + 1
              << " cannot start from the previous stage (" << outcome.failure
              << "); restarting it from the starting values";
      trial = start;
      outcome = solve(&trial);
    }
    if (!outcome.integrable) {
      result.integrable = false;
      result.failure = outcome.failure;
      return result;
    }
    *values = trial;
    result.iterations += outcome.iterations;
    result.failed_evaluations += outcome.failed_evaluations;
    const int stage_points = CountPoints(stage);
    result.stages.push_back({stage_points, outcome.iterations});
    VLOG(1) << c.name << ": stage " << w + 1 << "/" << windows.size() << " ("
            << stage_points << " samples): " << outcome.iterations
            << " iterations, " << outcome.termination;
    if (last) {
      result.converged = outcome.converged;
      result.termination = outcome.termination;
      result.probable_error =
          std::sqrt(outcome.ressum / (3 * stage_points - k));
    }
  }
  return result;
}

// Starting points for the multi-start: the stiffness scaled, the damping
// moved across its plausible range, the other terms zeroed or kept.
std::vector<std::vector<double>> SpreadStarts(const Case& c,
                                              const FreeLayout& free,
                                              const std::vector<double>& base,
                                              int count) {
  static const double kStiffness[] = {0.5, 2.0, 0.7, 1.4, 0.3, 3.0, 0.85, 1.2};
  static const double kDamping[] = {
      -5.0, 0.0, -15.0, -2.0, -10.0, 2.0, -25.0, -8.0};
  const auto& table = ParameterTable(c.model);
  std::vector<std::vector<double>> starts;
  for (int j = 0; j < count; ++j) {
    std::vector<double> s = base;
    for (int g = 0; g < free.size(); ++g) {
      if (free.segment[g] >= 0) continue;  // initial conditions: from data
      const std::string& name = table[free.position[g]].name;
      if (name == "Cm_alpha" || name == "Cn_beta") {
        s[g] = base[g] * kStiffness[j % 8];
        if (s[g] == 0.0)
          s[g] = (name == "Cm_alpha" ? -0.1 : 0.1) * kStiffness[j % 8];
      } else if (name == "Cm_q" || name == "Cn_r") {
        s[g] = kDamping[j % 8];
      } else if (j % 2 == 0) {
        s[g] = 0.0;
      }
    }
    starts.push_back(s);
  }
  return starts;
}

// A case made ready to fit: its segments' samples, the layout of the free
// coordinates, their starting values and the motion model.
struct Problem {
  std::vector<PreparedSegment> segments;
  FreeLayout free;
  std::vector<double> values;
  int points = 0;
  std::shared_ptr<const MotionModel> model;
};

Problem Prepare(const Case& c, const std::vector<TimeHistory>& data) {
  CHECK_EQ(data.size(), c.segments.size());
  double steps = 0.0, span = 0.0;
  for (const TimeHistory& d : data) {
    steps += TotalSubsteps(d.t.data(), d.size(), c.solver.step);
    span += d.t.back() - d.t.front();
  }
  CheckIntegrationSteps(steps, span, c.solver.step, c.source);
  Problem p;
  for (size_t s = 0; s < c.segments.size(); ++s) {
    p.segments.push_back(PrepareSegment(c, c.segments[s], data[s]));
  }
  for (int i = 0; i < NumParameters(c.model); ++i) {
    if (c.parameters[i].free && !IsInitialCondition(c.model, i)) {
      p.free.shared.push_back(i);
      p.free.position.push_back(i);
      p.free.segment.push_back(-1);
    }
  }
  for (size_t s = 0; s < p.segments.size(); ++s) {
    p.free.own_offset.push_back(p.free.size());
    for (int position : p.segments[s].own) {
      p.free.position.push_back(position);
      p.free.segment.push_back(static_cast<int>(s));
    }
    p.points += p.segments[s].data.size();
  }
  p.values.resize(p.free.size());
  for (int g = 0; g < p.free.size(); ++g) {
    p.values[g] = p.free.segment[g] < 0
                      ? c.parameters[p.free.position[g]].value
                      : p.segments[p.free.segment[g]].base[p.free.position[g]];
  }
  p.model = std::make_shared<const MotionModel>(
      c.Spec(), ActiveParameters(c.Values(), c.FreeFlags()));
  return p;
}

// Each segment's samples, screened for wild points (wild_points.h): those
// found are added to `outliers`; a segment whose policy is reject loses
// their samples.
std::vector<TimeHistory> ScreenedData(const Case& c,
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

}  // namespace

Case CaseAtSolution(const Case& c, const FitResult& r) {
  Case at = c;
  for (const ParameterEstimate& e : r.parameters) {
    if (e.segment.empty() && !IsInitialCondition(c.model, e.position)) {
      at.parameters[e.position].value = e.value;
      at.parameters[e.position].auto_start = false;
    }
  }
  for (size_t s = 0; s < at.segments.size() && s < r.segments.size(); ++s) {
    at.segments[s].initial_conditions = InitialConditionMode::kGiven;
    for (int j = 0; j < 6; ++j) {
      at.segments[s].initial[j].value = r.segments[s].initial[j];
      at.segments[s].initial[j].auto_start = false;
    }
  }
  return at;
}

bool Linearize(const Case& c, Linearization* out) {
  std::vector<Outlier> outliers;
  const Problem p = Prepare(c, ScreenedData(c, &outliers));
  Assembly a = Assemble(p.segments,
                        p.free,
                        p.model,
                        c.sigma,
                        p.values,
                        std::vector<double>(p.free.size(), 1.0));
  out->names = FreeNames(c, p.free, p.segments);
  out->positions = p.free.position;
  out->segments = p.free.segment;
  out->points = p.points;
  return Information(a, &out->jtj, &out->ressum, &out->jtr);
}

namespace {

// The fit of the given samples of each segment (the whole of Fit but the
// wild-point screen).
FitResult FitData(const Case& c, const std::vector<TimeHistory>& data) {
  const auto start_time = std::chrono::steady_clock::now();
  const Problem prepared = Prepare(c, data);
  const std::vector<PreparedSegment>& segments = prepared.segments;
  const FreeLayout& free = prepared.free;
  const int points = prepared.points;
  const int k = free.size();
  if (k == 0) {
    throw InputError(c.source +
                     ": parameters: every parameter is frozen; mark at least "
                     "one with free: true");
  }
  const int dof = 3 * points - k;
  if (dof <= 0) {
    throw InputError(c.source + ": too few points: " + std::to_string(points) +
                     " samples give " + std::to_string(3 * points) +
                     " residuals for " + std::to_string(k) +
                     " free parameters");
  }

  std::vector<double> values = prepared.values;
  const std::shared_ptr<const MotionModel>& model = prepared.model;
  const std::vector<std::string> names = FreeNames(c, free, segments);

  FitResult result;
  result.name = c.name;
  result.model = c.model;
  result.points = points;
  result.free_parameters = k;

  // Starting values from the data for the free parameters given none.
  std::vector<bool> auto_start(c.parameters.size(), false);
  bool any_auto = false;
  for (int g = 0; g < k; ++g) {
    if (free.segment[g] < 0 && c.parameters[free.position[g]].auto_start) {
      auto_start[free.position[g]] = true;
      any_auto = true;
    }
  }
  if (any_auto) {
    std::vector<double> full = c.Values();
    for (const std::string& line :
         EstimateStartValues(c, segments[0].data, auto_start, &full)) {
      result.pipeline.push_back("starting value: " + line);
      VLOG(1) << c.name << ": starting value " << line;
    }
    for (int g = 0; g < k; ++g) {
      if (free.segment[g] < 0 && auto_start[free.position[g]]) {
        values[g] = full[free.position[g]];
      }
    }
  }

  const std::vector<double> start_values = values;
  if (VLOG_IS_ON(1)) {
    std::ostringstream start;
    for (int g = 0; g < k; ++g) start << " " << names[g] << "=" << values[g];
    VLOG(1) << c.name << ": starting values" << start.str();
  }
  const double limit = c.solver.max_probable_error;
  const bool plain =
      c.solver.method == "gauss_newton" || !c.solver.continuation;
  const bool robust = !plain && c.solver.multi_start && c.solver.starts > 0;
  PipelineOutcome outcome =
      RunPipeline(c, segments, free, model, names, &values);
  if (StopRequested()) throw Interrupted();
  if (!outcome.integrable) {
    const std::string message =
        "the motion cannot be integrated from the "
        "starting values (" +
        outcome.failure + ")";
    if (!robust || limit <= 0.0) {
      throw InputError(c.source + ": " + message + "; check the parameters");
    }
    // The robust pipeline restarts from the data instead.
    result.pipeline.push_back(message + ": restarting from the data");
    outcome.probable_error = std::numeric_limits<double>::infinity();
    values = start_values;
  }
  if (limit > 0.0 && outcome.probable_error > limit && robust) {
    // Far above the noise level: a local minimum is likely. Restart from a
    // spread of starting points, in parallel, and keep the best.
    // The restarts ignore the given values: they start from what the data
    // say (linear-theory estimates of every free coefficient, nonlinear
    // terms at zero, initial conditions from the data), then spread from
    // there.
    std::vector<double> data_start = start_values;
    {
      std::vector<bool> all(c.parameters.size(), false);
      for (int g = 0; g < k; ++g) {
        if (free.segment[g] < 0) all[free.position[g]] = true;
      }
      std::vector<double> full = c.Values();
      EstimateStartValues(c, segments[0].data, all, &full);
      const ParameterLayout& layout = Layout(c.model);
      for (int g = 0; g < k; ++g) {
        if (free.segment[g] < 0) {
          data_start[g] = full[free.position[g]];
        } else {
          const PreparedSegment& p = segments[free.segment[g]];
          const std::array<double, 6> estimate =
              EstimateInitialConditions(c.model,
                                        p.data,
                                        full[layout.theta_offset],
                                        full[layout.psi_offset]);
          data_start[g] = estimate[free.position[g] - layout.first_initial];
        }
      }
    }
    std::vector<std::vector<double>> starts = {data_start};
    for (const auto& s :
         SpreadStarts(c, free, data_start, c.solver.starts - 1)) {
      starts.push_back(s);
    }
    std::vector<PipelineOutcome> outcomes(starts.size());
    std::vector<std::vector<double>> finals = starts;
    // Threads from the process's budget (thread_budget.h): inside a busy
    // batch the starts run one after the other.
    ParallelFor(static_cast<int>(starts.size()), [&](int j) {
      try {
        outcomes[j] = RunPipeline(c, segments, free, model, names, &finals[j]);
      } catch (const std::exception& e) {
        outcomes[j].integrable = false;
        outcomes[j].failure = e.what();
      }
    });
    double best = outcome.probable_error;
    int best_index = -1;
    for (size_t j = 0; j < starts.size(); ++j) {
      if (outcomes[j].integrable && outcomes[j].probable_error < best) {
        best = outcomes[j].probable_error;
        best_index = static_cast<int>(j);
      }
      result.iterations += outcomes[j].iterations;
    }
    int reached =
        std::abs(outcome.probable_error - best) <= 0.01 * best ? 1 : 0;
    for (const PipelineOutcome& o : outcomes) {
      reached +=
          o.integrable && std::abs(o.probable_error - best) <= 0.01 * best;
    }
    if (best_index >= 0) {
      result.iterations += outcome.iterations;
      outcome.iterations = 0;
      outcome = outcomes[best_index];
      values = finals[best_index];
    } else if (!outcome.integrable) {
      throw InputError(c.source +
                       ": the motion cannot be integrated from the starting "
                       "values nor from any restart (" +
                       outcome.failure +
                       "); check the body and flow constants");
    }
    result.starts_tried = static_cast<int>(starts.size()) + 1;
    result.starts_reached_best = reached;
    result.pipeline.push_back(
        "multi-start: probable error " + Fmt("%.3g", outcome.probable_error) +
        " after " + std::to_string(result.starts_tried) + " starts, " +
        std::to_string(reached) + " reached the best minimum");
  }
  if (StopRequested()) throw Interrupted();
  result.iterations += outcome.iterations;
  result.failed_evaluations += outcome.failed_evaluations;
  result.stages = outcome.stages;
  result.converged = outcome.converged;
  result.termination = outcome.termination;
  if (result.stages.size() > 1) {
    result.pipeline.push_back(
        "continuation: " + std::to_string(result.stages.size()) +
        " stages up to the whole record");
  }
  if (limit > 0.0 && outcome.probable_error > limit) {
    // Never call a fit converged that does not reach the noise level.
    result.converged = false;
    result.termination =
        "the fit did not reach the noise level: probable error " +
        Fmt("%.3g", outcome.probable_error) + " > " + Fmt("%g", limit) +
        " (a local minimum, a missing effect, or sigma smaller than the "
        "noise)";
  }
  if (!result.converged) LOG(WARNING) << c.name << ": " << result.termination;
  // Covariance at the solution. Parameters the data cannot see at all (a
  // zero Jacobian column in physical units) are named and held; the rest
  // are rescaled to unit columns so that the conditioning test of
  // ceres::Covariance measures correlation, not units.
  std::vector<double> scale(k, 1.0);
  Eigen::MatrixXd jtj;
  double ressum = 0.0;
  Assembly final_assembly =
      Assemble(segments, free, model, c.sigma, values, scale);
  if (!Information(final_assembly, &jtj, &ressum)) {
    throw std::runtime_error(c.source +
                             ": the motion cannot be integrated at the "
                             "solution");
  }
  const std::vector<bool> null_columns = NullColumns(jtj);
  scale = ColumnScales(jtj, scale);
  final_assembly = Assemble(segments, free, model, c.sigma, values, scale);
  // The information matrix in global coordinates first: once a block holds
  // some of its coordinates (a SubsetManifold), Evaluate returns only the
  // tangent-space columns.
  Information(final_assembly, &jtj, &ressum);
  HoldCoordinates(null_columns, &final_assembly);
  result.sum_of_residuals = std::sqrt(ressum);
  // A parameter the data do not determine spends no degree of freedom: the
  // probable error (Eq. 26) counts only the determined directions, so that
  // the others get the error bars of a fit with it frozen.
  int undetermined = 0;
  for (int g = 0; g < k; ++g) {
    if (!null_columns[g]) continue;
    ++undetermined;
    result.warnings.push_back(names[g] +
                              " is not determined by the data (it has no "
                              "effect on the fitted motion)");
    // Keep the rank analysis below away from it.
    jtj.row(g).setZero();
    jtj.col(g).setZero();
    jtj(g, g) = 1.0;
  }

  ceres::Covariance::Options cov_options;
  cov_options.algorithm_type = ceres::DENSE_SVD;
  cov_options.null_space_rank = 0;
  cov_options.min_reciprocal_condition_number = 1e-14;
  ceres::Covariance covariance(cov_options);
  std::vector<std::pair<const double*, const double*>> pairs;
  auto held = [&](size_t b) {
    return final_assembly.problem->IsParameterBlockConstant(
        final_assembly.blocks[b]);
  };
  for (size_t i = 0; i < final_assembly.blocks.size(); ++i) {
    for (size_t j = i; j < final_assembly.blocks.size(); ++j) {
      if (held(i) || held(j)) continue;
      pairs.emplace_back(final_assembly.blocks[i], final_assembly.blocks[j]);
    }
  }
  Eigen::MatrixXd cov_u = Eigen::MatrixXd::Zero(k, k);
  std::vector<bool> determined(k, true);
  for (int g = 0; g < k; ++g) determined[g] = !null_columns[g];
  // Block sizes in global order.
  std::vector<int> block_start, block_size;
  {
    int offset = 0;
    for (double* block : final_assembly.blocks) {
      block_start.push_back(offset);
      const int size = final_assembly.problem->ParameterBlockSize(block);
      block_size.push_back(size);
      offset += size;
    }
  }
  // ceres::Covariance refuses (and logs an error) when the reciprocal
  // condition number is below its limit; check first, so that a
  // rank-deficient fit goes straight to the named-null-space path below.
  bool well_conditioned = false;
  {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(jtj);
    const Eigen::VectorXd lambda = eigen.eigenvalues();
    well_conditioned = lambda.minCoeff() > 1e-13 * lambda.maxCoeff();
  }
  if (well_conditioned &&
      covariance.Compute(pairs, final_assembly.problem.get())) {
    for (size_t i = 0; i < final_assembly.blocks.size(); ++i) {
      for (size_t j = i; j < final_assembly.blocks.size(); ++j) {
        if (held(i) || held(j)) continue;
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
            block(block_size[i], block_size[j]);
        covariance.GetCovarianceBlock(
            final_assembly.blocks[i], final_assembly.blocks[j], block.data());
        cov_u.block(
            block_start[i], block_start[j], block_size[i], block_size[j]) =
            block;
        cov_u.block(
            block_start[j], block_start[i], block_size[j], block_size[i]) =
            block.transpose();
      }
    }
  } else {
    // Rank deficient: name the directions the data do not determine and use
    // the pseudo-inverse for the parameters outside them.
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(jtj);
    const Eigen::VectorXd lambda = eigen.eigenvalues();
    const double lambda_max = lambda.maxCoeff();
    Eigen::MatrixXd pinv = Eigen::MatrixXd::Zero(k, k);
    for (int e = 0; e < k; ++e) {
      const Eigen::VectorXd v = eigen.eigenvectors().col(e);
      bool null_coordinate = false;
      for (int g = 0; g < k; ++g) {
        null_coordinate |= null_columns[g] && std::abs(v(g)) > 0.5;
      }
      if (null_coordinate) continue;  // already named
      if (lambda(e) > 1e-14 * lambda_max) {
        pinv += v * v.transpose() / lambda(e);
        continue;
      }
      ++undetermined;
      std::vector<std::string> involved;
      std::vector<int> index;
      for (int g = 0; g < k; ++g) {
        if (std::abs(v(g)) > 0.2) {
          involved.push_back(names[g]);
          index.push_back(g);
          determined[g] = false;
        }
      }
      std::string message =
          involved.size() == 1
              ? involved[0] +
                    " is not determined by the data (it has no "
                    "effect on the fitted motion)"
              : JoinNames(involved) +
                    " cannot be separated (the information matrix is "
                    "singular)";
      if (index.size() == 2) {
        // Null direction in physical units n; determined w = (n_b, -n_a).
        const double na = scale[index[0]] * v(index[0]);
        const double nb = scale[index[1]] * v(index[1]);
        message += ": " + Combination(involved[0], involved[1], nb, -na);
      }
      result.warnings.push_back(message);
    }
    cov_u = pinv;
  }

  result.probable_error = std::sqrt(ressum / (dof + undetermined));
  // Physical covariance and RMS errors (Eq. 27).
  Eigen::MatrixXd cov(k, k);
  for (int a = 0; a < k; ++a) {
    for (int b = 0; b < k; ++b) cov(a, b) = scale[a] * cov_u(a, b) * scale[b];
  }
  std::vector<double> rms(k);
  for (int g = 0; g < k; ++g) {
    rms[g] =
        determined[g] ? result.probable_error * std::sqrt(cov(g, g)) : kNaN;
  }
  result.correlation_names = names;
  result.correlation = Eigen::MatrixXd::Constant(k, k, kNaN);
  for (int a = 0; a < k; ++a) {
    for (int b = 0; b < k; ++b) {
      if (determined[a] && determined[b]) {
        result.correlation(a, b) = cov(a, b) / std::sqrt(cov(a, a) * cov(b, b));
      }
    }
  }
  // Highly correlated pairs: name the combination that is determined.
  for (int a = 0; a < k; ++a) {
    for (int b = a + 1; b < k; ++b) {
      const double r = result.correlation(a, b);
      if (!(std::abs(r) > 0.99)) continue;
      Eigen::Matrix2d block;
      block << cov(a, a), cov(a, b), cov(b, a), cov(b, b);
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(block);
      // Largest-variance direction n is undetermined; w = (n_b, -n_a).
      const Eigen::Vector2d n = eigen.eigenvectors().col(1);
      Eigen::Vector2d w(n(1), -n(0));
      w /= w(0);
      const double value = w(0) * values[a] + w(1) * values[b];
      const double error = result.probable_error * std::sqrt(w.dot(block * w));
      std::string combination = Combination(names[a], names[b], w(0), w(1));
      result.warnings.push_back(
          names[a] + " and " + names[b] + " are " + Percent(std::abs(r)) +
          " correlated: " + combination + " (" + names[a] +
          (w(1) >= 0 ? " + " : " - ") + Fmt("%.4g", std::abs(w(1))) + " " +
          names[b] + " = " + Fmt("%.6g", value) + " +- " + Fmt("%.2g", error) +
          ")");
    }
  }
  // Groups of three or more nearly dependent parameters (e.g. Cm_alpha, t1,
  // t3 for small motion, the report's Eq. 43). The smallest eigenvalues of
  // the correlation matrix measure how much the others inflate a
  // combination's variance: a well-determined fit like Table 6 reaches
  // 1e-4 (its initial conditions are correlated with the damping terms),
  // the Eq. 43 case 1e-11. Below 1e-6 (a thousand-fold inflation of the
  // error) the group is named.
  if (result.correlation.allFinite()) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(result.correlation);
    for (int e = 0; e < k; ++e) {
      if (eigen.eigenvalues()(e) > 1e-6) continue;
      const Eigen::VectorXd v = eigen.eigenvectors().col(e);
      std::vector<std::string> involved;
      for (int g = 0; g < k; ++g) {
        if (std::abs(v(g)) > 0.25) involved.push_back(names[g]);
      }
      if (involved.size() >= 3) {
        result.warnings.push_back(
            JoinNames(involved) +
            " are nearly dependent: the data determine only " +
            std::to_string(involved.size() - 1) + " combinations of these " +
            std::to_string(involved.size()) + " parameters");
      }
    }
  }

  // Estimates for every parameter.
  const auto& table = ParameterTable(c.model);
  std::vector<double> final_values = c.Values();
  for (int g = 0; g < k; ++g) {
    if (free.segment[g] < 0) final_values[free.position[g]] = values[g];
  }
  for (int i = 0; i < NumParameters(c.model); ++i) {
    if (table[i].scaling == Scaling::kUnused) continue;
    if (IsInitialCondition(c.model, i) && segments.size() > 1) continue;
    ParameterEstimate e;
    e.name = table[i].name;
    e.position = i;
    e.units = table[i].units;
    e.value =
        IsInitialCondition(c.model, i) ? segments[0].base[i] : final_values[i];
    e.rms_error = kNaN;
    for (int g = 0; g < k; ++g) {
      if (free.position[g] == i && (free.segment[g] <= 0)) {
        e.free = true;
        e.value = values[g];
        e.rms_error = rms[g];
      }
    }
    result.parameters.push_back(e);
  }

  // Segments: fitted initial conditions, computed motion, residual levels.
  double sum2[3] = {0, 0, 0};
  for (size_t s = 0; s < segments.size(); ++s) {
    const PreparedSegment& p = segments[s];
    SegmentCostFunction* cost = final_assembly.costs[s];
    const std::vector<double> full = SegmentFullValues(final_assembly, s);
    SegmentFit fit;
    fit.name = p.name;
    fit.data = p.data;
    fit.initial_from_data = p.from_data;
    cost->ComputeAngles(full, &fit.computed, nullptr);
    const int first = Layout(c.model).first_initial;
    for (int j = 0; j < 6; ++j) fit.initial[j] = full[first + j];
    double seg2[3] = {0, 0, 0};
    const double* measured[3] = {
        p.data.phi.data(), p.data.theta.data(), p.data.psi.data()};
    for (int i = 0; i < p.data.size(); ++i) {
      for (int ch = 0; ch < 3; ++ch) {
        const double d = fit.computed[3 * i + ch] - measured[ch][i];
        seg2[ch] += d * d;
        sum2[ch] += d * d;
      }
    }
    const double n = p.data.size();
    fit.rms_residual_deg = {
        std::sqrt(seg2[0] / n), std::sqrt(seg2[1] / n), std::sqrt(seg2[2] / n)};
    // Multi-segment fits list each segment's own initial conditions.
    if (segments.size() > 1) {
      for (int g = 0; g < k; ++g) {
        if (free.segment[g] != static_cast<int>(s)) continue;
        ParameterEstimate e;
        e.name = names[g];
        e.segment = p.name;
        e.position = free.position[g];
        e.units = table[free.position[g]].units;
        e.value = values[g];
        e.rms_error = rms[g];
        e.free = true;
        result.parameters.push_back(e);
      }
    }
    result.segments.push_back(std::move(fit));
  }
  result.rms_residual_deg = {std::sqrt(sum2[0] / points),
                             std::sqrt(sum2[1] / points),
                             std::sqrt(sum2[2] / points)};
  result.seconds = std::chrono::duration<double>(
                       std::chrono::steady_clock::now() - start_time)
                       .count();
  return result;
}

// Rounds of post-fit screening and refitting for rejecting segments.
constexpr int kWildPointRounds = 3;
// Wild points named one by one in the warnings; the rest only in the
// report's outliers.
constexpr int kWildPointWarnings = 10;

// "the data hold 2 wild points (first: ...); data: {outliers: reject}
// drops them", for a fit that failed with wild points in its data.
std::string WildPointSummary(const std::vector<Outlier>& outliers) {
  return "the data hold " + std::to_string(outliers.size()) + " wild point" +
         (outliers.size() == 1 ? "" : "s") +
         " (first: " + outliers[0].point.Describe() +
         "); data: {outliers: reject} drops them";
}

void ReportWildPoints(const Case& c,
                      const std::vector<Outlier>& outliers,
                      FitResult* result) {
  result->outliers = outliers;
  int dropped = 0;
  for (size_t j = 0; j < outliers.size(); ++j) {
    const Outlier& o = outliers[j];
    dropped += o.dropped;
    if (static_cast<int>(j) >= kWildPointWarnings) continue;
    result->warnings.push_back(
        "wild point" +
        (c.segments.size() > 1 ? " in segment '" + o.segment + "'" : "") +
        ": " + o.point.Describe() +
        (o.dropped ? "; dropped"
                   : "; kept (data: {outliers: reject} drops it)"));
  }
  if (static_cast<int>(outliers.size()) > kWildPointWarnings) {
    result->warnings.push_back(
        std::to_string(outliers.size() - kWildPointWarnings) +
        " more wild points (all in report.json's outliers)");
  }
  const int kept = static_cast<int>(outliers.size()) - dropped;
  if (kept > 0 && !result->converged) {
    // Point at the data as well as at the model.
    result->termination += "; the data hold " + std::to_string(kept) +
                           " wild point" + (kept == 1 ? "" : "s") +
                           ", kept (see the warnings; data: {outliers: "
                           "reject} drops them)";
  }
  if (dropped > 0) {
    result->pipeline.push_back("wild points: " + std::to_string(dropped) +
                               " dropped (their samples left out of the "
                               "fit)");
  }
}

}  // namespace

FitResult Fit(const Case& c) {
  if (c.segments.empty()) {
    throw InputError(c.source +
                     ": data: missing (a fit needs data: or segments:)");
  }
  std::vector<Outlier> outliers;
  std::vector<TimeHistory> data = ScreenedData(c, &outliers);
  FitResult result;
  try {
    result = FitData(c, data);
  } catch (const InputError& e) {
    if (outliers.empty()) throw;
    throw InputError(std::string(e.what()) + "; " + WildPointSummary(outliers));
  }
  // After the fit: residuals the fit cannot reach. A rejecting segment
  // drops them and the fit runs again from where it stopped (a wild point
  // that hid others can only show once it is gone; three rounds at most).
  // The residuals of a fit that did not reach the noise level are no
  // reference: the misfit, not the data, would be named.
  for (int round = 0; round < kWildPointRounds && result.converged; ++round) {
    bool refit = false;
    for (size_t s = 0; s < c.segments.size(); ++s) {
      const bool reject = c.segments[s].outliers == OutlierPolicy::kReject;
      std::vector<int> known;
      for (const Outlier& o : outliers) {
        if (o.segment == c.segments[s].name && !o.dropped) {
          known.push_back(o.point.sample);
        }
      }
      const SegmentFit& fit = result.segments[s];
      std::vector<int> drop;
      for (const WildPoint& w :
           ScreenResiduals(fit.data, fit.computed, known)) {
        outliers.push_back({c.segments[s].name, w, reject, true});
        if (reject) drop.push_back(w.sample);
      }
      if (!drop.empty()) {
        data[s] = DropSamples(fit.data, drop);
        refit = true;
      }
    }
    if (!refit) break;
    const double seconds = result.seconds;
    const int iterations = result.iterations;
    result = FitData(CaseAtSolution(c, result), data);
    result.seconds += seconds;
    result.iterations += iterations;
  }
  ReportWildPoints(c, outliers, &result);
  return result;
}

}  // namespace fit3dof
