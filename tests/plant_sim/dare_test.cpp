#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include <Eigen/Core>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "plant_sim/dare.hpp"
#include "plant_sim/lqr.hpp"

namespace ambid::sim {
namespace dare_test {

Eigen::MatrixXd scalar(double v) { return Eigen::MatrixXd::Constant(1, 1, v); }

// b^2 X^2 - (a^2 r - r + q b^2) X - q r = 0, positive root.
double scalar_dare(double a, double b, double q, double r) {
  const double p = a * a * r - r + q * b * b;
  return (p + std::sqrt(p * p + 4 * b * b * q * r)) / (2 * b * b);
}

Eigen::MatrixXd random_matrix(std::mt19937_64& rng, Eigen::Index rows, Eigen::Index cols) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m(i) = n(rng);
  return m;
}

double relative_residual(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q,
                         const Eigen::MatrixXd& R, const Eigen::MatrixXd& X, const Eigen::MatrixXd& N = {}) {
  return dare_residual(A, B, Q, R, X, N).norm() / std::max(1.0, X.norm());
}

// Riccati difference equation from X = 0, iterated to its fixed point: an independent
// (slow, linearly converging) route to the stabilising solution.
Eigen::MatrixXd riccati_recursion(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q,
                                  const Eigen::MatrixXd& R, const Eigen::MatrixXd& N) {
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(A.rows(), A.rows());
  for (int k = 0; k < 2000; ++k) {
    const Eigen::MatrixXd cross = A.transpose() * X * B + N;
    const Eigen::MatrixXd gain = linalg::inverse(R + B.transpose() * X * B) * cross.transpose();
    const Eigen::MatrixXd next = A.transpose() * X * A - cross * gain + Q;
    X = 0.5 * (next + next.transpose());  // unsymmetrised, rounding grows in the skew part
  }
  return X;
}

TEST(Dare, ScalarMatchesClosedForm) {
  for (const double a : {2.0, 0.5, -1.5, 1.0}) {
    const double b = 0.7, q = 3.0, r = 0.2;
    const Eigen::MatrixXd X = solve_dare(scalar(a), scalar(b), scalar(q), scalar(r));
    const double expected = scalar_dare(a, b, q, r);
    EXPECT_NEAR(X(0, 0), expected, 1e-12 * expected) << "a = " << a;
    const LqrGain g = dlqr(scalar(a), scalar(b), scalar(q), scalar(r));
    EXPECT_NEAR(g.K(0, 0), a * b * expected / (r + b * b * expected), 1e-12);
    EXPECT_LT(std::abs(g.closed_loop_poles(0)), 1.0);
  }
}

TEST(Dare, RandomMimoResidualAndStability) {
  std::mt19937_64 rng(42);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Index n = 2 + trial % 6, m = 1 + trial % 3;
    const Eigen::MatrixXd A = 1.3 * random_matrix(rng, n, n) / std::sqrt(double(n));
    const Eigen::MatrixXd B = random_matrix(rng, n, m);
    const Eigen::MatrixXd Cq = random_matrix(rng, n, n);
    const Eigen::MatrixXd Q = Cq.transpose() * Cq;
    const Eigen::MatrixXd Rr = random_matrix(rng, m, m);
    const Eigen::MatrixXd R = Rr.transpose() * Rr + Eigen::MatrixXd::Identity(m, m);
    const LqrGain g = dlqr(A, B, Q, R);
    EXPECT_LT(relative_residual(A, B, Q, R, g.X), 1e-10) << "trial " << trial;
    EXPECT_LT((g.X - g.X.transpose()).norm(), 1e-10 * g.X.norm());
    EXPECT_GE(linalg::symmetric_eigenvalues(g.X).minCoeff(), -1e-9 * g.X.norm());
    EXPECT_LT(g.closed_loop_poles.cwiseAbs().maxCoeff(), 1.0);
  }
}

TEST(Dare, CrossTermMatchesRiccatiRecursion) {
  std::mt19937_64 rng(7);
  const Eigen::Index n = 4, m = 2;
  const Eigen::MatrixXd A = 1.2 * random_matrix(rng, n, n) / 2.0;
  const Eigen::MatrixXd B = random_matrix(rng, n, m);
  const Eigen::MatrixXd M = random_matrix(rng, n + m, n + m);
  const Eigen::MatrixXd J = M.transpose() * M + 0.1 * Eigen::MatrixXd::Identity(n + m, n + m);
  const Eigen::MatrixXd Q = J.topLeftCorner(n, n), R = J.bottomRightCorner(m, m);
  const Eigen::MatrixXd N = J.topRightCorner(n, m);
  const Eigen::MatrixXd X = solve_dare(A, B, Q, R, N);
  EXPECT_LT(relative_residual(A, B, Q, R, X, N), 1e-10);
  const Eigen::MatrixXd slow = riccati_recursion(A, B, Q, R, N);
  EXPECT_LT((X - slow).norm(), 1e-9 * X.norm());
}

TEST(Dare, BadlyScaledMagneticBearingLikeProblem) {
  // Unstable mode exp(882 * 1e-4) with tiny input gains, as for a ZOH bearing model.
  Eigen::MatrixXd A(3, 3), B(3, 1);
  A << 1.0039, 1.0e-4, 1.3e-6, 77.8, 1.0039, 0.027, 0, -0.11, 0.9959;
  B << 1.2e-12, 3.6e-8, 2.33e-4;
  const Eigen::Vector3d q(1e10, 1e2, 1.0);
  const Eigen::MatrixXd Q = q.asDiagonal();
  const Eigen::MatrixXd R = scalar(1e-2);
  const LqrGain g = dlqr(A, B, Q, R);
  EXPECT_LT(relative_residual(A, B, Q, R, g.X), 1e-10);
  EXPECT_LT(g.closed_loop_poles.cwiseAbs().maxCoeff(), 1.0);
}

TEST(Dare, UnstabilisablePairNamesTheEigenvalue) {
  Eigen::MatrixXd A(2, 2), B(2, 1);
  A << 2.0, 0.0, 0.0, 0.5;
  B << 0.0, 1.0;
  try {
    solve_dare(A, B, Eigen::MatrixXd::Identity(2, 2), scalar(1.0));
    FAIL() << "expected Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("not stabilisable"), std::string::npos) << what;
    EXPECT_NE(what.find("eigenvalue 2"), std::string::npos) << what;
  }
}

TEST(Dare, UnitCircleModeUnseenByQHasNoStabilisingSolution) {
  Eigen::MatrixXd A(2, 2), B(2, 1);
  A << 1.0, 0.0, 0.0, 0.5;
  B << 1.0, 1.0;
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(2, 2);
  Q(1, 1) = 1.0;
  EXPECT_THROW(solve_dare(A, B, Q, scalar(1.0)), Error);
}

TEST(Dare, RejectsBadWeights) {
  const Eigen::MatrixXd A = scalar(1.5), B = scalar(1.0), Q = scalar(1.0);
  EXPECT_THROW(solve_dare(A, B, Q, scalar(0.0)), Error);
  EXPECT_THROW(solve_dare(A, B, Q, scalar(-1.0)), Error);
  EXPECT_THROW(solve_dare(A, B, Eigen::MatrixXd::Identity(2, 2), scalar(1.0)), Error);
  EXPECT_THROW(solve_dare(A, B, Q, scalar(1.0), scalar(5.0)), Error);  // [1 5; 5 1] indefinite
  Eigen::MatrixXd Qa(2, 2);
  Qa << 1, 2, 0, 1;
  EXPECT_THROW(solve_dare(Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd::Ones(2, 1), Qa, scalar(1.0)), Error);
}

TEST(Dare, PredictorGainIsDualAndSatisfiesFilterRiccati) {
  Eigen::MatrixXd A(3, 3), C(1, 3);
  A << 1.1, 0.2, 0.0, 0.0, 0.9, 0.3, 0.1, 0.0, 0.7;
  C << 1.0, 0.0, 0.5;
  const Eigen::MatrixXd W = Eigen::Vector3d(1.0, 0.5, 0.2).asDiagonal();
  const Eigen::MatrixXd V = scalar(0.1);
  const ObserverGain o = predictor_gain(A, C, W, V);
  EXPECT_LT(o.observer_poles.cwiseAbs().maxCoeff(), 1.0);
  // P = A P A' + W - A P C' (V + C P C')^{-1} C P A',  L = A P C' (V + C P C')^{-1}
  EXPECT_LT(relative_residual(A.transpose(), C.transpose(), W, V, o.P), 1e-10);
  const Eigen::MatrixXd L = A * o.P * C.transpose() * linalg::inverse(V + C * o.P * C.transpose());
  EXPECT_LT((L - o.L).norm(), 1e-12 * L.norm());
}

TEST(Dare, UndetectablePairIsNamedInObserverError) {
  Eigen::MatrixXd A(2, 2), C(1, 2);
  A << 1.5, 0.0, 0.0, 0.5;
  C << 0.0, 1.0;
  try {
    predictor_gain(A, C, Eigen::MatrixXd::Identity(2, 2), scalar(1.0));
    FAIL() << "expected Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("detectable"), std::string::npos) << what;
    EXPECT_NE(what.find("1.5"), std::string::npos) << what;
  }
}

}  // namespace dare_test
}  // namespace ambid::sim
