// Known-controller closed-loop identification (Lee ch. 2) on closed loops simulated here,
// sample by sample, around open-loop-unstable plants.
#include "identifier/time_domain/closed_loop_id.hpp"

#include <random>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace closed_loop_id_test {

using testing::eigenvalue_error;
using testing::markov_of;
using testing::matrix_with_eigenvalues;
using testing::max_relative_error;
using testing::random_matrix;
using testing::spectral_radius;
using C = std::complex<double>;

// An unstable plant (n = 4, m = 2, p = 2) built around a stabilising Lee-form controller
// u = Yd * y + r with a stable controller of 2 states.
struct LeeCase {
  testing::Plant plant;
  testing::Controller controller;  // contract form, zero u columns
};

LeeCase lee_case(std::mt19937_64& rng) {
  LeeCase c;
  auto& P = c.plant;
  P.B = random_matrix(4, 2, rng);
  P.C = random_matrix(2, 4, rng);
  P.D = Eigen::MatrixXd::Zero(2, 2);
  Eigen::MatrixXd Dd = random_matrix(2, 2, rng);
  const Eigen::MatrixXd Acl0 = matrix_with_eigenvalues({C(0.5, 0.0), C(0.3, 0.4), C(-0.2, 0.0)}, rng);
  // Scale the static part of the controller so that the plant A = Acl0 - B Dd C has spectral
  // radius 1.2: unstable like a sampled magnetic bearing, not violently so.
  const double hi = testing::scale_to_radius(Acl0, -P.B * Dd * P.C, 1.2);
  Dd *= hi;
  P.A = Acl0 - P.B * Dd * P.C;
  auto& K = c.controller;
  K.A = matrix_with_eigenvalues({C(0.5, 0.0), C(-0.3, 0.0)}, rng);
  K.B = Eigen::MatrixXd::Zero(2, 4);
  K.B.rightCols(2) = random_matrix(2, 2, rng, 0.2);
  K.C = random_matrix(2, 2, rng, 0.2);
  K.D = Eigen::MatrixXd::Zero(2, 4);
  K.D.rightCols(2) = Dd;
  P.G = Eigen::MatrixXd::Zero(4, 2);
  return c;
}

KnownController known(const testing::Controller& k) { return KnownController{k.A, k.B, k.C, k.D}; }

Eigen::MatrixXd closed_loop_A(const LeeCase& c) {
  const auto& P = c.plant;
  const auto& K = c.controller;
  const Eigen::MatrixXd Dy = K.D.rightCols(2), By = K.B.rightCols(2), Bu = K.B.leftCols(2);
  Eigen::MatrixXd A(P.A.rows() + K.A.rows(), P.A.rows() + K.A.rows());
  A << P.A + P.B * Dy * P.C, P.B * K.C, (Bu * Dy + By) * P.C, K.A + Bu * K.C;
  return A;
}

TEST(KnownControllerClid, NoiseFreeLeeControllerIsExact) {
  std::mt19937_64 rng(71);
  const LeeCase c = lee_case(rng);
  ASSERT_GT(spectral_radius(c.plant.A), 1.05);
  ASSERT_LT(spectral_radius(closed_loop_A(c)), 0.99);
  const Eigen::MatrixXd r = random_matrix(800, 2, rng);
  const testing::LoopData d = testing::run_loop(c.plant, &c.controller, {}, r);

  KnownControllerIdOptions o;
  o.arx_order = 3;  // p q = 2 * 3 = closed-loop order 4 + 2: the ARX is exact
  o.markov_count = 20;
  o.sample_time = 1e-3;
  const ClosedLoopIdResult res = identify_with_known_controller(r, d.y, known(c.controller), o);

  const auto& P = c.plant;
  const auto Y = markov_of(P.A, P.B, P.C, P.D, 40);
  const double e_markov = max_relative_error(Y, res.open_loop.system, 1, 20);
  EXPECT_LT(e_markov, 1e-8);
  EXPECT_EQ(res.suggested_order, 4);
  EXPECT_EQ(res.plant.states(), 4);
  const double e_model =
      max_relative_error(Y, markov_of(res.plant.A, res.plant.B, res.plant.C, res.plant.D, 40), 1, 40);
  EXPECT_LT(e_model, 1e-8);
  const double e_eig = eigenvalue_error(P.A, res.plant.A);
  EXPECT_LT(e_eig, 1e-8);
  EXPECT_GT(spectral_radius(res.plant.A), 1.05);  // identified unstable, not stabilised
  EXPECT_NEAR(res.controller_spectral_radius, 0.5, 1e-12);
  EXPECT_EQ(res.plant.sample_time, 1e-3);
  ::testing::Test::RecordProperty("markov_error", testing::sci(e_markov));
  ::testing::Test::RecordProperty("model_error", testing::sci(e_model));
  ::testing::Test::RecordProperty("eigenvalue_error", testing::sci(e_eig));
}

// An observer-based controller in the contract form reads u: r also drives its state.
TEST(KnownControllerClid, NoiseFreeObserverControllerReadingUIsExact) {
  std::mt19937_64 rng(72);
  testing::Plant P;
  P.A = matrix_with_eigenvalues({C(1.2, 0.0), C(0.8, 0.0), C(0.95, 0.2)}, rng);
  P.B = random_matrix(4, 2, rng);
  P.C = random_matrix(2, 4, rng);
  P.D = Eigen::MatrixXd::Zero(2, 2);
  P.G = Eigen::MatrixXd::Zero(4, 2);
  const Eigen::MatrixXd F =
      testing::lqr_gain(P.A, P.B, Eigen::MatrixXd::Identity(4, 4), Eigen::MatrixXd::Identity(2, 2));
  const Eigen::MatrixXd L = testing::lqr_gain(P.A.transpose(), P.C.transpose(), Eigen::MatrixXd::Identity(4, 4),
                                              Eigen::MatrixXd::Identity(2, 2))
                                .transpose();
  ASSERT_LT(spectral_radius(P.A - P.B * F), 1.0);
  ASSERT_LT(spectral_radius(P.A - L * P.C), 1.0);
  testing::Controller K;
  K.A = P.A - L * P.C;
  K.B.resize(4, 4);
  K.B << P.B, L;
  K.C = -F;
  K.D = Eigen::MatrixXd::Zero(2, 4);
  const Eigen::MatrixXd r = random_matrix(600, 2, rng);
  const testing::LoopData d = testing::run_loop(P, &K, {}, r);

  KnownControllerIdOptions o;
  o.arx_order = 2;  // the observer error is not excited by r: the r -> y loop has 4 states
  o.markov_count = 20;
  o.sample_time = 1e-4;
  const ClosedLoopIdResult res = identify_with_known_controller(r, d.y, KnownController{K.A, K.B, K.C, K.D}, o);
  const auto Y = markov_of(P.A, P.B, P.C, P.D, 40);
  EXPECT_LT(max_relative_error(Y, res.open_loop.system, 1, 20), 1e-8);
  EXPECT_LT(max_relative_error(Y, markov_of(res.plant.A, res.plant.B, res.plant.C, res.plant.D, 40), 1, 40), 1e-8);
  EXPECT_LT(eigenvalue_error(P.A, res.plant.A), 1e-8);
  EXPECT_GT(spectral_radius(res.plant.A), 1.15);
  EXPECT_NEAR(res.controller_spectral_radius, spectral_radius(P.A - L * P.C - P.B * F), 1e-12);
}

// Innovation-model noise e (white, known predictor gain G = AK): the Kalman Markov
// parameters and the gain come out within the statistical accuracy of 20000 samples.
TEST(KnownControllerClid, NoisyDataGiveThePlantAndTheKalmanGain) {
  std::mt19937_64 rng(73);
  LeeCase c = lee_case(rng);
  auto& P = c.plant;
  P.G = testing::lqr_gain(P.A.transpose(), P.C.transpose(), Eigen::MatrixXd::Identity(4, 4),
                          1e-2 * Eigen::MatrixXd::Identity(2, 2))
            .transpose();
  const double rho_pred = spectral_radius(P.A - P.G * P.C);
  ASSERT_LT(rho_pred, 0.6);
  const Eigen::Index N = 20000;
  const Eigen::MatrixXd r = random_matrix(N, 2, rng);
  const Eigen::MatrixXd e = random_matrix(N, 2, rng, 0.05);
  const testing::LoopData d = testing::run_loop(P, &c.controller, {}, r, e);

  KnownControllerIdOptions o;
  o.arx_order = 20;  // 0.6^20 ~ 4e-5
  o.markov_count = 20;
  o.sample_time = 1e-3;
  o.era.order = 4;
  const ClosedLoopIdResult res = identify_with_known_controller(r, d.y, known(c.controller), o);

  const auto Y = markov_of(P.A, P.B, P.C, P.D, 20);
  const auto Yhat = markov_of(res.plant.A, res.plant.B, res.plant.C, res.plant.D, 20);
  const double e_markov = max_relative_error(Y, Yhat, 1, 20);
  EXPECT_LT(e_markov, 0.02);
  const auto Nt = markov_of(P.A, P.G, P.C, Eigen::MatrixXd::Identity(2, 2), 5);
  const auto Nh = markov_of(res.plant.A, res.predictor_gain, res.plant.C, Eigen::MatrixXd::Identity(2, 2), 5);
  const double e_gain = max_relative_error(Nt, Nh, 1, 5);
  EXPECT_LT(e_gain, 0.05);
  // The filter gain K satisfies AK = A K in the same coordinates.
  ASSERT_EQ(res.filter_gain.rows(), 4);
  EXPECT_LT((res.plant.A * res.filter_gain - res.predictor_gain).norm(), 1e-9 * res.predictor_gain.norm());
  const double e_eig = eigenvalue_error(P.A, res.plant.A);
  EXPECT_LT(e_eig, 0.01);
  EXPECT_GT(spectral_radius(res.plant.A), 1.05);  // still unstable
  ::testing::Test::RecordProperty("markov_error", testing::sci(e_markov));
  ::testing::Test::RecordProperty("gain_markov_error", testing::sci(e_gain));
  ::testing::Test::RecordProperty("eigenvalue_error", testing::sci(e_eig));
}

TEST(KnownControllerClid, ContractControllerIsRearrangedAndFeedthroughFromUIsRefused) {
  StateSpaceController sc;
  sc.sample_time = 1e-4;
  sc.inputs = {"i1", "x", "u2"};
  sc.outputs = {"u2"};
  sc.A = Eigen::MatrixXd::Identity(1, 1) * 0.5;
  sc.B.resize(1, 3);
  sc.B << 1.0, 2.0, 3.0;
  sc.C = Eigen::MatrixXd::Ones(1, 1) * 4.0;
  sc.D.resize(1, 3);
  sc.D << 5.0, 6.0, 0.0;
  const KnownController k = known_controller(sc, {"u1", "u2"}, {"x", "i1", "i2"});
  Eigen::MatrixXd B(1, 5), Cm(2, 1), D(2, 5);
  B << 0.0, 3.0, 2.0, 1.0, 0.0;
  Cm << 0.0, 4.0;
  D << 0, 0, 0, 0, 0, 0, 0, 6.0, 5.0, 0;
  EXPECT_EQ(k.B, B);
  EXPECT_EQ(k.C, Cm);
  EXPECT_EQ(k.D, D);
  sc.D(0, 2) = 0.1;  // u2 -> uf2 directly
  try {
    known_controller(sc, {"u1", "u2"}, {"x", "i1", "i2"});
    FAIL() << "expected Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("feedthrough from plant input 'u2'"), std::string::npos) << e.what();
  }
  sc.inputs[0] = "temperature";
  EXPECT_THROW(known_controller(sc, {"u1", "u2"}, {"x", "i1", "i2"}), Error);

  // The same refusal when the controller matrices are given directly.
  std::mt19937_64 rng(74);
  const LeeCase c = lee_case(rng);
  KnownController bad = known(c.controller);
  bad.D(1, 0) = 0.3;
  const Eigen::MatrixXd r = random_matrix(200, 2, rng);
  KnownControllerIdOptions o;
  o.arx_order = 3;
  o.markov_count = 10;
  o.sample_time = 1e-3;
  EXPECT_THROW(identify_with_known_controller(r, Eigen::MatrixXd::Zero(200, 2), bad, o), Error);
}

TEST(KnownControllerClid, ShortOrUnexcitingDataAreInsufficient) {
  std::mt19937_64 rng(75);
  const LeeCase c = lee_case(rng);
  KnownControllerIdOptions o;
  o.arx_order = 3;
  o.markov_count = 20;
  o.sample_time = 1e-3;
  {
    const Eigen::MatrixXd r = random_matrix(14, 2, rng);
    const testing::LoopData d = testing::run_loop(c.plant, &c.controller, {}, r);
    EXPECT_THROW(identify_with_known_controller(r, d.y, known(c.controller), o), InsufficientData);
  }
  {
    Eigen::MatrixXd r = random_matrix(500, 2, rng);
    r.col(1).setZero();  // the second actuator is never excited
    const testing::LoopData d = testing::run_loop(c.plant, &c.controller, {}, r);
    try {
      identify_with_known_controller(r, d.y, known(c.controller), o);
      FAIL() << "expected InsufficientData";
    } catch (const InsufficientData& e) {
      EXPECT_NE(std::string(e.what()).find("r2[k-1] is identically zero"), std::string::npos) << e.what();
    }
  }
  {
    // Noise-free data with a too high ARX order: the closed loop (6 states) cannot fill 4 x 4 lags.
    const Eigen::MatrixXd r = random_matrix(500, 2, rng);
    const testing::LoopData d = testing::run_loop(c.plant, &c.controller, {}, r);
    o.arx_order = 4;
    try {
      identify_with_known_controller(r, d.y, known(c.controller), o);
      FAIL() << "expected InsufficientData";
    } catch (const InsufficientData& e) {
      EXPECT_NE(std::string(e.what()).find("rank deficient"), std::string::npos) << e.what();
    }
  }
}

}  // namespace closed_loop_id_test
}  // namespace ambid::ident
