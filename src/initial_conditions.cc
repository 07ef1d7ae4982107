// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Initial conditions from the data (initial_conditions.h): angles and
// rates at the first sample from a local polynomial fit (INLCON = 0).

#include "fit3dof/initial_conditions.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "fit3dof/angles.h"
#include "fit3dof/data_selection.h"

namespace fit3dof {
namespace {

// Samples used by the local fits: enough to average the noise, few enough
// that a cubic follows the motion. With the report's 16 to 20 samples per
// cycle, a cubic through 7 samples (a third of a cycle) measured best on the
// Table 6 record: rate error 0.3 deg/s RMS at 0.01 deg noise, against 4.3
// deg/s for the two-point difference and 0.7 to 1.5 deg/s for 4 to 9
// samples (tests/initial_conditions_test.cc).
constexpr int kWindow = 7;
constexpr int kPolynomialDegree = 3;

}  // namespace

PolynomialEstimate LocalPolynomial(const std::vector<double>& t,
                                   const std::vector<double>& y,
                                   int count,
                                   int degree) {
  count = std::min<int>(count, static_cast<int>(t.size()));
  degree = std::max(0, std::min(degree, count - 1));
  PolynomialEstimate estimate;
  if (count <= 0) return estimate;
  estimate.value = y[0];
  if (count == 1) return estimate;
  // Scaled time keeps the Vandermonde matrix well conditioned.
  const double span = t[count - 1] - t[0];
  Eigen::MatrixXd a(count, degree + 1);
  Eigen::VectorXd b(count);
  for (int i = 0; i < count; ++i) {
    const double tau = (t[i] - t[0]) / span;
    double power = 1.0;
    for (int j = 0; j <= degree; ++j) {
      a(i, j) = power;
      power *= tau;
    }
    b(i) = y[i];
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
  estimate.value = c(0);
  estimate.slope = degree >= 1 ? c(1) / span : 0.0;
  return estimate;
}

std::array<double, 6> EstimateInitialConditions(ModelKind model,
                                                const TimeHistory& record,
                                                double theta_offset,
                                                double psi_offset) {
  const std::vector<double> phi = UnwrapDegrees(record.phi);
  std::vector<double> theta = record.theta;
  std::vector<double> psi = record.psi;
  for (double& x : theta) x -= theta_offset;
  for (double& x : psi) x -= psi_offset;
  const PolynomialEstimate f =
      LocalPolynomial(record.t, phi, kWindow, kPolynomialDegree);
  const PolynomialEstimate th =
      LocalPolynomial(record.t, theta, kWindow, kPolynomialDegree);
  const PolynomialEstimate ps =
      LocalPolynomial(record.t, psi, kWindow, kPolynomialDegree);
  if (model == ModelKind::kSymmetric) {
    return {f.value, f.slope, th.value, th.slope, ps.value, ps.slope};
  }
  // Euler rates to body rates, as the listing's ICS (degrees cancel in the
  // linear combination; the trigonometry needs radians).
  double p, q, r;
  EulerToBodyRates(std::sin(f.value * kDegree),
                   std::cos(f.value * kDegree),
                   std::sin(th.value * kDegree),
                   std::cos(th.value * kDegree),
                   f.slope,
                   th.slope,
                   ps.slope,
                   &p,
                   &q,
                   &r);
  return {f.value, th.value, ps.value, p, q, r};
}

}  // namespace fit3dof
