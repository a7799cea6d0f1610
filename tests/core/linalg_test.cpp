#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid {
namespace linalg_test {

TEST(Linalg, EigenvaluesOfCompanionMatrixAreThePolynomialRoots) {
  // x^3 - 6 x^2 + 11 x - 6 = (x - 1)(x - 2)(x - 3)
  Eigen::MatrixXd companion(3, 3);
  companion << 0, 1, 0, 0, 0, 1, 6, -11, 6;
  const Eigen::VectorXcd eig = linalg::eigenvalues(companion);
  ASSERT_EQ(eig.size(), 3);
  std::vector<double> re;
  for (const std::complex<double>& z : eig) {
    EXPECT_NEAR(z.imag(), 0.0, 1e-12);
    re.push_back(z.real());
  }
  std::sort(re.begin(), re.end());
  EXPECT_NEAR(re[0], 1.0, 1e-12);
  EXPECT_NEAR(re[1], 2.0, 1e-12);
  EXPECT_NEAR(re[2], 3.0, 1e-12);
}

TEST(Linalg, SpectralRadiusOfScaledRotationIsTheScale) {
  const double r = 0.9, t = 0.7;
  Eigen::MatrixXd A(2, 2);
  A << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
  EXPECT_NEAR(linalg::spectral_radius(r * A), r, 1e-14);
  EXPECT_EQ(linalg::spectral_radius(Eigen::MatrixXd(0, 0)), 0.0);
}

TEST(Linalg, SymmetricEigenvaluesAscending) {
  Eigen::MatrixXd A(2, 2);
  A << 2, 1, 1, 2;
  const Eigen::VectorXd e = linalg::symmetric_eigenvalues(A);
  EXPECT_NEAR(e(0), 1.0, 1e-14);
  EXPECT_NEAR(e(1), 3.0, 1e-14);
}

TEST(Linalg, HermitianEigenOfAPauliMixture) {
  // 2 I + sigma_y = [[2, -i], [i, 2]]: eigenvalues 1 and 3, eigenvectors (1, -i)/sqrt2 and (1, i)/sqrt2.
  const std::complex<double> i(0.0, 1.0);
  Eigen::MatrixXcd A(2, 2);
  A << 2.0, -i, i, 2.0;
  const linalg::HermitianEigen e = linalg::hermitian_eigen(A);
  EXPECT_NEAR(e.values(0), 1.0, 1e-14);
  EXPECT_NEAR(e.values(1), 3.0, 1e-14);
  const Eigen::Vector2cd low = Eigen::Vector2cd(1.0, -i) / std::sqrt(2.0);
  EXPECT_NEAR(std::abs(e.vectors.col(0).dot(low)), 1.0, 1e-14);  // the same line, up to a phase
  EXPECT_LT((A * e.vectors - e.vectors * e.values.asDiagonal()).norm(), 1e-14);
  EXPECT_THROW(linalg::hermitian_eigen(Eigen::MatrixXcd::Ones(2, 3)), Error);
}

TEST(Linalg, SvdSolveRecoversExactSolutionOfConsistentOverdeterminedSystem) {
  Eigen::MatrixXd A(5, 2);
  A << 1, 0, 1, 1, 1, 2, 1, 3, 1, 4;
  const Eigen::Vector2d truth(2.0, -1.0);
  const Eigen::MatrixXd x = linalg::svd_solve(A, A * truth);
  EXPECT_NEAR(x(0, 0), 2.0, 1e-13);
  EXPECT_NEAR(x(1, 0), -1.0, 1e-13);
}

TEST(Linalg, SvdSolveOfRankDeficientSystemIsTheMinimumNormSolution) {
  // Columns equal: every x with x0 + x1 = 1 fits exactly; the shortest is (1/2, 1/2).
  Eigen::MatrixXd A(3, 2);
  A << 1, 1, 2, 2, 3, 3;
  Eigen::MatrixXd b(3, 1);
  b << 1, 2, 3;
  const Eigen::MatrixXd x = linalg::svd_solve(A, b);
  EXPECT_NEAR(x(0, 0), 0.5, 1e-13);
  EXPECT_NEAR(x(1, 0), 0.5, 1e-13);
}

TEST(Linalg, ComplexSvdSolveAndSingularValues) {
  using cd = std::complex<double>;
  Eigen::MatrixXcd A(2, 2);
  A << cd(0, 2), 0, 0, cd(3, 0);  // singular values 3 and 2
  Eigen::MatrixXcd b(2, 1);
  b << cd(0, 4), cd(6, 3);
  const Eigen::MatrixXcd x = linalg::svd_solve(A, b);
  EXPECT_NEAR(std::abs(x(0, 0) - cd(2, 0)), 0.0, 1e-14);
  EXPECT_NEAR(std::abs(x(1, 0) - cd(2, 1)), 0.0, 1e-14);
  const Eigen::VectorXd s = linalg::singular_values(A);
  EXPECT_NEAR(s(0), 3.0, 1e-14);
  EXPECT_NEAR(s(1), 2.0, 1e-14);
}

TEST(Linalg, ConditionNumberOfDiagonal) {
  const Eigen::MatrixXd A = Eigen::Vector2d(1e3, 1.0).asDiagonal();
  EXPECT_NEAR(linalg::condition_number(A), 1e3, 1e-10);
  EXPECT_TRUE(std::isinf(linalg::condition_number(Eigen::MatrixXd(Eigen::Vector2d(1.0, 0.0).asDiagonal()))));
}

TEST(Linalg, ThinSvdReconstructsTheMatrix) {
  Eigen::MatrixXd A(3, 2);
  A << 1, 2, 3, 4, 5, 6;
  const linalg::Svd s = linalg::svd(A);
  ASSERT_EQ(s.U.cols(), 2);
  EXPECT_LT((s.U * s.S.asDiagonal() * s.V.transpose() - A).norm(), 1e-13);
}

TEST(Linalg, QrRankSeesADependentColumn) {
  Eigen::MatrixXd A(4, 3);
  A << 1, 0, 1, 0, 1, 1, 1, 1, 2, 2, -1, 1;  // third column = first + second
  const Eigen::VectorXd b = A.col(0);
  EXPECT_EQ(linalg::qr_solve(A, b).rank, 2);
  const Eigen::MatrixXd full = A.leftCols(2);
  const linalg::RankedSolution<Eigen::VectorXd> ls = linalg::qr_solve(full, Eigen::VectorXd(2 * A.col(0) - A.col(1)));
  EXPECT_EQ(ls.rank, 2);
  EXPECT_NEAR(ls.x(0), 2.0, 1e-13);
  EXPECT_NEAR(ls.x(1), -1.0, 1e-13);
  EXPECT_EQ(linalg::rank(A), 2);
  EXPECT_EQ(linalg::qr_inverse_gram(A).size(), 0);
}

TEST(Linalg, QrInverseGramOfOrthogonalColumns) {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3, 2);
  J(0, 0) = 2.0;
  J(2, 1) = 4.0;  // J'J = diag(4, 16)
  const Eigen::MatrixXd g = linalg::qr_inverse_gram(J);
  EXPECT_NEAR(g(0, 0), 0.25, 1e-15);
  EXPECT_NEAR(g(1, 1), 1.0 / 16.0, 1e-15);
  EXPECT_NEAR(g(0, 1), 0.0, 1e-15);
}

TEST(Linalg, NullSpaceAndPseudoInverse) {
  Eigen::MatrixXd C(1, 3);
  C << 1, 1, 0;
  const Eigen::MatrixXd N = linalg::null_space(C);
  ASSERT_EQ(N.cols(), 2);
  EXPECT_LT((C * N).norm(), 1e-14);
  EXPECT_LT((N.transpose() * N - Eigen::MatrixXd::Identity(2, 2)).norm(), 1e-14);
  const linalg::PseudoInverse p = linalg::pseudo_inverse(C);
  EXPECT_EQ(p.rank, 1);
  EXPECT_LT((p.pinv - Eigen::Vector3d(0.5, 0.5, 0.0)).norm(), 1e-14);
  EXPECT_EQ(linalg::null_space(Eigen::MatrixXd::Identity(2, 2)).cols(), 0);
}

TEST(Linalg, ColumnSpaceIsAnOrthonormalBasisOfTheRange) {
  Eigen::MatrixXd A(4, 2);
  A << 1, 1, 2, 1, 3, 1, 4, 1;  // [k, 1]: rank 2
  const Eigen::MatrixXd Q = linalg::column_space(A);
  ASSERT_EQ(Q.cols(), 2);
  EXPECT_LT((Q.transpose() * Q - Eigen::MatrixXd::Identity(2, 2)).norm(), 1e-14);
  EXPECT_LT((A - Q * (Q.transpose() * A)).norm(), 1e-14);  // the columns of A lie in its span
  // A constant first column is the second one again: rank 1, spanned by (1, 1, 1, 1) / 2.
  A.col(0).setConstant(3.0);
  const Eigen::MatrixXd q = linalg::column_space(A);
  ASSERT_EQ(q.cols(), 1);
  EXPECT_NEAR(std::abs(q(0, 0)), 0.5, 1e-15);
  EXPECT_LT((q * q.transpose() - Eigen::MatrixXd::Constant(4, 4, 0.25)).norm(), 1e-14);
}

TEST(Linalg, Inverse3x3ByCofactors) {
  Eigen::Matrix3d A;
  A << 2, 0, 0, 1, 4, 0, 0, 0, 5;
  Eigen::Matrix3d truth;  // lower triangular: the inverse by forward substitution
  truth << 0.5, 0, 0, -0.125, 0.25, 0, 0, 0, 0.2;
  EXPECT_LT((linalg::inverse_3x3(A) - truth).norm(), 1e-15);
}

TEST(Linalg, SquareSolvers) {
  Eigen::MatrixXd A(2, 2);
  A << 4, 1, 1, 3;  // symmetric positive definite, det 11
  const Eigen::MatrixXd b = Eigen::Vector2d(1, 2);
  const Eigen::Vector2d truth(1.0 / 11.0, 7.0 / 11.0);
  EXPECT_LT((linalg::lu_solve(A, b).x - truth).norm(), 1e-15);
  EXPECT_GT(linalg::lu_solve(A, b).rcond, 0.1);
  EXPECT_LT((linalg::llt_solve(A, b) - truth).norm(), 1e-15);
  EXPECT_LT((linalg::ldlt_solve(A, b) - truth).norm(), 1e-15);
  EXPECT_LT((*linalg::regular_solve(A, b) - truth).norm(), 1e-15);
  EXPECT_LT((linalg::inverse(A) * A - Eigen::MatrixXd::Identity(2, 2)).norm(), 1e-15);
  EXPECT_LT((*linalg::regular_inverse(A) * A - Eigen::MatrixXd::Identity(2, 2)).norm(), 1e-15);
  Eigen::MatrixXd singular(2, 2);
  singular << 1, 2, 2, 4;
  EXPECT_FALSE(linalg::regular_inverse(singular).has_value());
  EXPECT_THROW(linalg::llt_solve(-A, b), Error);
}

TEST(Linalg, MatrixExpOfRotationGenerator) {
  const double w = 1.3;
  Eigen::MatrixXd G(2, 2);
  G << 0, -w, w, 0;
  const Eigen::MatrixXd E = linalg::matrix_exp(G);
  EXPECT_NEAR(E(0, 0), std::cos(w), 1e-14);
  EXPECT_NEAR(E(0, 1), -std::sin(w), 1e-14);
  EXPECT_NEAR(E(1, 0), std::sin(w), 1e-14);
  EXPECT_NEAR(E(1, 1), std::cos(w), 1e-14);
}

TEST(Linalg, MatrixLogInvertsMatrixExp) {
  Eigen::MatrixXd A(3, 3);
  A << -0.3, 0.2, 0.0, 0.1, -0.5, 0.4, 0.0, -0.2, -0.1;
  EXPECT_LT((linalg::matrix_log(linalg::matrix_exp(A)) - A).norm(), 1e-13);
}

TEST(Linalg, NonSquareInputThrowsWithItsDimensions) {
  const Eigen::MatrixXd A = Eigen::MatrixXd::Ones(3, 2);
  for (auto f : {+[](const Eigen::MatrixXd& m) { linalg::eigenvalues(m); },
                 +[](const Eigen::MatrixXd& m) { linalg::matrix_exp(m); },
                 +[](const Eigen::MatrixXd& m) { linalg::matrix_log(m); },
                 +[](const Eigen::MatrixXd& m) { linalg::inverse(m); }}) {
    try {
      f(A);
      ADD_FAILURE() << "no error on a 3x2 matrix";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("3x2"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(
      linalg::lu_solve(Eigen::MatrixXd(Eigen::MatrixXd::Identity(2, 2)), Eigen::MatrixXd(Eigen::MatrixXd::Ones(3, 1))),
      Error);
}

}  // namespace linalg_test
}  // namespace ambid
