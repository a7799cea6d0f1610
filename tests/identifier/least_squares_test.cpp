#include "identifier/time_domain/least_squares.hpp"

#include <random>
#include <string>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace least_squares_test {

using testing::random_matrix;

// Independent reference: the minimum-norm solution by a full SVD of Phi itself.
Eigen::MatrixXd svd_solution(const Eigen::MatrixXd& phi, const Eigen::MatrixXd& z) { return linalg::svd_solve(phi, z); }

TEST(LeastSquares, ExactDataGiveTheTrueParameters) {
  std::mt19937_64 rng(11);
  const Eigen::MatrixXd phi = random_matrix(300, 7, rng);
  const Eigen::MatrixXd theta = random_matrix(7, 3, rng);
  const LeastSquaresSolution s = solve_least_squares(phi, phi * theta);
  EXPECT_LT((s.theta - theta).norm() / theta.norm(), 1e-13);
  EXPECT_EQ(s.rank, 7);
  EXPECT_EQ(s.rows, 300);
  EXPECT_EQ(s.degrees_of_freedom, 293);
  EXPECT_LT(s.residual_gram.norm(), 1e-20 * (phi * theta).squaredNorm() + 1e-24);
}

TEST(LeastSquares, StreamingBlocksEqualOneShotAndTheSvdSolution) {
  std::mt19937_64 rng(12);
  const Eigen::MatrixXd phi = random_matrix(1001, 9, rng);
  const Eigen::MatrixXd z = phi * random_matrix(9, 2, rng) + 0.1 * random_matrix(1001, 2, rng);
  const Eigen::MatrixXd ref = svd_solution(phi, z);
  const Eigen::MatrixXd E = z - phi * ref;

  for (const Eigen::Index block : {Eigen::Index{1}, Eigen::Index{7}, Eigen::Index{300}, Eigen::Index{1001}}) {
    LeastSquaresAccumulator acc(9, 2);
    for (Eigen::Index k = 0; k < phi.rows(); k += block) {
      const Eigen::Index rows = std::min(block, phi.rows() - k);
      acc.add(phi.middleRows(k, rows), z.middleRows(k, rows));
    }
    EXPECT_EQ(acc.rows(), 1001);
    const LeastSquaresSolution s = acc.solve();
    SCOPED_TRACE("block " + std::to_string(block));
    EXPECT_LT((s.theta - ref).norm() / ref.norm(), 1e-12);
    const Eigen::MatrixXd gram = E.transpose() * E;
    EXPECT_LT((s.residual_gram - gram).norm() / gram.norm(), 1e-11);
    EXPECT_LT((s.residual_covariance - gram / 992.0).norm() / gram.norm(), 1e-11);
    // (Phi'Phi)^-1 from Phi's own SVD: V S^-2 V'.
    const linalg::Svd svd = linalg::svd(phi);
    const Eigen::MatrixXd ig = svd.V * svd.S.cwiseAbs2().cwiseInverse().asDiagonal() * svd.V.transpose();
    EXPECT_LT((s.inverse_gram - ig).norm() / ig.norm(), 1e-11);
    EXPECT_NEAR(s.covariance(2, 1, 4, 0), s.residual_covariance(1, 0) * ig(2, 4), 1e-11 * std::abs(ig(2, 4)) + 1e-18);
  }
}

TEST(LeastSquares, ConditionNumberIsIndependentOfRegressorUnits) {
  std::mt19937_64 rng(13);
  Eigen::MatrixXd phi = random_matrix(200, 5, rng);
  const Eigen::MatrixXd z = random_matrix(200, 1, rng);
  const LeastSquaresSolution a = solve_least_squares(phi, z);
  phi.col(3) *= 1e7;
  const LeastSquaresSolution b = solve_least_squares(phi, z);
  EXPECT_NEAR(a.condition_number, b.condition_number, 1e-8 * a.condition_number);
  EXPECT_GT(b.raw_condition_number, 1e6);
  EXPECT_NEAR(b.theta(3, 0) * 1e7, a.theta(3, 0), 1e-10 * std::abs(a.theta(3, 0)));
  // The singular values of the equilibrated factor are those of Phi with unit columns.
  Eigen::MatrixXd unit = phi;
  for (Eigen::Index j = 0; j < 5; ++j) unit.col(j).normalize();
  const Eigen::VectorXd sv = linalg::singular_values(unit);
  EXPECT_LT((b.singular_values - sv).norm() / sv.norm(), 1e-12);
  EXPECT_NEAR(b.column_norms(3), phi.col(3).norm(), 1e-12 * phi.col(3).norm());
}

TEST(LeastSquares, TikhonovMatchesTheAugmentedProblem) {
  std::mt19937_64 rng(14);
  const Eigen::MatrixXd phi = random_matrix(50, 6, rng);
  const Eigen::MatrixXd z = random_matrix(50, 2, rng);
  const double lambda = 3.5;
  Eigen::MatrixXd aug(56, 6), zaug = Eigen::MatrixXd::Zero(56, 2);
  aug << phi, std::sqrt(lambda) * Eigen::MatrixXd::Identity(6, 6);
  zaug.topRows(50) = z;
  const Eigen::MatrixXd ref = svd_solution(aug, zaug);
  LeastSquaresOptions o;
  o.regularization = lambda;
  const LeastSquaresSolution s = solve_least_squares(phi, z, o);
  EXPECT_LT((s.theta - ref).norm() / ref.norm(), 1e-12);
  const Eigen::MatrixXd E = z - phi * ref;  // residual of the data rows only
  EXPECT_LT((s.residual_gram - E.transpose() * E).norm() / (E.transpose() * E).norm(), 1e-11);
  // Sandwich covariance (Phi'Phi + lambda I)^-1 Phi'Phi (Phi'Phi + lambda I)^-1, built from the SVD.
  const linalg::Svd svd = linalg::svd(phi);
  const Eigen::VectorXd s2 = svd.S.cwiseAbs2();
  const Eigen::VectorXd f = s2.cwiseQuotient((s2.array() + lambda).square().matrix());
  const Eigen::MatrixXd cov = svd.V * f.asDiagonal() * svd.V.transpose();
  EXPECT_LT((s.inverse_gram - cov).norm() / cov.norm(), 1e-11);
}

TEST(LeastSquares, TooFewRowsAreInsufficientData) {
  std::mt19937_64 rng(15);
  LeastSquaresAccumulator acc(6, 1);
  acc.add(random_matrix(6, 6, rng), random_matrix(6, 1, rng));
  try {
    acc.solve();
    FAIL() << "expected InsufficientData";
  } catch (const InsufficientData& e) {
    EXPECT_NE(std::string(e.what()).find("6 data rows for 6 regressors"), std::string::npos) << e.what();
  }
}

TEST(LeastSquares, ZeroRegressorIsNamed) {
  std::mt19937_64 rng(16);
  Eigen::MatrixXd phi = random_matrix(40, 3, rng);
  phi.col(1).setZero();
  try {
    solve_least_squares(phi, random_matrix(40, 1, rng), {}, {"a", "b", "c"});
    FAIL() << "expected InsufficientData";
  } catch (const InsufficientData& e) {
    EXPECT_NE(std::string(e.what()).find("regressor b is identically zero"), std::string::npos) << e.what();
  }
}

TEST(LeastSquares, RankDeficiencySaysHowManyAndWhich) {
  std::mt19937_64 rng(17);
  Eigen::MatrixXd phi = random_matrix(100, 5, rng);
  phi.col(4) = 2.0 * phi.col(1) - phi.col(2);  // one exact dependency among b, c, e
  try {
    solve_least_squares(phi, random_matrix(100, 1, rng), {}, {"a", "b", "c", "d", "e"});
    FAIL() << "expected InsufficientData";
  } catch (const InsufficientData& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("rank deficient"), std::string::npos) << msg;
    EXPECT_NE(msg.find("rank 4 of 5"), std::string::npos) << msg;
    EXPECT_NE(msg.find("1 direction"), std::string::npos) << msg;
    EXPECT_NE(msg.find("b ("), std::string::npos) << msg;
    EXPECT_NE(msg.find("e ("), std::string::npos) << msg;
    EXPECT_EQ(msg.find("a ("), std::string::npos) << msg;
    EXPECT_EQ(msg.find("d ("), std::string::npos) << msg;
  }
  // Regularisation makes the same data solvable.
  LeastSquaresOptions o;
  o.regularization = 1e-3;
  EXPECT_NO_THROW(solve_least_squares(phi, random_matrix(100, 1, rng), o));
}

TEST(LeastSquares, IllConditioningBeyondTheLimitIsRefused) {
  std::mt19937_64 rng(18);
  Eigen::MatrixXd phi = random_matrix(100, 3, rng);
  phi.col(2) = phi.col(0) + 1e-7 * random_matrix(100, 1, rng);
  LeastSquaresOptions o;
  o.max_condition = 1e6;
  try {
    solve_least_squares(phi, random_matrix(100, 1, rng), o, {"x", "y", "z"});
    FAIL() << "expected InsufficientData";
  } catch (const InsufficientData& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("ill-conditioned"), std::string::npos) << msg;
    EXPECT_NE(msg.find("x ("), std::string::npos) << msg;
    EXPECT_NE(msg.find("z ("), std::string::npos) << msg;
  }
  o.max_condition = 1e10;
  const LeastSquaresSolution s = solve_least_squares(phi, random_matrix(100, 1, rng), o);
  EXPECT_GT(s.condition_number, 1e6);
}

TEST(LeastSquares, BadInputsAreErrors) {
  LeastSquaresAccumulator acc(2, 1);
  EXPECT_THROW(acc.add(Eigen::MatrixXd::Ones(3, 3), Eigen::MatrixXd::Ones(3, 1)), Error);
  Eigen::MatrixXd phi = Eigen::MatrixXd::Ones(3, 2);
  phi(1, 0) = std::nan("");
  EXPECT_THROW(acc.add(phi, Eigen::MatrixXd::Ones(3, 1)), Error);
  EXPECT_THROW(LeastSquaresAccumulator(0, 1), Error);
  EXPECT_THROW(LeastSquaresAccumulator(2, 1, {"only one"}), Error);
}

}  // namespace least_squares_test
}  // namespace ambid::ident
