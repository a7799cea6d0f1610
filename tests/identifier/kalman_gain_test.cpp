#include "identifier/time_domain/kalman_gain.hpp"

#include <random>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace kalman_gain_test {

using testing::markov_of;
using testing::matrix_with_eigenvalues;
using testing::random_matrix;
using C = std::complex<double>;

TEST(KalmanGain, PredictorAndFilterGainFromExactMarkovParameters) {
  std::mt19937_64 rng(51);
  const Eigen::MatrixXd A = matrix_with_eigenvalues({C(1.2, 0.0), C(0.9, 0.3), C(0.4, 0.0)}, rng);
  const Eigen::MatrixXd Cm = random_matrix(2, 4, rng);
  const Eigen::MatrixXd K = random_matrix(4, 2, rng);
  const auto N = markov_of(A, A * K, Cm, Eigen::MatrixXd::Identity(2, 2), 10);  // N_k = C A^(k-1) A K
  const KalmanGainEstimate est = kalman_gain_from_markov(A, Cm, N, 6);
  EXPECT_LT((est.predictor_gain - A * K).norm() / (A * K).norm(), 1e-12);
  ASSERT_EQ(est.filter_gain.rows(), 4);
  EXPECT_LT((est.filter_gain - K).norm() / K.norm(), 1e-12);
  EXPECT_EQ(est.fit.rows, 12);
}

TEST(KalmanGain, SingularAGivesOnlyThePredictorGain) {
  std::mt19937_64 rng(52);
  const Eigen::MatrixXd A = matrix_with_eigenvalues({C(0.0, 0.0), C(0.9, 0.3), C(0.4, 0.0)}, rng);
  const Eigen::MatrixXd Cm = random_matrix(2, 4, rng);
  const Eigen::MatrixXd AK = random_matrix(4, 2, rng);
  const auto N = markov_of(A, AK, Cm, Eigen::MatrixXd::Identity(2, 2), 6);
  const KalmanGainEstimate est = kalman_gain_from_markov(A, Cm, N);
  EXPECT_LT((est.predictor_gain - AK).norm() / AK.norm(), 1e-12);
  EXPECT_EQ(est.filter_gain.size(), 0);
}

TEST(KalmanGain, UnobservableModelIsInsufficientData) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Identity(3, 3) * 0.5;
  A(2, 2) = 0.7;
  Eigen::MatrixXd Cm = Eigen::MatrixXd::Zero(1, 3);
  Cm(0, 0) = 1.0;
  Cm(0, 1) = 1.0;  // states 1 and 2 share a pole and a sensor: not observable separately
  const auto N = markov_of(A, Eigen::MatrixXd::Ones(3, 1), Cm, Eigen::MatrixXd::Identity(1, 1), 8);
  EXPECT_THROW(kalman_gain_from_markov(A, Cm, N), InsufficientData);
  EXPECT_THROW(kalman_gain_from_markov(A, Cm, N, 9), Error);
}

}  // namespace kalman_gain_test
}  // namespace ambid::ident
