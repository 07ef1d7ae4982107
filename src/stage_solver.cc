// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Levenberg-Marquardt and Gauss-Newton solves of one stage (stage_solver.h).

#include "stage_solver.h"

#include <glog/logging.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <sstream>
#include <string>

#include "assembly.h"
#include "ceres/ceres.h"
#include "fit3dof/interrupt.h"
#include "fit3dof/progress.h"
#include "fit3dof/thread_budget.h"
#include "format.h"
#include "symmetric_eigen.h"

namespace fit3dof {
namespace {

// Whether `settings`' limited coordinate among `values` lies past its limit.
bool PastLimit(const StageSettings& settings,
               const std::vector<double>& values) {
  return settings.limited >= 0 &&
         std::abs(values[settings.limited]) > settings.limit;
}

// Whether `settings`' outgrowing coordinate among `values` is larger than
// the outgrown one.
bool Outgrown(const StageSettings& settings,
              const std::vector<double>& values) {
  return settings.outgrowing >= 0 && std::abs(values[settings.outgrowing]) >
                                         std::abs(values[settings.outgrown]);
}

// The termination of a run that `settings`' limit or outgrown coordinate
// stopped at `values`: "|name| > limit" or "|name| > |name|".
std::string BeyondTermination(const StageSettings& settings,
                              const std::vector<std::string>& names,
                              const std::vector<double>& values) {
  if (PastLimit(settings, values)) {
    return kLimitTermination + ("|" + names[settings.limited] + "| > ") +
           FormatNumber("%g", settings.limit);
  }
  return kLimitTermination + ("|" + names[settings.outgrowing] + "| > |") +
         names[settings.outgrown] + "|";
}

// Logs each iteration the way the report's listing prints it and applies its
// convergence rule: stop when the probable error changes by less than BOUND
// (or, where the settings ask, when the BIC hardly falls).
//
// Also an evaluation callback, so that the Jacobian at the point where the
// rule stops the run is not computed (SegmentCostFunction::
// skip_next_jacobian): Ceres evaluates it for every accepted step before
// the iteration callback sees the step. The rule needs only the cost, which
// the trial evaluation has already given: before that Jacobian, the rule is
// applied to the blocks' remembered cost, and if it stops there the
// iteration callback follows that verdict.
class ReportIterationCallback : public ceres::IterationCallback,
                                public ceres::EvaluationCallback {
 public:
  ReportIterationCallback(const FreeLayout* free,
                          const std::vector<double>* scale,
                          const std::vector<std::string>* names,
                          int residuals,
                          int degrees_of_freedom,
                          const StageSettings& settings)
      : free_(free),
        scale_(scale),
        names_(names),
        residuals_(residuals),
        dof_(degrees_of_freedom),
        settings_(settings) {}

  // The assembly solved (its problem holds this as evaluation callback);
  // its blocks remember their residuals from here on.
  void Watch(Assembly* assembly) {
    assembly_ = assembly;
    for (SegmentCostFunction* cost : assembly->costs) {
      cost->set_remember_residuals(true);
    }
  }

  // Whether the BIC's rule, not the probable error's, ended it.
  bool stopped_by_bic() const { return ended_.by_bic; }
  // Whether it ended below StageSettings::stop_below.
  bool stopped_below() const { return ended_.below; }
  // Whether it ended out of reach of it (StageSettings::out_of_reach).
  bool stopped_out_of_reach() const { return ended_.out_of_reach; }
  // Whether its limited coordinate passed its limit (StageSettings::limited).
  bool stopped_beyond() const { return ended_.beyond; }

  void PrepareForEvaluation(bool evaluate_jacobians,
                            bool new_evaluation_point) override {
    // Ceres evaluates the Jacobian at a point it evaluated before only for
    // an accepted step (TrustRegionMinimizer::HandleSuccessfulStep).
    if (!evaluate_jacobians || new_evaluation_point || assembly_ == nullptr) {
      return;
    }
    double cost = 0.0;
    for (const SegmentCostFunction* c : assembly_->costs) {
      cost += c->remembered_cost();
    }
    if (!std::isfinite(cost)) return;
    const Verdict verdict = Decide(2.0 * cost, last_iteration_ + 1);
    if (verdict.stop || last_iteration_ + 1 >= settings_.max_iterations) {
      for (const SegmentCostFunction* c : assembly_->costs) {
        c->skip_next_jacobian();
      }
      skipped_ = verdict;
      skipped_iteration_ = last_iteration_ + 1;
    }
  }

  ceres::CallbackReturnType operator()(
      const ceres::IterationSummary& summary) override {
    if (StopRequested()) return ceres::SOLVER_ABORT;  // Ctrl-C in a batch
    last_iteration_ = summary.iteration;
    const double ressum = 2.0 * summary.cost;
    const double e = std::sqrt(ressum / dof_);
    std::vector<double> values = FreeValues(*assembly_, *free_, *scale_);
    if (summary.iteration == 0) {
      old_e_ = e;
      old_ressum_ = ressum;
      previous_ = values;
      VLOG(1) << "start: sum of residuals " << std::sqrt(ressum)
              << "  probable error " << e;
      if (e < settings_.stop_below) {
        ended_.stop = ended_.below = true;
        return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
      }
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
    // The verdict the Jacobian was skipped on, if it was: Ceres sums the
    // blocks' costs in its own order, which can differ in the last bit.
    ended_ = skipped_iteration_ == summary.iteration
                 ? skipped_
                 : Decide(ressum, summary.iteration);
    if (!ended_.stop && Beyond(values)) ended_.stop = ended_.beyond = true;
    falls_.push_back(old_e_ - e);
    if (static_cast<int>(falls_.size()) > kOutOfReachPace - 1) {
      falls_.pop_front();
    }
    old_e_ = e;
    old_ressum_ = ressum;
    previous_ = values;
    return ended_.stop ? ceres::SOLVER_TERMINATE_SUCCESSFULLY
                       : ceres::SOLVER_CONTINUE;
  }

 private:
  struct Verdict {
    bool stop = false;
    bool by_bic = false;
    bool below = false;
    bool out_of_reach = false;
    bool beyond = false;
  };

  // Whether the limited coordinate among `values` lies past its limit, or
  // the outgrowing one past the outgrown (StageSettings).
  bool Beyond(const std::vector<double>& values) const {
    return PastLimit(settings_, values) || Outgrown(settings_, values);
  }

  // The rule applied to a successful step of `iteration` to a residual sum
  // of squares `ressum`, from the state the previous ones left.
  Verdict Decide(double ressum, int iteration) const {
    const double e = std::sqrt(ressum / dof_);
    const double change = std::abs(e - old_e_);
    const double bic_drop = residuals_ * std::log(old_ressum_ / ressum);
    Verdict verdict;
    if (change <
        std::max(settings_.tolerance, settings_.relative_tolerance * e)) {
      verdict.stop = true;
    } else if (bic_drop < settings_.bic_tolerance) {
      verdict.stop = verdict.by_bic = true;
    } else if (e < settings_.stop_below) {
      verdict.stop = verdict.below = true;
    } else if (settings_.out_of_reach && OutOfReach(e, old_e_ - e, iteration)) {
      verdict.stop = verdict.out_of_reach = true;
    }
    return verdict;
  }

  // Whether StageSettings::stop_below is out of reach from `e`, reached by
  // a fall of `fall`, after `iteration` (kOutOfReachMargin).
  bool OutOfReach(double e, double fall, int iteration) const {
    // The pace: the largest of the last kOutOfReachPace falls, this one's
    // and those falls_ holds.
    if (static_cast<int>(falls_.size()) < kOutOfReachPace - 1) return false;
    double pace = fall;
    for (double f : falls_) pace = std::max(pace, f);
    const int remaining = settings_.max_iterations - iteration;
    return e - settings_.stop_below > kOutOfReachMargin * remaining * pace;
  }

  Assembly* assembly_ = nullptr;
  const FreeLayout* free_;
  const std::vector<double>* scale_;
  const std::vector<std::string>* names_;
  int residuals_;
  int dof_;
  StageSettings settings_;
  double old_e_ = 0.0;
  double old_ressum_ = 0.0;
  // The verdict the run has ended on, if it has.
  Verdict ended_;
  // The falls of the probable error in the last kOutOfReachPace - 1
  // successful iterations.
  std::deque<double> falls_;
  std::vector<double> previous_;
  int last_iteration_ = 0;
  // The iteration whose Jacobian was skipped (-1: none) and its verdict.
  int skipped_iteration_ = -1;
  Verdict skipped_;
};

// The largest relative difference, over the columns not `null`, between
// two Jacobians of the same problem: ||a_g - b_g|| / ||b_g|| for column g.
double ColumnDisagreement(const ceres::CRSMatrix& a,
                          const ceres::CRSMatrix& b,
                          const std::vector<bool>& null) {
  CHECK_EQ(a.num_cols, b.num_cols);
  CHECK(a.rows == b.rows && a.cols == b.cols) << "different sparsity";
  std::vector<double> difference(a.num_cols, 0.0), norm(a.num_cols, 0.0);
  for (size_t e = 0; e < a.values.size(); ++e) {
    const double d = a.values[e] - b.values[e];
    difference[a.cols[e]] += d * d;
    norm[a.cols[e]] += b.values[e] * b.values[e];
  }
  double worst = 0.0;
  for (int g = 0; g < a.num_cols; ++g) {
    if (null[g]) continue;
    const double relative = std::sqrt(difference[g] / norm[g]);
    if (!(relative <= worst)) worst = relative;  // NaN: the worst
  }
  return worst;
}

// Whether the Jacobians from the motion at kJacobianStepFactor times the
// model's step serve `probe`'s Levenberg-Marquardt run: every column the
// data see within kJacobianAgreement of the model's own (`exact`, at the
// start). Not where a column is rounding: at zero spin the derivatives
// with respect to Cl_p and Cm_p_alpha are the integration's last bits,
// scaled to unit norm, and the coarser motion's differ from them by 80
// times their size (Levenberg-Marquardt then crawled 31 iterations where
// it had taken 6).
bool CoarserJacobiansServe(const ceres::CRSMatrix& exact,
                           const std::vector<bool>& null,
                           double step,
                           Assembly* probe) {
  for (SegmentCostFunction* cost : probe->costs) cost->set_jacobian_step(step);
  ceres::CRSMatrix coarse;
  std::vector<double> residuals;
  const bool ok = EvaluateJacobian(*probe, &coarse, &residuals);
  for (SegmentCostFunction* cost : probe->costs) cost->set_jacobian_step(0.0);
  return ok && ColumnDisagreement(coarse, exact, null) <= kJacobianAgreement;
}

// One Levenberg-Marquardt run (SolveStage); *held: whether it held each
// coordinate, unseen by the data at the start.
StageOutcome SolveStageOnce(const std::vector<PreparedSegment>& segments,
                            const FreeLayout& free,
                            const std::shared_ptr<const MotionModel>& model,
                            const std::vector<std::string>& names,
                            const StageSettings& settings,
                            std::vector<double>* values,
                            std::vector<bool>* held) {
  const double tolerance = settings.tolerance;
  const double relative_tolerance = settings.relative_tolerance;
  StageOutcome outcome;
  const int k = free.size();
  const int points = CountPoints(segments);
  std::vector<double> scale(k, 1.0);
  std::vector<bool> null_columns;
  const double jacobian_step = kJacobianStepFactor * model->spec().max_step;
  bool coarser_jacobians = false;
  {
    // Scale the free coordinates by the Jacobian at the start.
    Assembly probe = Assemble(segments, free, model, *values, scale);
    ceres::CRSMatrix jacobian;
    std::vector<double> residuals;
    if (!EvaluateJacobian(probe, &jacobian, &residuals)) {
      outcome.integrable = false;
      outcome.failure = "the motion blows up";
      for (size_t s = 0; s < probe.costs.size(); ++s) {
        IntegrationFailure failure;
        std::vector<double> angles;
        if (!probe.costs[s]->ComputeAngles(
                SegmentFullValues(probe, s), &angles, &failure)) {
          outcome.failure = failure.reason +
                            FormatNumber(" at t = %.4g s", failure.time) +
                            " in segment '" + segments[s].name + "'";
          break;
        }
      }
      return outcome;
    }
    Eigen::MatrixXd jtj;
    double ressum;
    NormalEquations(jacobian, residuals, &jtj, &ressum, nullptr);
    scale = ColumnScales(jtj, scale);
    null_columns = NullColumns(jtj);
    coarser_jacobians =
        settings.coarser_jacobians &&
        CoarserJacobiansServe(jacobian, null_columns, jacobian_step, &probe);
  }
  *held = null_columns;
  ReportIterationCallback callback(
      &free, &scale, &names, 3 * points, 3 * points - k, settings);
  Assembly assembly =
      Assemble(segments, free, model, *values, scale, &callback);
  callback.Watch(&assembly);
  // A coordinate without any effect on the residuals would let
  // Levenberg-Marquardt step without bound along it (the cost never
  // objects); hold it where it is. The covariance names it afterwards.
  HoldCoordinates(null_columns, &assembly);
  if (coarser_jacobians) {
    for (SegmentCostFunction* cost : assembly.costs) {
      cost->set_jacobian_step(jacobian_step);
    }
    VLOG(2) << "Jacobians from the motion at a step of " << jacobian_step
            << " s";
  }
  outcome.coarser_jacobians = coarser_jacobians;
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = settings.max_iterations;
  const ThreadLease lease(HelperThreadsFor(assembly));
  options.num_threads = 1 + lease.count();
  options.initial_trust_region_radius = settings.initial_radius;
  // The report's rule (the callback) decides convergence; Ceres' own
  // tolerances only stop a fit that cannot move at all.
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-16;
  options.parameter_tolerance = 1e-14;
  // SILENT also keeps Ceres from logging every rejected trial step.
  options.logging_type = ceres::SILENT;
  options.update_state_every_iteration = true;
  options.callbacks.push_back(&callback);
  ceres::Solver::Summary summary;
  ceres::Solve(options, assembly.problem.get(), &summary);
  outcome.iterations = static_cast<int>(summary.iterations.size()) - 1;
  outcome.accepted_steps = summary.num_successful_steps - 1;  // less the start
  for (const SegmentCostFunction* cost : assembly.costs) {
    outcome.failed_evaluations += cost->failed_evaluations();
    outcome.jacobians += cost->jacobian_evaluations();
  }
  *values = FreeValues(assembly, free, scale);
  outcome.converged = summary.termination_type == ceres::USER_SUCCESS ||
                      summary.termination_type == ceres::CONVERGENCE;
  if (summary.termination_type == ceres::USER_SUCCESS &&
      callback.stopped_by_bic()) {
    outcome.termination =
        kBicRuleTermination + FormatNumber("%g", settings.bic_tolerance);
  } else if (summary.termination_type == ceres::USER_SUCCESS &&
             callback.stopped_below()) {
    outcome.termination =
        kBelowTermination + FormatNumber("%g", settings.stop_below);
  } else if (summary.termination_type == ceres::USER_SUCCESS &&
             callback.stopped_out_of_reach()) {
    outcome.termination =
        kOutOfReachTermination + FormatNumber("%g", settings.stop_below);
  } else if (summary.termination_type == ceres::USER_SUCCESS &&
             callback.stopped_beyond()) {
    outcome.termination = BeyondTermination(settings, names, *values);
  } else if (summary.termination_type == ceres::USER_SUCCESS) {
    outcome.termination =
        kToleranceTermination +
        FormatNumber("%g", std::max(tolerance, relative_tolerance));
  } else if (summary.termination_type == ceres::NO_CONVERGENCE) {
    outcome.termination = "CONVERGENCE CRITERIA NOT SATISFIED AFTER " +
                          std::to_string(outcome.iterations) + " ITERATIONS";
  } else {
    outcome.termination = summary.message;
  }
  outcome.ressum = 2.0 * summary.final_cost;
  return outcome;
}

// Whether a coordinate held by the last run now has an effect on the
// residuals at `values`.
bool HeldComesIntoView(const std::vector<PreparedSegment>& segments,
                       const FreeLayout& free,
                       const std::shared_ptr<const MotionModel>& model,
                       const std::vector<double>& values,
                       const std::vector<bool>& held) {
  if (std::none_of(held.begin(), held.end(), [](bool h) { return h; })) {
    return false;
  }
  Assembly a = Assemble(
      segments, free, model, values, std::vector<double>(values.size(), 1.0));
  Eigen::MatrixXd jtj;
  double ressum;
  if (!Information(a, &jtj, &ressum)) return false;
  const std::vector<bool> now = NullColumns(jtj);
  for (size_t g = 0; g < held.size(); ++g) {
    if (held[g] && !now[g]) return true;
  }
  return false;
}

}  // namespace

StageOutcome SolveStage(const std::vector<PreparedSegment>& segments,
                        const FreeLayout& free,
                        const std::shared_ptr<const MotionModel>& model,
                        const std::vector<std::string>& names,
                        const StageSettings& settings,
                        std::vector<double>* values) {
  // A coordinate the data cannot see at the start may come into view as
  // the others move: a bearing moment's angle (bearing_moment.h) does
  // nothing while Cm_bearing is zero, where a diagnosis starts it, and had
  // stayed at its start value, reported as fitted. Solved again from the
  // answer, it is fitted then.
  constexpr int kMostRuns = 3;
  std::vector<bool> held;
  StageOutcome outcome =
      SolveStageOnce(segments, free, model, names, settings, values, &held);
  for (int run = 1; run < kMostRuns && outcome.integrable &&
                    HeldComesIntoView(segments, free, model, *values, held);
       ++run) {
    std::vector<double> trial = *values;
    StageOutcome again =
        SolveStageOnce(segments, free, model, names, settings, &trial, &held);
    if (!again.integrable) break;
    again.iterations += outcome.iterations;
    again.failed_evaluations += outcome.failed_evaluations;
    again.accepted_steps += outcome.accepted_steps;
    again.jacobians += outcome.jacobians;
    outcome = again;
    *values = trial;
  }
  return outcome;
}

StageOutcome SolveGaussNewton(const std::vector<PreparedSegment>& segments,
                              const FreeLayout& free,
                              const std::shared_ptr<const MotionModel>& model,
                              const StageSettings& settings,
                              std::vector<double>* values) {
  const double tolerance = settings.tolerance;
  const int max_iterations = settings.max_iterations;
  StageOutcome outcome;
  const int k = free.size();
  const int points = CountPoints(segments);
  const int dof = 3 * points - k;
  std::vector<double> scale(k, 1.0);
  double old_e = -1.0;
  std::vector<double> last_good = *values;
  for (int iteration = 0; !StopRequested(); ++iteration) {
    Assembly a = Assemble(segments, free, model, *values, scale);
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
      a = Assemble(segments, free, model, *values, scale);
      Information(a, &jtj, &ressum, &jtr);
    }
    outcome.ressum = ressum;
    last_good = *values;
    const double e = std::sqrt(ressum / dof);
    if (old_e >= 0.0 && std::abs(e - old_e) < tolerance) {
      outcome.converged = true;
      outcome.termination =
          kToleranceTermination + FormatNumber("%g", tolerance);
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
    const SymmetricEigen eigen(jtj);
    const Eigen::VectorXd lambda = eigen.values();
    Eigen::VectorXd du = Eigen::VectorXd::Zero(k);
    for (int j = 0; j < k; ++j) {
      if (lambda(j) > 1e-14 * lambda.maxCoeff()) {
        const Eigen::VectorXd v = eigen.vectors().col(j);
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

}  // namespace fit3dof
