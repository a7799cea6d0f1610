#include "identifier/families/physical_coordinates.hpp"

#include <random>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace physical_coordinates_test {

using testing::random_matrix;

// M q'' + Dd q' + K q = G u with one negative stiffness (an unstable, AMB-like mode),
// measured through a calibration y = C1 q, sampled at 1 ms, then put in random coordinates.
TEST(PhysicalCoordinates, SecondOrderFormRecoversStiffnessDampingAndInput) {
  std::mt19937_64 rng(61);
  const int h = 3;
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(h, h) + 0.1 * random_matrix(h, h, rng);
  M = 0.5 * (M + M.transpose());
  Eigen::MatrixXd K(h, h);
  K << -4000.0, 300.0, 0.0, 300.0, 9000.0, -500.0, 0.0, -500.0, 2500.0;
  Eigen::MatrixXd Dd(h, h);
  Dd << 2.0, 0.3, 0.0, 0.3, 5.0, 0.1, 0.0, 0.1, 1.0;
  const Eigen::MatrixXd G = random_matrix(h, 2, rng);
  const Eigen::MatrixXd C1 = Eigen::MatrixXd::Identity(h, h) * 50.0 + random_matrix(h, h, rng);
  const Eigen::MatrixXd Minv = linalg::inverse(M);
  ContinuousSystem phys;
  phys.A = Eigen::MatrixXd::Zero(2 * h, 2 * h);
  phys.A.topRightCorner(h, h).setIdentity();
  phys.A.bottomLeftCorner(h, h) = -Minv * K;
  phys.A.bottomRightCorner(h, h) = -Minv * Dd;
  phys.B = Eigen::MatrixXd::Zero(2 * h, 2);
  phys.B.bottomRows(h) = Minv * G;
  phys.C = Eigen::MatrixXd::Zero(h, 2 * h);
  phys.C.leftCols(h) = C1;
  phys.D = Eigen::MatrixXd::Zero(h, 2);
  DiscreteSystem d = c2d_zoh(phys, 1e-3);
  const Eigen::MatrixXd T = Eigen::MatrixXd::Identity(2 * h, 2 * h) + 0.5 * random_matrix(2 * h, 2 * h, rng);
  const Eigen::MatrixXd Ti = linalg::inverse(T);
  d.A = Ti * d.A * T;
  d.B = Ti * d.B;
  d.C = d.C * T;

  const SecondOrderForm f = second_order_form(d, C1);
  const Eigen::MatrixXd A21 = -Minv * K, A22 = -Minv * Dd, B2 = Minv * G;
  EXPECT_LT((f.stiffness - A21).norm() / A21.norm(), 1e-8);
  EXPECT_LT((f.damping - A22).norm() / A22.norm(), 1e-8);
  EXPECT_LT((f.input - B2).norm() / B2.norm(), 1e-8);
  EXPECT_LT(f.system.A.topLeftCorner(h, h).norm(), 1e-8 * A21.norm());
  EXPECT_LT((f.system.A.topRightCorner(h, h) - Eigen::MatrixXd::Identity(h, h)).norm(), 1e-8);
  EXPECT_LT(f.system.B.topRows(h).norm(), 1e-8 * B2.norm());
  EXPECT_LT((f.system.C.leftCols(h) - Eigen::MatrixXd::Identity(h, h)).norm(), 1e-10);
  EXPECT_LT(f.system.C.rightCols(h).norm(), 1e-10);
  // The unstable mode is still there.
  EXPECT_GT(linalg::eigenvalues(f.system.A).real().maxCoeff(), 10.0);
}

TEST(PhysicalCoordinates, WrongShapesAndSingularMapsAreErrors) {
  ContinuousSystem s;
  s.A = Eigen::MatrixXd::Identity(3, 3);
  s.B = Eigen::MatrixXd::Ones(3, 1);
  s.C = Eigen::MatrixXd::Ones(1, 3);
  s.D = Eigen::MatrixXd::Zero(1, 1);
  EXPECT_THROW(second_order_form(s), Error);  // 3 states, 1 output
  s.A = Eigen::MatrixXd::Identity(2, 2);      // C A = C: [C; C A] singular
  s.B = Eigen::MatrixXd::Ones(2, 1);
  s.C = Eigen::MatrixXd::Ones(1, 2);
  EXPECT_THROW(second_order_form(s), Error);
  s.A << 0, 1, -1, 0;
  EXPECT_NO_THROW(second_order_form(s));
  EXPECT_THROW(second_order_form(s, Eigen::MatrixXd::Zero(1, 1)), Error);
}

TEST(PhysicalCoordinates, MeasuredCoordinatesWithAKnownSquareC) {
  std::mt19937_64 rng(62);
  DiscreteSystem phys;
  phys.A = random_matrix(3, 3, rng, 0.5);
  phys.B = random_matrix(3, 2, rng);
  phys.C = Eigen::MatrixXd::Identity(3, 3) + 0.2 * random_matrix(3, 3, rng);
  phys.D = Eigen::MatrixXd::Zero(3, 2);
  phys.sample_time = 0.01;
  const Eigen::MatrixXd T = random_matrix(3, 3, rng) + 2.0 * Eigen::MatrixXd::Identity(3, 3);
  DiscreteSystem other = phys;
  other.A = linalg::inverse(T) * phys.A * T;
  other.B = linalg::inverse(T) * phys.B;
  other.C = phys.C * T;
  const DiscreteSystem back = to_measured_coordinates(other, phys.C);
  EXPECT_LT((back.A - phys.A).norm(), 1e-12);
  EXPECT_LT((back.B - phys.B).norm(), 1e-12);
  EXPECT_LT((back.C - phys.C).norm(), 1e-12);
}

}  // namespace physical_coordinates_test
}  // namespace ambid::ident
