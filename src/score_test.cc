// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The score (Lagrange-multiplier) test of a candidate effect at the current
// solution (diagnose.h): how much the weighted residual sum of squares
// would drop, to first order, if its parameters were freed.

#include <Eigen/Dense>
#include <algorithm>

#include "assembly.h"
#include "ceres/crs_matrix.h"
#include "diagnose_internal.h"
#include "fit3dof/fit.h"
#include "fit3dof/parameters.h"
#include "fit_problem.h"
#include "symmetric_eigen.h"

namespace fit3dof {
namespace {

// Directions of the effect's information (scaled to its largest) below
// this fraction are spanned by the free parameters: dropped from the
// score, and an effect no more novel than this is an exact twin.
constexpr double kRankDrop = 1e-6;

// How close (relative) a candidate's residuals at the solution, its terms
// at their start, must be to the solution's for the solution's Jacobian to
// serve its score test: the same motion but for the rounding of terms that
// add zero.
constexpr double kSameMotion = 1e-9;

// The share of a near twin's signal a free parameter must carry to be
// listed among those the twin moves (TwinShifts).
constexpr double kCarried = 0.1;

// Pseudo-inverse of a symmetric positive semi-definite matrix, dropping
// directions below `relative` of the largest eigenvalue; `rank` receives
// the number kept.
Eigen::MatrixXd PseudoInverse(const Eigen::MatrixXd& m,
                              double relative,
                              int* rank) {
  if (m.rows() == 0) {
    if (rank) *rank = 0;
    return m;
  }
  const SymmetricEigen eigen(m);
  const Eigen::VectorXd lambda = eigen.values();
  const double limit = relative * std::max(lambda.maxCoeff(), 0.0);
  Eigen::MatrixXd inverse = Eigen::MatrixXd::Zero(m.rows(), m.cols());
  int kept = 0;
  for (int j = 0; j < lambda.size(); ++j) {
    if (lambda(j) > limit && lambda(j) > 0.0) {
      const Eigen::VectorXd v = eigen.vectors().col(j);
      inverse += v * v.transpose() / lambda(j);
      ++kept;
    }
  }
  if (rank) *rank = kept;
  return inverse;
}

// The smallest eigenvalue of the Schur complement `schur` of the
// effect's information `icc`, each term scaled to its own information:
// the least fraction of any direction's information left once the free
// parameters have taken theirs (1 - R^2 for one term).
double Novelty(const Eigen::MatrixXd& icc, const Eigen::MatrixXd& schur) {
  const Eigen::ArrayXd own = icc.diagonal().array();
  if ((own <= 0.0).any()) return 0.0;
  const Eigen::VectorXd scale = own.rsqrt().matrix();
  const Eigen::MatrixXd scaled =
      scale.asDiagonal() * schur * scale.asDiagonal();
  const SymmetricEigen eigen(scaled);
  return std::max(eigen.values().minCoeff(), 0.0);
}

// The information of a candidate's `added` terms (c) and of the parameters
// already free (f) at the current solution, split into blocks.
struct ScoreInformation {
  Linearization l;
  std::vector<int> c_index, f_index;  // rows of l.jtj
  Eigen::MatrixXd iff, icf, icc;
  Eigen::VectorXd gf, gc;  // the parts of J^T r
};

bool SplitInformation(const Case& candidate,
                      const std::vector<std::string>& added,
                      const std::vector<TimeHistory>& data,
                      ScoreInformation* info) {
  Linearization& l = info->l;
  if (!Linearize(candidate, data, &l)) return false;
  const auto& table = ParameterTable(candidate.model);
  for (size_t g = 0; g < l.names.size(); ++g) {
    const bool is_added =
        l.segments[g] < 0 &&
        std::find(added.begin(), added.end(), table[l.positions[g]].name) !=
            added.end();
    (is_added ? info->c_index : info->f_index).push_back(static_cast<int>(g));
  }
  auto block = [&](const std::vector<int>& rows, const std::vector<int>& cols) {
    Eigen::MatrixXd m(rows.size(), cols.size());
    for (size_t i = 0; i < rows.size(); ++i) {
      for (size_t j = 0; j < cols.size(); ++j)
        m(i, j) = l.jtj(rows[i], cols[j]);
    }
    return m;
  };
  auto part = [&](const std::vector<int>& rows) {
    Eigen::VectorXd v(rows.size());
    for (size_t i = 0; i < rows.size(); ++i) v(i) = l.jtr(rows[i]);
    return v;
  };
  info->iff = block(info->f_index, info->f_index);
  info->icf = block(info->c_index, info->f_index);
  info->icc = block(info->c_index, info->c_index);
  info->gf = part(info->f_index);
  info->gc = part(info->c_index);
  return !info->c_index.empty();
}

// The Jacobian (unit scale: with respect to the values) and the weighted
// residuals of a problem at its values; false if the motion cannot be
// integrated.
bool DenseJacobian(const FitProblem& p,
                   Eigen::MatrixXd* jacobian,
                   Eigen::VectorXd* residuals) {
  const Assembly a = Assemble(p.segments,
                              p.free,
                              p.model,
                              p.values,
                              std::vector<double>(p.free.size(), 1.0));
  ceres::CRSMatrix crs;
  std::vector<double> r;
  if (!EvaluateJacobian(a, &crs, &r)) return false;
  *jacobian = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int row = 0; row < crs.num_rows; ++row) {
    for (int e = crs.rows[row]; e < crs.rows[row + 1]; ++e) {
      (*jacobian)(row, crs.cols[e]) = crs.values[e];
    }
  }
  *residuals = Eigen::Map<const Eigen::VectorXd>(r.data(), r.size());
  return true;
}

// `p` with only its shared coordinates `kept` (global indices, in order)
// free, every other one frozen at its value.
FitProblem OnlyFree(const FitProblem& p, const std::vector<int>& kept) {
  FitProblem only = p;
  for (PreparedSegment& segment : only.segments) {
    for (int g = 0; g < p.free.size(); ++g) {
      if (p.free.segment[g] < 0) segment.base[p.free.position[g]] = p.values[g];
    }
    segment.own.clear();  // their values are in base
  }
  only.free.shared.clear();
  only.free.position.clear();
  only.free.segment.clear();
  only.values.clear();
  only.names.clear();
  for (int g : kept) {
    CHECK_LT(p.free.segment[g], 0) << "a segment's own coordinate";
    only.free.shared.push_back(p.free.position[g]);
    only.free.position.push_back(p.free.position[g]);
    only.free.segment.push_back(-1);
    only.values.push_back(p.values[g]);
    only.names.push_back(p.names[g]);
  }
  only.free.own_offset.assign(p.segments.size(), static_cast<int>(kept.size()));
  return only;
}

// The candidate's information from `base`'s Jacobian of the parameters
// free at the solution and its own of the added terms alone; false where
// that does not hold (InformationAtSolution says when), *info untouched.
bool SharedInformation(const Case& candidate,
                       const std::vector<std::string>& added,
                       const std::vector<TimeHistory>& data,
                       const InformationAtSolution& base,
                       ScoreInformation* info) {
  if (!base.ok || candidate.model != base.model) return false;
  const FitProblem p = PrepareProblem(candidate, data);
  const auto& table = ParameterTable(candidate.model);
  std::vector<int> c_index;
  std::vector<std::string> f_names;
  for (int g = 0; g < p.free.size(); ++g) {
    const bool is_added =
        p.free.segment[g] < 0 &&
        std::find(added.begin(), added.end(), table[p.free.position[g]].name) !=
            added.end();
    if (is_added) {
      c_index.push_back(g);
    } else {
      f_names.push_back(p.names[g]);
    }
  }
  if (c_index.empty() || f_names != base.names) return false;
  Eigen::MatrixXd jc;
  Eigen::VectorXd r;
  if (!DenseJacobian(OnlyFree(p, c_index), &jc, &r)) return false;
  // The terms at their start must leave the motion the solution's.
  if (r.size() != base.residuals.size() ||
      (r - base.residuals).norm() > kSameMotion * (1.0 + r.norm())) {
    return false;
  }
  info->l.points = p.points;
  info->l.ressum = r.squaredNorm();
  info->c_index = c_index;
  info->iff = base.information;
  info->icf = jc.transpose() * base.jacobian;
  info->icc = jc.transpose() * jc;
  info->gf = base.jacobian.transpose() * r;
  info->gc = jc.transpose() * r;
  return true;
}

CandidateScore ScoreOf(const ScoreInformation& info, const std::string& id) {
  CandidateScore score;
  score.effect = id;
  const Eigen::MatrixXd& icf = info.icf;
  const Eigen::MatrixXd& icc = info.icc;
  const Eigen::MatrixXd iff_inverse = PseudoInverse(info.iff, 1e-14, nullptr);
  const Eigen::MatrixXd schur = icc - icf * iff_inverse * icf.transpose();
  const Eigen::VectorXd g = info.gc - icf * iff_inverse * info.gf;
  int rank = 0;
  // Directions the parameters already free span (Eq. 43) carry no new
  // information: they drop out here.
  const double own = icc.diagonal().maxCoeff();
  Eigen::MatrixXd schur_scaled = schur / std::max(own, 1e-300);
  const Eigen::MatrixXd inverse =
      PseudoInverse(schur_scaled, kRankDrop, &rank) / std::max(own, 1e-300);
  const int dof = 3 * info.l.points - static_cast<int>(info.iff.rows());
  const double variance = info.l.ressum / std::max(dof, 1);
  score.score = g.dot(inverse * g) / variance;
  score.dof = rank;
  score.novelty = Novelty(icc, schur);
  return score;
}

}  // namespace

InformationAtSolution::InformationAtSolution(
    const Case& at, const std::vector<TimeHistory>& data) {
  const FitProblem p = PrepareProblem(at, data);
  model = at.model;
  names = p.names;
  ok = DenseJacobian(p, &jacobian, &residuals);
  if (ok) information = jacobian.transpose() * jacobian;
}

CandidateScore Score(const Case& candidate,
                     const std::vector<std::string>& added,
                     const std::string& id,
                     const std::vector<TimeHistory>& data,
                     const InformationAtSolution* at) {
  ScoreInformation info;
  if (at == nullptr || !SharedInformation(candidate, added, data, *at, &info)) {
    if (!SplitInformation(candidate, added, data, &info)) {
      CandidateScore none;
      none.effect = id;
      return none;
    }
  }
  return ScoreOf(info, id);
}

bool SharesInformation(const Case& candidate,
                       const std::vector<std::string>& added,
                       const std::vector<TimeHistory>& data,
                       const InformationAtSolution& at) {
  ScoreInformation info;
  return SharedInformation(candidate, added, data, at, &info);
}

std::vector<TwinShift> TwinShifts(const Case& candidate,
                                  const std::vector<std::string>& added,
                                  const std::vector<TimeHistory>& data) {
  std::vector<TwinShift> shifts;
  ScoreInformation info;
  if (!SplitInformation(candidate, added, data, &info)) return shifts;
  // Least squares without the terms projects their signal onto the free
  // parameters' sensitivities: a term at m moves them by
  // iff^-1 I_fc m.
  const Eigen::MatrixXd per_unit =
      PseudoInverse(info.iff, 1e-14, nullptr) * info.icf.transpose();
  const auto& table = ParameterTable(candidate.model);
  for (size_t j = 0; j < info.c_index.size(); ++j) {
    const int c = info.c_index[j];
    const double own = std::sqrt(std::max(info.icc(j, j), 1e-300));
    for (size_t i = 0; i < info.f_index.size(); ++i) {
      const int f = info.f_index[i];
      // The model's own coefficients, not a segment's initial conditions;
      // each listed when it carries a tenth of the term's signal or more.
      const double carried =
          std::abs(per_unit(i, j)) * std::sqrt(std::max(info.iff(i, i), 0.0));
      if (info.l.segments[f] >= 0 || carried < kCarried * own) continue;
      shifts.push_back({table[info.l.positions[c]].name,
                        table[info.l.positions[f]].name,
                        per_unit(i, j)});
    }
  }
  return shifts;
}

bool IsTwin(const CandidateScore& score) {
  // Less than 1% of its information left once the free parameters have
  // theirs.
  return score.novelty < 0.01;
}

bool IsNearTwin(const CandidateScore& score) {
  // Below the rank drop: an exact twin, its terms and the free parameters
  // one combination to the record (Eq. 43's tunnel terms, 1e-9), which no
  // fit tells apart; the nominal fit's convention holds it absent.
  return IsTwin(score) && score.novelty >= kRankDrop;
}

}  // namespace fit3dof
