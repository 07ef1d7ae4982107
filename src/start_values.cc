// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Starting values from the data (start_values.h): the epicyclic fit of
// theta + i psi and the coefficients it implies.

#include "fit3dof/start_values.h"

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>

#include "fit3dof/angles.h"
#include "fit3dof/data_selection.h"
#include "fit3dof/model_conversion.h"
#include "fit3dof/scaling.h"
#include "fit3dof/time_history.h"

namespace fit3dof {
namespace {

using Complex = std::complex<double>;

std::string Line(const char* format,
                 const std::string& name,
                 double value,
                 const std::string& why) {
  char buffer[256];
  std::snprintf(
      buffer, sizeof(buffer), format, name.c_str(), value, why.c_str());
  return buffer;
}

}  // namespace

EpicyclicFit FitEpicycle(const TimeHistory& record, double cycles) {
  EpicyclicFit fit;
  const int n_all = record.size();
  if (n_all < 12) {
    fit.message = "too few samples for the epicyclic fit";
    return fit;
  }
  const double dt = (record.t.back() - record.t.front()) / (n_all - 1);
  for (int i = 1; i < n_all; ++i) {
    if (std::abs(record.t[i] - record.t[i - 1] - dt) > 0.01 * dt) {
      fit.message = "the samples are not evenly spaced";
      return fit;
    }
  }
  const double period = CrossingPeriod(record, 2.0);
  int n = n_all;
  if (period > 0.0) {
    n = std::min(n_all, std::max(30, static_cast<int>(cycles * period / dt)));
  }
  // Differenced complex angle: the constant trim arm drops out.
  std::vector<Complex> y(n - 1);
  for (int i = 0; i + 1 < n; ++i) {
    y[i] = Complex(record.theta[i + 1] - record.theta[i],
                   record.psi[i + 1] - record.psi[i]) *
           kDegree;
  }
  const int m = static_cast<int>(y.size());
  const int pencil = std::max(3, m / 3);
  const int rows = m - pencil;
  if (rows < 3) {
    fit.message = "too few samples for the matrix pencil";
    return fit;
  }
  Eigen::MatrixXcd hankel(rows, pencil + 1);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c <= pencil; ++c) hankel(r, c) = y[r + c];
  }
  Eigen::JacobiSVD<Eigen::MatrixXcd> svd(hankel, Eigen::ComputeThinV);
  const Eigen::MatrixXcd v = svd.matrixV().leftCols(2);
  const Eigen::MatrixXcd v1 = v.topRows(pencil);
  const Eigen::MatrixXcd v2 = v.bottomRows(pencil);
  // The rows of the Hankel matrix are combinations of [1, mu_j, ..., mu_j^L]
  // with mu_j = exp(s_j dt); they span the same space as the conjugated
  // right singular vectors, so conj(v2) = conj(v1) A with eigenvalues mu_j
  // (Hua and Sarkar's pencil, solved in the least-squares sense).
  const Eigen::MatrixXcd a =
      v1.conjugate().completeOrthogonalDecomposition().solve(v2.conjugate());
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> eigen(a);
  if (eigen.info() != Eigen::Success) {
    fit.message = "the matrix pencil has no eigenvalues";
    return fit;
  }
  Complex s[2];
  for (int j = 0; j < 2; ++j) s[j] = std::log(eigen.eigenvalues()(j)) / dt;
  if (!std::isfinite(std::abs(s[0])) || !std::isfinite(std::abs(s[1]))) {
    fit.message = "the motion has no clear epicyclic arms";
    return fit;
  }
  if (std::abs(s[1].imag()) > std::abs(s[0].imag())) std::swap(s[0], s[1]);
  fit.ok = true;
  fit.s1 = s[0];
  fit.s2 = s[1];
  return fit;
}

std::vector<std::string> EstimateStartValues(
    const Case& c,
    const TimeHistory& record,
    const std::vector<bool>& auto_start,
    std::vector<double>* values) {
  std::vector<std::string> log;
  const auto& table = ParameterTable(c.model);
  const std::vector<double> scale =
      InternalScaleFactors(c.model, c.body, c.flow);
  auto position = [&](const char* name) {
    return FindParameter(c.model, name);
  };
  auto wanted = [&](const char* name) {
    const int i = position(name);
    return i >= 0 && auto_start[i];
  };
  auto set_at = [&](int i, double internal, const std::string& why) {
    if (i < 0 || !auto_start[i]) return;
    (*values)[i] = internal / scale[i];
    log.push_back(Line("%s = %.6g (%s)", table[i].name, (*values)[i], why));
  };
  auto set = [&](const char* name, double internal, const std::string& why) {
    set_at(position(name), internal, why);
  };
  const bool symmetric = c.model == ModelKind::kSymmetric;
  // A symmetric-form constant, or its images in the asymmetric program
  // (Cm_alpha -> Cm_alpha and -Cn_beta, ...; model_conversion.h).
  auto set_symmetric =
      [&](const char* name, double internal, const std::string& why) {
        for (const ImagePosition& image :
             ImagesIn(c.model, ModelKind::kSymmetric, name)) {
          set_at(image.position, image.factor * internal, why);
        }
      };
  // Internal constants of the symmetric form, mapped to both programs.
  const double ratio = symmetric ? c.body.Ix / c.body.Iy
                                 : 2.0 * c.body.Ix / (c.body.Iy + c.body.Iz);
  const bool pitch_yaw_wanted =
      symmetric
          ? wanted("Cm_alpha") || wanted("Cm_q") || wanted("Cm_p_alpha")
          : wanted("Cm_alpha") || wanted("Cn_beta") || wanted("Cm_q") ||
                wanted("Cn_r") || wanted("Cm_p_beta") || wanted("Cn_p_alpha");
  // Spin from the roll record: phi = a + b t + c t^2 over the record.
  const std::vector<double> phi = UnwrapDegrees(record.phi);
  Eigen::MatrixXd basis(record.size(), 3);
  Eigen::VectorXd rhs(record.size());
  const double t0 = record.t.front();
  for (int i = 0; i < record.size(); ++i) {
    const double t = record.t[i] - t0;
    basis(i, 0) = 1.0;
    basis(i, 1) = t;
    basis(i, 2) = t * t;
    rhs(i) = phi[i] * kDegree;
  }
  const Eigen::Vector3d quad = basis.colPivHouseholderQr().solve(rhs);
  const double duration = record.t.back() - t0;
  const double p_mean = quad(1) + quad(2) * duration;  // rad/s
  const double pdot = 2.0 * quad(2);
  if (pitch_yaw_wanted) {
    const EpicyclicFit epicycle = FitEpicycle(record);
    if (!epicycle.ok) {
      log.push_back("epicyclic fit failed (" + epicycle.message +
                    "); pitch and yaw terms start at zero");
    } else {
      const Complex sum = epicycle.s1 + epicycle.s2;
      const Complex product = epicycle.s1 * epicycle.s2;
      char arms[160];
      std::snprintf(arms,
                    sizeof(arms),
                    "arms %.3f%+.3fi and %.3f%+.3fi 1/s",
                    epicycle.s1.real(),
                    epicycle.s1.imag(),
                    epicycle.s2.real(),
                    epicycle.s2.imag());
      const double c1 = -product.real();
      const double c2 = sum.real();
      const double c4p = -product.imag();
      set_symmetric(
          "Cm_alpha", c1, std::string("stiffness from the epicycle, ") + arms);
      set_symmetric(
          "Cm_q", c2, "damping from the epicycle (Cm_q + Cm_alphadot)");
      if (std::abs(p_mean) > 1e-3) {
        set_symmetric(
            "Cm_p_alpha", c4p / p_mean, "Magnus moment from the epicycle");
      }
      char spin[160];
      std::snprintf(
          spin,
          sizeof(spin),
          "epicycle: R p = %.4g rad/s against %.4g from the roll record",
          sum.imag(),
          ratio * p_mean);
      log.push_back(spin);
    }
  }
  if (std::abs(p_mean) > 1e-3) {
    if (wanted("Cl_p")) {
      set("Cl_p", pdot / p_mean, "roll damping from the decay of the spin");
    } else if (wanted("Cl_0")) {
      double roll_damping = 0.0;
      const int clp = position("Cl_p");
      if (clp >= 0) roll_damping = (*values)[clp] * scale[clp];
      set("Cl_0",
          pdot - roll_damping * p_mean,
          "roll torque from the spin rate");
    }
  }
  // Everything else that is auto starts at zero.
  for (size_t i = 0; i < auto_start.size(); ++i) {
    if (!auto_start[i] || IsInitialCondition(c.model, static_cast<int>(i)))
      continue;
    bool done = false;
    for (const std::string& line : log) {
      done |= line.rfind(table[i].name + " = ", 0) == 0;
    }
    if (!done) {
      (*values)[i] = 0.0;
      log.push_back(table[i].name + " = 0 (no linear-theory estimate)");
    }
  }
  return log;
}

}  // namespace fit3dof
