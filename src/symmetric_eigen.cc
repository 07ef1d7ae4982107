// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The eigen-decomposition of a symmetric matrix (symmetric_eigen.h).

#include "symmetric_eigen.h"

#include <glog/logging.h>

#include <Eigen/Eigenvalues>

namespace fit3dof {

SymmetricEigen::SymmetricEigen(const Eigen::MatrixXd& symmetric) {
  CHECK_EQ(symmetric.rows(), symmetric.cols());
  // Eigen's solver reads the first coefficient of any matrix.
  if (symmetric.size() == 0) return;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(symmetric);
  values_ = eigen.eigenvalues();
  vectors_ = eigen.eigenvectors();
}

}  // namespace fit3dof
