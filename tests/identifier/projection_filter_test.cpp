// Unknown-feedback closed-loop identification by projection filters (Lee ch. 4) on closed
// loops simulated here around open-loop-unstable plants.
#include "identifier/time_domain/projection_filter.hpp"

#include <random>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace projection_filter_test {

using testing::eigenvalue_error;
using testing::markov_of;
using testing::matrix_with_eigenvalues;
using testing::max_relative_error;
using testing::random_matrix;
using testing::spectral_radius;
using C = std::complex<double>;

testing::Plant unstable_plant(std::mt19937_64& rng, bool feedthrough) {
  testing::Plant P;
  P.A = matrix_with_eigenvalues({C(1.25, 0.0), C(0.8, 0.0), C(0.97, 0.15)}, rng);
  P.B = random_matrix(4, 2, rng);
  P.C = random_matrix(2, 4, rng);
  P.D = feedthrough ? random_matrix(2, 2, rng) : Eigen::MatrixXd::Zero(2, 2);
  P.G = Eigen::MatrixXd::Zero(4, 2);
  return P;
}

Eigen::MatrixXd state_feedback(const testing::Plant& P) {
  return testing::lqr_gain(P.A, P.B, Eigen::MatrixXd::Identity(4, 4), Eigen::MatrixXd::Identity(2, 2));
}

void expect_exact(const testing::Plant& P, const Eigen::MatrixXd& F, const ProjectionFilterResult& res, double tol) {
  const auto Y = markov_of(P.A, P.B, P.C, P.D, 40);
  const double e_markov = max_relative_error(Y, res.plant_markov.system, 0, 25);
  const double e_model =
      max_relative_error(Y, markov_of(res.plant.A, res.plant.B, res.plant.C, res.plant.D, 40), 0, 40);
  const auto FB = markov_of(P.A, P.B, -F, Eigen::MatrixXd::Zero(2, 2), 40);
  const double e_fb_markov = max_relative_error(FB, res.feedback_markov.system, 1, 25);
  const double e_fb = max_relative_error(
      FB, markov_of(res.plant.A, res.plant.B, -res.feedback_gain, Eigen::MatrixXd::Zero(2, 2), 40), 1, 40);
  const double e_eig = eigenvalue_error(P.A, res.plant.A);
  const double e_cl = eigenvalue_error(P.A - P.B * F, res.plant.A - res.plant.B * res.feedback_gain);
  EXPECT_LT(e_markov, tol);
  EXPECT_LT(e_model, tol);
  EXPECT_LT(e_fb_markov, tol);
  EXPECT_LT(e_fb, tol);
  EXPECT_LT(e_eig, tol);
  EXPECT_LT(e_cl, tol);
  EXPECT_GT(spectral_radius(res.plant.A), 1.2);  // unstable, as the truth
  ::testing::Test::RecordProperty("markov_error", testing::sci(e_markov));
  ::testing::Test::RecordProperty("model_error", testing::sci(e_model));
  ::testing::Test::RecordProperty("feedback_error", testing::sci(e_fb));
  ::testing::Test::RecordProperty("eigenvalue_error", testing::sci(e_eig));
}

TEST(ProjectionFilter, NoiseFreeStateFeedbackWithFeedthroughIsExact) {
  std::mt19937_64 rng(81);
  const testing::Plant P = unstable_plant(rng, true);
  const Eigen::MatrixXd F = state_feedback(P);
  ASSERT_LT(spectral_radius(P.A - P.B * F), 1.0);
  const Eigen::MatrixXd r = random_matrix(600, 2, rng);
  const testing::LoopData d = testing::run_loop(P, nullptr, F, r);
  ProjectionFilterOptions o;
  o.arx_order = 2;  // p q = n: the ARX is exact and its regressors have full rank
  o.markov_count = 25;
  o.estimate_feedthrough = true;
  o.sample_time = 0.01;
  const ProjectionFilterResult res = identify_projection_filter(d.y, d.u, d.uf, o);
  EXPECT_EQ(res.suggested_order, 4);
  EXPECT_LT((res.plant.D - P.D).norm() / P.D.norm(), 1e-10);
  expect_exact(P, F, res, 1e-8);
}

TEST(ProjectionFilter, NoiseFreeStrictlyProperPlantAndCombinedRealisation) {
  std::mt19937_64 rng(82);
  const testing::Plant P = unstable_plant(rng, false);
  const Eigen::MatrixXd F = state_feedback(P);
  const Eigen::MatrixXd r = random_matrix(600, 2, rng);
  const testing::LoopData d = testing::run_loop(P, nullptr, F, r);
  ProjectionFilterOptions o;
  o.arx_order = 2;
  o.markov_count = 25;
  o.sample_time = 0.01;
  const ProjectionFilterResult res = identify_projection_filter(d.y, d.u, d.uf, o);
  EXPECT_EQ(res.plant.D.norm(), 0.0);
  expect_exact(P, F, res, 1e-8);
  // Lee's case 1: one Hankel matrix of [C; -F] A^(k-1) [B, AK].
  o.combined_realisation = true;
  o.era.order = 4;
  const ProjectionFilterResult comb = identify_projection_filter(d.y, d.u, d.uf, o);
  expect_exact(P, F, comb, 1e-8);
}

// A dynamic (observer-based) controller: noise-free, the observer starts at the true state,
// so uf = -F x exactly and the method is exact as for state feedback.
TEST(ProjectionFilter, NoiseFreeObserverBasedController) {
  std::mt19937_64 rng(83);
  const testing::Plant P = unstable_plant(rng, false);
  const Eigen::MatrixXd F = state_feedback(P);
  const Eigen::MatrixXd L = testing::lqr_gain(P.A.transpose(), P.C.transpose(), Eigen::MatrixXd::Identity(4, 4),
                                              Eigen::MatrixXd::Identity(2, 2))
                                .transpose();
  testing::Controller K;
  K.A = P.A - L * P.C;
  K.B.resize(4, 4);
  K.B << P.B, L;
  K.C = -F;
  K.D = Eigen::MatrixXd::Zero(2, 4);
  const Eigen::MatrixXd r = random_matrix(600, 2, rng);
  const testing::LoopData d = testing::run_loop(P, &K, {}, r);
  ProjectionFilterOptions o;
  o.arx_order = 2;
  o.markov_count = 25;
  o.sample_time = 0.01;
  const ProjectionFilterResult res = identify_projection_filter(d.y, d.u, d.uf, o);
  expect_exact(P, F, res, 1e-8);
}

// Process and measurement noise: the plant comes out within the statistical accuracy of the
// record, unstable as it is.
TEST(ProjectionFilter, NoisyDataKeepThePlantUnstable) {
  std::mt19937_64 rng(84);
  // Innovation model with a fast predictor: A = Abar + G C with rho(Abar) = 0.3 and G scaled
  // so that rho(A) = 1.25.
  testing::Plant P;
  const Eigen::MatrixXd Abar = matrix_with_eigenvalues({C(0.3, 0.0), C(-0.2, 0.1), C(0.1, 0.0)}, rng);
  P.B = random_matrix(4, 2, rng);
  P.C = random_matrix(2, 4, rng);
  P.D = Eigen::MatrixXd::Zero(2, 2);
  P.G = random_matrix(4, 2, rng);
  P.G *= testing::scale_to_radius(Abar, P.G * P.C, 1.25);
  P.A = Abar + P.G * P.C;
  const Eigen::MatrixXd F = state_feedback(P);
  ASSERT_LT(spectral_radius(P.A - P.B * F), 1.0);
  ASSERT_LT(spectral_radius(P.A - P.G * P.C), 0.31);
  const Eigen::Index N = 20000;
  const Eigen::MatrixXd r = random_matrix(N, 2, rng);
  const Eigen::MatrixXd e = random_matrix(N, 2, rng, 0.05);
  const testing::LoopData d = testing::run_loop(P, nullptr, F, r, e);
  ProjectionFilterOptions o;
  o.arx_order = 15;
  o.markov_count = 25;
  o.sample_time = 0.01;
  o.era.order = 4;
  const ProjectionFilterResult res = identify_projection_filter(d.y, d.u, d.uf, o);
  const auto Y = markov_of(P.A, P.B, P.C, P.D, 30);
  const double e_model =
      max_relative_error(Y, markov_of(res.plant.A, res.plant.B, res.plant.C, res.plant.D, 30), 1, 30);
  const double e_eig = eigenvalue_error(P.A, res.plant.A);
  const auto Nt = markov_of(P.A, P.G, P.C, Eigen::MatrixXd::Identity(2, 2), 5);
  const auto Nh = markov_of(res.plant.A, res.predictor_gain, res.plant.C, Eigen::MatrixXd::Identity(2, 2), 5);
  const double e_gain = max_relative_error(Nt, Nh, 1, 5);
  // The closed loop with the identified F, compared by its Markov parameters while they are
  // significant (its poles are within 0.32 of the origin).
  const double e_cl = max_relative_error(
      markov_of(P.A - P.B * F, P.B, P.C, P.D, 5),
      markov_of(res.plant.A - res.plant.B * res.feedback_gain, res.plant.B, res.plant.C, res.plant.D, 5), 1, 5);
  EXPECT_LT(e_model, 0.02);
  EXPECT_LT(e_eig, 0.01);
  EXPECT_LT(e_gain, 0.05);
  EXPECT_LT(e_cl, 0.02);
  EXPECT_GT(spectral_radius(res.plant.A), 1.2);
  ::testing::Test::RecordProperty("closed_loop_error", testing::sci(e_cl));
  ::testing::Test::RecordProperty("model_error", testing::sci(e_model));
  ::testing::Test::RecordProperty("eigenvalue_error", testing::sci(e_eig));
  ::testing::Test::RecordProperty("gain_markov_error", testing::sci(e_gain));
}

TEST(ProjectionFilter, UnexcitedOrShortDataAreInsufficient) {
  std::mt19937_64 rng(85);
  const testing::Plant P = unstable_plant(rng, false);
  const Eigen::MatrixXd F = state_feedback(P);
  ProjectionFilterOptions o;
  o.arx_order = 2;
  o.markov_count = 25;
  o.sample_time = 0.01;
  {
    // No excitation: a free response from an initial state spans only the 4 plant states.
    Eigen::VectorXd x0(4);
    x0 << 1.0, -0.5, 0.3, 0.2;
    const testing::LoopData d = testing::run_loop(P, nullptr, F, Eigen::MatrixXd::Zero(300, 2), {}, {}, x0);
    try {
      identify_projection_filter(d.y, d.u, d.uf, o);
      FAIL() << "expected InsufficientData";
    } catch (const InsufficientData& e) {
      EXPECT_NE(std::string(e.what()).find("rank deficient"), std::string::npos) << e.what();
    }
  }
  {
    const Eigen::MatrixXd r = random_matrix(10, 2, rng);
    const testing::LoopData d = testing::run_loop(P, nullptr, F, r);
    EXPECT_THROW(identify_projection_filter(d.y, d.u, d.uf, o), InsufficientData);
  }
  EXPECT_THROW(identify_projection_filter(Eigen::MatrixXd::Ones(50, 2), Eigen::MatrixXd::Ones(50, 2),
                                          Eigen::MatrixXd::Ones(50, 1), o),
               Error);
}

}  // namespace projection_filter_test
}  // namespace ambid::ident
