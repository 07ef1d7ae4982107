// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Covariance, rank analysis and named combinations at a fit's solution
// (uncertainty.h).

#include "uncertainty.h"

#include <glog/logging.h>

#include <Eigen/Dense>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "assembly.h"
#include "ceres/ceres.h"
#include "colored_covariance.h"
#include "fit3dof/angles.h"
#include "fit3dof/input_error.h"
#include "format.h"
#include "symmetric_eigen.h"

namespace fit3dof {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

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
         FormatNumber("%.3g", std::abs(c)) + " " + b + " is determined";
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " and " : ", ";
    out += names[i];
  }
  return out;
}

std::string NoEffect(const std::string& name) {
  return name +
         " is not determined by the data (it has no effect on the fitted "
         "motion)";
}

// The information matrix at the solution, in unit-column coordinates, with
// the Jacobian it comes from and the coordinates the data cannot see.
struct SolutionInformation {
  ceres::CRSMatrix jacobian;  // every coordinate's column, scaled
  std::vector<double> residuals;
  Eigen::MatrixXd jtj;
  double ressum = 0.0;
  std::vector<double> scale;       // physical value = scale * u
  std::vector<bool> null_columns;  // no effect on the motion
};

SolutionInformation InformationAtSolution(const FitProblem& p,
                                          const std::vector<double>& values,
                                          const std::string& source) {
  const int k = p.free.size();
  SolutionInformation info;
  info.scale.assign(k, 1.0);
  const Assembly a = Assemble(p.segments, p.free, p.model, values, info.scale);
  if (!EvaluateJacobian(a, &info.jacobian, &info.residuals)) {
    throw InputError(source +
                     ": the motion cannot be integrated at the solution");
  }
  NormalEquations(info.jacobian, info.residuals, &info.jtj, &info.ressum);
  info.null_columns = NullColumns(info.jtj);
  info.scale = ColumnScales(info.jtj, info.scale);
  // In the coordinates u = value / scale each column is the physical one
  // times its scale: no second evaluation of the motion's Jacobian, and
  // J^T J scales the same way.
  for (size_t v = 0; v < info.jacobian.values.size(); ++v) {
    info.jacobian.values[v] *= info.scale[info.jacobian.cols[v]];
  }
  const Eigen::Map<const Eigen::VectorXd> s(info.scale.data(), k);
  info.jtj = s.asDiagonal() * info.jtj * s.asDiagonal();
  return info;
}

// B = (J^T J)^-1 over the coordinates not held, from the singular values
// of the Jacobian already evaluated (what ceres::Covariance's DENSE_SVD
// computes, but it evaluates the Jacobian again: with the second
// evaluation for the scaled columns, that was a quarter of a search fit's
// time on an 800-sample record); false when the matrix is too
// ill-conditioned for it. Held coordinates keep zero rows and columns.
bool SvdCovariance(const SolutionInformation& info, Eigen::MatrixXd* cov_u) {
  // Rank-deficient fits go to the named-null-space path.
  const SymmetricEigen eigen(info.jtj);
  const Eigen::VectorXd lambda = eigen.values();
  if (!(lambda.minCoeff() > 1e-13 * lambda.maxCoeff())) return false;
  const int k = static_cast<int>(info.jtj.rows());
  std::vector<int> column(k, -1);
  int kept = 0;
  for (int g = 0; g < k; ++g) {
    if (!info.null_columns[g]) column[g] = kept++;
  }
  if (kept == 0) return false;
  const ceres::CRSMatrix& crs = info.jacobian;
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(crs.num_rows, kept);
  for (int r = 0; r < crs.num_rows; ++r) {
    for (int a = crs.rows[r]; a < crs.rows[r + 1]; ++a) {
      if (column[crs.cols[a]] >= 0) j(r, column[crs.cols[a]]) = crs.values[a];
    }
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(j, Eigen::ComputeThinV);
  const Eigen::VectorXd s = svd.singularValues();
  if (!(s.minCoeff() * s.minCoeff() > 1e-14 * s.maxCoeff() * s.maxCoeff())) {
    return false;
  }
  const Eigen::MatrixXd v = svd.matrixV();
  const Eigen::MatrixXd inverse =
      v * s.array().square().inverse().matrix().asDiagonal() * v.transpose();
  cov_u->setZero(k, k);
  for (int a = 0; a < k; ++a) {
    for (int b = 0; b < k; ++b) {
      if (column[a] >= 0 && column[b] >= 0) {
        (*cov_u)(a, b) = inverse(column[a], column[b]);
      }
    }
  }
  return true;
}

// Rank deficient: the pseudo-inverse for the parameters outside the null
// space, and each null direction named (with the determined combination
// when two parameters share it). Marks the parameters involved as not
// determined; returns how many directions it named.
int PseudoInverse(const SolutionInformation& info,
                  const std::vector<std::string>& names,
                  Eigen::MatrixXd* cov_u,
                  std::vector<bool>* determined,
                  std::vector<std::string>* warnings) {
  const int k = static_cast<int>(names.size());
  const SymmetricEigen eigen(info.jtj);
  const Eigen::VectorXd lambda = eigen.values();
  const double lambda_max = lambda.maxCoeff();
  cov_u->setZero(k, k);
  int named = 0;
  for (int e = 0; e < k; ++e) {
    const Eigen::VectorXd v = eigen.vectors().col(e);
    bool null_coordinate = false;
    for (int g = 0; g < k; ++g) {
      null_coordinate |= info.null_columns[g] && std::abs(v(g)) > 0.5;
    }
    if (null_coordinate) continue;  // already named
    if (lambda(e) > 1e-14 * lambda_max) {
      *cov_u += v * v.transpose() / lambda(e);
      continue;
    }
    ++named;
    std::vector<std::string> involved;
    std::vector<int> index;
    for (int g = 0; g < k; ++g) {
      if (std::abs(v(g)) > 0.2) {
        involved.push_back(names[g]);
        index.push_back(g);
        (*determined)[g] = false;
      }
    }
    std::string message =
        involved.size() == 1
            ? NoEffect(involved[0])
            : JoinNames(involved) +
                  " cannot be separated (the information matrix is "
                  "singular)";
    if (index.size() == 2) {
      // Null direction in physical units n; determined w = (n_b, -n_a).
      const double na = info.scale[index[0]] * v(index[0]);
      const double nb = info.scale[index[1]] * v(index[1]);
      message += ": " + Combination(involved[0], involved[1], nb, -na);
    }
    warnings->push_back(message);
  }
  return named;
}

// Highly correlated pairs: the combination that is determined, with its
// value and error.
void NamePairs(const Eigen::MatrixXd& cov,
               const std::vector<std::string>& names,
               const std::vector<double>& values,
               Uncertainty* u) {
  const int k = static_cast<int>(names.size());
  for (int a = 0; a < k; ++a) {
    for (int b = a + 1; b < k; ++b) {
      const double r = u->correlation(a, b);
      if (!(std::abs(r) > 0.99)) continue;
      Eigen::Matrix2d block;
      block << cov(a, a), cov(a, b), cov(b, a), cov(b, b);
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(block);
      // Largest-variance direction n is undetermined; w = (n_b, -n_a).
      const Eigen::Vector2d n = eigen.eigenvectors().col(1);
      Eigen::Vector2d w(n(1), -n(0));
      w /= w(0);
      const double value = w(0) * values[a] + w(1) * values[b];
      const double error = u->probable_error * std::sqrt(w.dot(block * w));
      u->warnings.push_back(
          names[a] + " and " + names[b] + " are " + Percent(std::abs(r)) +
          " correlated: " + Combination(names[a], names[b], w(0), w(1)) + " (" +
          names[a] + (w(1) >= 0 ? " + " : " - ") +
          FormatNumber("%.4g", std::abs(w(1))) + " " + names[b] + " = " +
          FormatNumber("%.6g", value) + " +- " + FormatNumber("%.2g", error) +
          ")");
    }
  }
}

// Groups of three or more nearly dependent parameters (e.g. Cm_alpha, t1,
// t3 for small motion, the report's Eq. 43). The smallest eigenvalues of
// the correlation matrix measure how much the others inflate a
// combination's variance: a well-determined fit like Table 6 reaches
// 1e-4 (its initial conditions are correlated with the damping terms),
// the Eq. 43 case 1e-11. Below 1e-6 (a thousand-fold inflation of the
// error) the group is named.
void NameGroups(const std::vector<std::string>& names, Uncertainty* u) {
  if (!u->correlation.allFinite()) return;
  const int k = static_cast<int>(names.size());
  const SymmetricEigen eigen(u->correlation);
  for (int e = 0; e < k; ++e) {
    if (eigen.values()(e) > 1e-6) continue;
    const Eigen::VectorXd v = eigen.vectors().col(e);
    std::vector<std::string> involved;
    for (int g = 0; g < k; ++g) {
      if (std::abs(v(g)) > 0.25) involved.push_back(names[g]);
    }
    if (involved.size() >= 3) {
      u->warnings.push_back(JoinNames(involved) +
                            " are nearly dependent: the data determine only " +
                            std::to_string(involved.size() - 1) +
                            " combinations of these " +
                            std::to_string(involved.size()) + " parameters");
    }
  }
}

// A segment's fitted angles (rad; phi, theta, psi), its residual rows
// starting at `row`: the measured ones plus the residuals. Fitted, not
// measured: a roll angle sensed in steps would hide its own steps' error
// from its harmonics.
std::array<Eigen::VectorXd, 3> FittedAngles(const PreparedSegment& segment,
                                            const SolutionInformation& info,
                                            int row) {
  const int n = segment.data.size();
  std::array<Eigen::VectorXd, 3> fitted;
  for (int c = 0; c < 3; ++c) {
    fitted[c].resize(n);
    const std::vector<double>& measured = segment.data.channel(c);
    for (int i = 0; i < n; ++i) {
      fitted[c](i) =
          (measured[i] + info.residuals[row + 3 * i + c] * segment.sigma[c]) /
          kDegreesPerRadian;
    }
  }
  return fitted;
}

// Each segment's channels as residual series: the Jacobian rows and the
// weighted residuals of phi, theta, psi in time order, with the fitted
// roll (for roll-locked lines) and, in pitch and yaw, the channel's own
// angle (for calibration terms).
std::vector<ResidualSeries> SeriesOf(const FitProblem& problem,
                                     const SolutionInformation& info) {
  const ceres::CRSMatrix& crs = info.jacobian;
  std::vector<ResidualSeries> series;
  int row = 0;
  for (const PreparedSegment& segment : problem.segments) {
    const int n = segment.data.size();
    const std::array<Eigen::VectorXd, 3> fitted =
        FittedAngles(segment, info, row);
    for (int channel = 0; channel < 3; ++channel) {
      ResidualSeries s{
          Eigen::MatrixXd::Zero(n, crs.num_cols),
          Eigen::VectorXd(n),
          Eigen::Map<const Eigen::VectorXd>(segment.data.t.data(), n),
          fitted[0],
          channel == 0 ? Eigen::VectorXd() : fitted[channel],
          static_cast<int>(&segment - problem.segments.data()),
          segment.min_lag_window};
      for (int i = 0; i < n; ++i) {
        const int r = row + 3 * i + channel;
        s.residual(i) = info.residuals[r];
        for (int a = crs.rows[r]; a < crs.rows[r + 1]; ++a) {
          s.jacobian(i, crs.cols[a]) = crs.values[a];
        }
      }
      series.push_back(std::move(s));
    }
    row += 3 * n;
  }
  CHECK_EQ(row, crs.num_rows);
  return series;
}

// The standard errors with the residuals' own correlation
// (colored_covariance.h), and each series' statistics.
void CorrectForCorrelation(const FitProblem& problem,
                           const SolutionInformation& info,
                           const Eigen::MatrixXd& cov_u,
                           const std::vector<bool>& determined,
                           int undetermined,
                           Uncertainty* u) {
  const int k = problem.free.size();
  std::vector<SeriesCorrelation> stats;
  const Eigen::MatrixXd bracket =
      ColoredInformation(SeriesOf(problem, info), cov_u, &stats);
  const Eigen::MatrixXd colored = SandwichCovariance(cov_u, bracket);
  // The residual variances are sums over N samples of residuals that have
  // spent N_free degrees of freedom (as E does, Eq. 26).
  const double n = 3.0 * problem.points;
  const double dof = n / std::max(1.0, n - (k - undetermined));
  u->standard_error.assign(k, kNaN);
  for (int g = 0; g < k; ++g) {
    if (determined[g]) {
      u->standard_error[g] = info.scale[g] * std::sqrt(dof * colored(g, g));
    }
  }
  u->series = std::move(stats);
}

}  // namespace

Uncertainty EstimateUncertainty(const FitProblem& problem,
                                const std::vector<double>& values,
                                const std::string& source) {
  const int k = problem.free.size();
  const std::vector<std::string>& names = problem.names;
  SolutionInformation info = InformationAtSolution(problem, values, source);
  Uncertainty u;
  u.sum_of_residuals = std::sqrt(info.ressum);
  int undetermined = 0;
  std::vector<bool> determined(k, true);
  for (int g = 0; g < k; ++g) {
    if (!info.null_columns[g]) continue;
    ++undetermined;
    determined[g] = false;
    u.warnings.push_back(NoEffect(names[g]));
    // Keep the rank analysis away from it.
    info.jtj.row(g).setZero();
    info.jtj.col(g).setZero();
    info.jtj(g, g) = 1.0;
  }
  Eigen::MatrixXd cov_u;
  if (!SvdCovariance(info, &cov_u)) {
    undetermined +=
        PseudoInverse(info, names, &cov_u, &determined, &u.warnings);
  }
  const int dof = 3 * problem.points - k;
  u.probable_error = std::sqrt(info.ressum / (dof + undetermined));
  // Physical covariance and RMS errors (Eq. 27).
  Eigen::MatrixXd cov(k, k);
  for (int a = 0; a < k; ++a) {
    for (int b = 0; b < k; ++b) {
      cov(a, b) = info.scale[a] * cov_u(a, b) * info.scale[b];
    }
  }
  u.rms.resize(k);
  u.correlation = Eigen::MatrixXd::Constant(k, k, kNaN);
  for (int a = 0; a < k; ++a) {
    u.rms[a] = determined[a] ? u.probable_error * std::sqrt(cov(a, a)) : kNaN;
    for (int b = 0; b < k; ++b) {
      if (determined[a] && determined[b]) {
        u.correlation(a, b) = cov(a, b) / std::sqrt(cov(a, a) * cov(b, b));
      }
    }
  }
  u.scale = info.scale;
  CorrectForCorrelation(problem, info, cov_u, determined, undetermined, &u);
  NamePairs(cov, names, values, &u);
  NameGroups(names, &u);
  return u;
}

}  // namespace fit3dof
