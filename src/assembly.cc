// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A FitProblem as a Ceres problem, and its normal equations (assembly.h).

#include "assembly.h"

#include <glog/logging.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "fit3dof/thread_budget.h"

namespace fit3dof {

Assembly Assemble(const std::vector<PreparedSegment>& segments,
                  const FreeLayout& free,
                  const std::shared_ptr<const MotionModel>& model,
                  const std::vector<double>& values,
                  const std::vector<double>& scale,
                  ceres::EvaluationCallback* evaluation_callback) {
  Assembly a;
  ceres::Problem::Options options;
  options.evaluation_callback = evaluation_callback;
  a.problem = std::make_unique<ceres::Problem>(options);
  const int ks = static_cast<int>(free.shared.size());
  a.u.resize(free.size());
  for (int g = 0; g < free.size(); ++g) a.u[g] = values[g] / scale[g];
  if (ks > 0) a.blocks.push_back(a.u.data());
  for (size_t s = 0; s < segments.size(); ++s) {
    std::vector<double*> blocks;
    if (ks > 0) blocks.push_back(a.u.data());
    if (!segments[s].own.empty()) {
      blocks.push_back(a.u.data() + free.own_offset[s]);
      a.blocks.push_back(blocks.back());
    }
    a.segment_blocks.push_back(blocks);
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
        model, base, positions, ks, segment_scale, p.data, p.sigma);
    cost->set_innovation_weights(p.innovation_weights);
    cost->set_ties(free.ties);
    a.problem->AddResidualBlock(cost, nullptr, a.segment_blocks[s]);
    a.costs.push_back(cost);
  }
  return a;
}

std::vector<double> FreeValues(const Assembly& a,
                               const FreeLayout& free,
                               const std::vector<double>& scale) {
  std::vector<double> values(free.size());
  for (int g = 0; g < free.size(); ++g) values[g] = scale[g] * a.u[g];
  return values;
}

std::vector<double> SegmentFullValues(const Assembly& a, size_t s) {
  const std::vector<double*>& blocks = a.segment_blocks[s];
  const std::vector<const double*> values(blocks.begin(), blocks.end());
  return a.costs[s]->FullValues(values.data());
}

int HelperThreadsFor(const Assembly& a) { return a.costs.size() == 2 ? 1 : 0; }

bool EvaluateJacobian(const Assembly& a,
                      ceres::CRSMatrix* jacobian,
                      std::vector<double>* residuals) {
  ceres::Problem::EvaluateOptions options;
  options.parameter_blocks = a.blocks;
  const ThreadLease lease(HelperThreadsFor(a));
  options.num_threads = 1 + lease.count();
  double cost = 0.0;
  if (!a.problem->Evaluate(options, &cost, residuals, nullptr, jacobian)) {
    return false;
  }
  // Columns in global free order need every coordinate in the Jacobian: an
  // assembly with held coordinates (SubsetManifold) has fewer columns.
  int ambient = 0;
  for (double* block : a.blocks) {
    ambient += a.problem->ParameterBlockSize(block);
  }
  CHECK_EQ(jacobian->num_cols, ambient)
      << "EvaluateJacobian() needs an assembly without held coordinates";
  return true;
}

void NormalEquations(const ceres::CRSMatrix& crs,
                     const std::vector<double>& residuals,
                     Eigen::MatrixXd* jtj,
                     double* ressum,
                     Eigen::VectorXd* jtr) {
  // J^T J and J^T r row by row from the CRS form: no second copy of a
  // Jacobian that has 3 rows per sample.
  const int k = crs.num_cols;
  jtj->setZero(k, k);
  if (jtr != nullptr) jtr->setZero(k);
  *ressum = 0.0;
  for (int r = 0; r < crs.num_rows; ++r) {
    *ressum += residuals[r] * residuals[r];
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
}

bool Information(const Assembly& a,
                 Eigen::MatrixXd* jtj,
                 double* ressum,
                 Eigen::VectorXd* jtr) {
  ceres::CRSMatrix crs;
  std::vector<double> residuals;
  if (!EvaluateJacobian(a, &crs, &residuals)) return false;
  NormalEquations(crs, residuals, jtj, ressum, jtr);
  return true;
}

bool SumOfSquares(const Assembly& a, double* ressum) {
  double cost = 0.0;
  if (!a.problem->Evaluate(ceres::Problem::EvaluateOptions(),
                           &cost,
                           nullptr,
                           nullptr,
                           nullptr)) {
    return false;
  }
  *ressum = 2.0 * cost;
  return std::isfinite(*ressum);
}

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

// Real columns span about 1e-1 (deg per unit of a cubic damping term) to
// 1e8 (deg per unit of Cl_0).
std::vector<bool> NullColumns(const Eigen::MatrixXd& jtj) {
  const double largest = jtj.diagonal().maxCoeff();
  std::vector<bool> null(jtj.rows());
  for (int g = 0; g < jtj.rows(); ++g) {
    null[g] = !(jtj(g, g) > 1e-20 * largest);
  }
  return null;
}

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

}  // namespace fit3dof
