// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "symmetric_eigen.h"

#include <Eigen/Core>

#include "gtest/gtest.h"

namespace fit3dof {
namespace {

TEST(SymmetricEigen, RebuildsTheMatrixFromAscendingOrthonormalPairs) {
  Eigen::MatrixXd a(3, 3);
  a << 4.0, 1.0, 0.5,  //
      1.0, 3.0, -0.2,  //
      0.5, -0.2, 1.0;
  const SymmetricEigen eigen(a);
  ASSERT_EQ(eigen.values().size(), 3);
  EXPECT_LT(eigen.values()(0), eigen.values()(1));
  EXPECT_LT(eigen.values()(1), eigen.values()(2));
  const Eigen::MatrixXd& v = eigen.vectors();
  EXPECT_LT((v.transpose() * v - Eigen::MatrixXd::Identity(3, 3)).norm(),
            1e-14);
  EXPECT_LT((v * eigen.values().asDiagonal() * v.transpose() - a).norm(),
            1e-13);
  EXPECT_NEAR(eigen.values().sum(), a.trace(), 1e-13);
}

TEST(SymmetricEigen, FindsTheNullDirectionOfASemidefiniteMatrix) {
  // Two equal columns: J^T J of a Jacobian whose parameters share one
  // effect has (1, -1) / sqrt(2) as its null direction.
  Eigen::MatrixXd j(3, 2);
  j << 1.0, 1.0,  //
      2.0, 2.0,   //
      -1.0, -1.0;
  const SymmetricEigen eigen(j.transpose() * j);
  EXPECT_NEAR(eigen.values()(0), 0.0, 1e-12);
  EXPECT_NEAR(eigen.values()(1), 12.0, 1e-12);
  EXPECT_NEAR(
      std::abs(eigen.vectors()(0, 0) + eigen.vectors()(1, 0)), 0.0, 1e-12);
}

TEST(SymmetricEigen, AnEmptyMatrixHasNoPairs) {
  const SymmetricEigen eigen(Eigen::MatrixXd(0, 0));
  EXPECT_EQ(eigen.values().size(), 0);
  EXPECT_EQ(eigen.vectors().size(), 0);
}

}  // namespace
}  // namespace fit3dof
