// The default ARX order (time_domain/arx_order.hpp) and why it grows: in closed loop with
// innovation noise, an ARX model of fixed low order keeps its truncation bias however long the
// record, while the order that grows with the record lets the error fall with it.
#include "identifier/time_domain/arx_order.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "identifier/time_domain/arx.hpp"
#include "identifier/time_domain/markov.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace arx_order_test {

using testing::random_matrix;
using C = std::complex<double>;

TEST(ArxOrder, GrowsWithTheLogarithmOfTheRecordWithinTheVarianceCap) {
  // 2 ln N, at most N / (20 (p + m)) with p = 3, m = 2 (the amb1dof_voltage regressors).
  EXPECT_EQ(default_arx_order(2500, 3, 2), 16);   // 2 ln 2500 = 15.6 (cap 25)
  EXPECT_EQ(default_arx_order(10000, 3, 2), 19);  // 18.4
  EXPECT_EQ(default_arx_order(80000, 3, 2), 23);  // 22.6
  EXPECT_EQ(default_arx_order(1000, 3, 2), 10);   // 13.8, capped at 1000 / 100
  EXPECT_EQ(default_arx_order(100, 3, 2), 1);     // the last record long enough
  try {
    default_arx_order(99, 3, 2);
    FAIL() << "expected InsufficientData";
  } catch (const InsufficientData& e) {
    EXPECT_NE(std::string(e.what()).find("needs more than 99 samples"), std::string::npos) << e.what();
  }
  EXPECT_THROW(default_arx_order(10000, 0, 2), Error);
  Eigen::Index previous = 0;
  for (Eigen::Index n = 100; n < 1000000; n = n * 3 / 2) {
    const Eigen::Index q = default_arx_order(n, 3, 2);
    EXPECT_GE(q, previous) << n;
    previous = q;
  }
  EXPECT_EQ(default_markov_counts(), (std::vector<Eigen::Index>{30, 60, 100}));
}

// Innovation model x[k+1] = A x + B u + G e, y = C x + e with the predictor A - G C of radius
// 0.85 and an unstable A, in closed loop under state feedback, excited by r. The ARX
// coefficients of y on u are C (A - G C)^(i-1) [B, G]: an order-q model misses 0.85^q of them.
struct NoisyLoop {
  testing::Plant plant;
  Eigen::MatrixXd F;
};

NoisyLoop noisy_loop(std::mt19937_64& rng) {
  NoisyLoop l;
  auto& P = l.plant;
  const Eigen::MatrixXd predictor = testing::matrix_with_eigenvalues({C(0.85, 0.0), C(0.6, 0.4), C(-0.3, 0.0)}, rng);
  P.B = random_matrix(4, 2, rng);
  P.C = random_matrix(2, 4, rng);
  P.D = Eigen::MatrixXd::Zero(2, 2);
  const Eigen::MatrixXd G0 = random_matrix(4, 2, rng);
  P.G = testing::scale_to_radius(predictor, G0 * P.C, 1.1) * G0;  // A = predictor + G C, radius 1.1
  P.A = predictor + P.G * P.C;
  l.F = testing::lqr_gain(P.A, P.B, Eigen::MatrixXd::Identity(4, 4), Eigen::MatrixXd::Identity(2, 2));
  return l;
}

// Largest relative error of the first 10 plant Markov parameters from the ARX model of y on u.
double markov_error(const NoisyLoop& l, Eigen::Index samples, Eigen::Index order, std::mt19937_64& rng) {
  const Eigen::MatrixXd r = random_matrix(samples, 2, rng);
  const Eigen::MatrixXd e = random_matrix(samples, 2, rng, 0.3);
  const testing::LoopData d = testing::run_loop(l.plant, nullptr, l.F, r, e);
  ArxOptions o;
  o.order = order;
  const MarkovSequence estimate = markov_from_arx(fit_arx(d.y, d.u, o), 10).system;
  const auto& P = l.plant;
  return testing::max_relative_error(testing::markov_of(P.A, P.B, P.C, P.D, 10), estimate, 1, 10);
}

TEST(ArxOrder, FixedLowOrderKeepsItsBiasTheGrowingOrderDoesNot) {
  std::mt19937_64 rng(2024);
  const NoisyLoop l = noisy_loop(rng);
  ASSERT_GT(testing::spectral_radius(l.plant.A), 1.05);
  ASSERT_NEAR(testing::spectral_radius(l.plant.A - l.plant.G * l.plant.C), 0.85, 1e-9);
  ASSERT_LT(testing::spectral_radius(l.plant.A - l.plant.B * l.F), 1.0);
  const Eigen::Index short_record = 2000, long_record = 32000;
  const double fixed_short = markov_error(l, short_record, 3, rng);
  const double fixed_long = markov_error(l, long_record, 3, rng);
  const double grown_short = markov_error(l, short_record, default_arx_order(short_record, 2, 2), rng);
  const double grown_long = markov_error(l, long_record, default_arx_order(long_record, 2, 2), rng);
  ::testing::Test::RecordProperty("fixed_order_3_short", testing::sci(fixed_short));
  ::testing::Test::RecordProperty("fixed_order_3_long", testing::sci(fixed_long));
  ::testing::Test::RecordProperty("grown_order_short", testing::sci(grown_short));
  ::testing::Test::RecordProperty("grown_order_long", testing::sci(grown_long));
  std::printf("Markov error, order 3: %.3g (N %lld), %.3g (N %lld); grown order %lld / %lld: %.3g, %.3g\n", fixed_short,
              (long long)short_record, fixed_long, (long long)long_record,
              (long long)default_arx_order(short_record, 2, 2), (long long)default_arx_order(long_record, 2, 2),
              grown_short, grown_long);
  // 16 times the data: a standard error falls 4-fold. The fixed order's error does not fall
  // (its bias), the growing order's error falls with the standard error.
  EXPECT_GT(fixed_long, 0.7 * fixed_short);
  EXPECT_LT(grown_long, 0.4 * grown_short);
  EXPECT_LT(grown_long, 0.2 * fixed_long);
}

}  // namespace arx_order_test
}  // namespace ambid::ident
