// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The eigen-decomposition of a symmetric matrix (information matrices,
// their Schur complements, correlation matrices), compiled in one unit:
// Eigen's SelfAdjointEigenSolver over dynamic matrices costs each unit that
// instantiates it about 6 s of compile time (12 s with the sanitizers), and
// the sanitized build compiles everything a second time in CI's 30 minutes.

#ifndef FIT3DOF_SRC_SYMMETRIC_EIGEN_H_
#define FIT3DOF_SRC_SYMMETRIC_EIGEN_H_

#include <Eigen/Core>

namespace fit3dof {

class SymmetricEigen {
 public:
  // Reads the lower triangle of `symmetric` (Eigen's convention); a 0 x 0
  // matrix has no pairs.
  explicit SymmetricEigen(const Eigen::MatrixXd& symmetric);

  // Ascending.
  const Eigen::VectorXd& values() const { return values_; }
  // Orthonormal columns, in the order of values().
  const Eigen::MatrixXd& vectors() const { return vectors_; }

 private:
  Eigen::VectorXd values_;
  Eigen::MatrixXd vectors_;
};

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_SYMMETRIC_EIGEN_H_
