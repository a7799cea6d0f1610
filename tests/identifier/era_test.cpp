#include "identifier/time_domain/era.hpp"

#include <random>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace era_test {

using testing::eigenvalue_error;
using testing::markov_of;
using testing::matrix_with_eigenvalues;
using testing::max_relative_error;
using testing::random_matrix;
using C = std::complex<double>;

struct TrueSystem {
  Eigen::MatrixXd A, B, C, D;
};

// 6 states (an unstable real pair like a magnetic bearing, a lightly damped mode, a fast
// real mode and a slow one), 3 inputs, 2 outputs.
TrueSystem true_system(std::mt19937_64& rng) {
  TrueSystem s;
  s.A = matrix_with_eigenvalues({C(1.15, 0.0), C(0.87, 0.0), C(0.95, 0.25), C(0.5, 0.0), C(-0.3, 0.0)}, rng);
  s.B = random_matrix(6, 3, rng);
  s.C = random_matrix(2, 6, rng);
  s.D = random_matrix(2, 3, rng);
  return s;
}

TEST(Era, RealisesAnUnstableSystemExactly) {
  std::mt19937_64 rng(41);
  const TrueSystem t = true_system(rng);
  const auto y = markov_of(t.A, t.B, t.C, t.D, 30);
  const EraResult r = era(y, 1e-3);
  EXPECT_EQ(r.suggested_order, 6);
  EXPECT_EQ(r.order, 6);
  // Lee's sizes: r = floor(30 * 3 / 5) = 18 block rows, s = 12 block columns.
  EXPECT_EQ(r.block_rows, 18);
  EXPECT_EQ(r.block_columns, 12);
  EXPECT_EQ(r.hankel_singular_values.size(), 36);
  EXPECT_LT(r.hankel_singular_values(6), 1e-12 * r.hankel_singular_values(0));
  EXPECT_GT(r.hankel_singular_values(5), 1e-6 * r.hankel_singular_values(0));
  EXPECT_LT(eigenvalue_error(t.A, r.system.A), 1e-9);
  // Markov parameters of the realisation, also beyond the data used (k up to 50).
  const auto yhat = markov_of(r.system.A, r.system.B, r.system.C, r.system.D, 50);
  const auto ytrue = markov_of(t.A, t.B, t.C, t.D, 50);
  const double e = max_relative_error(ytrue, yhat, 0, 50);
  EXPECT_LT(e, 1e-8);
  EXPECT_EQ(r.system.sample_time, 1e-3);
  EXPECT_GT(testing::spectral_radius(r.system.A), 1.1);  // still unstable
  ::testing::Test::RecordProperty("markov_error", testing::sci(e));
}

TEST(Era, DataCorrelationVariantRealisesTheSameSystem) {
  std::mt19937_64 rng(42);
  const TrueSystem t = true_system(rng);
  const auto y = markov_of(t.A, t.B, t.C, t.D, 34);
  EraOptions o;
  o.data_correlation = true;
  o.correlation_blocks = 2;
  const EraResult r = era(y, 1e-3, o);
  EXPECT_EQ(r.order, 6);
  EXPECT_GT(r.correlation_singular_values.size(), 6);
  EXPECT_LT(eigenvalue_error(t.A, r.system.A), 1e-8);
  const double e = max_relative_error(markov_of(t.A, t.B, t.C, t.D, 40),
                                      markov_of(r.system.A, r.system.B, r.system.C, r.system.D, 40), 0, 40);
  EXPECT_LT(e, 1e-7);
  ::testing::Test::RecordProperty("markov_error", testing::sci(e));
}

TEST(Era, OrderOverrideAndBlockSizes) {
  std::mt19937_64 rng(43);
  const TrueSystem t = true_system(rng);
  const auto y = markov_of(t.A, t.B, t.C, t.D, 30);
  EraOptions o;
  o.order = 4;
  o.block_rows = 10;
  o.block_columns = 10;
  const EraResult r = era(y, 1e-3, o);
  EXPECT_EQ(r.system.states(), 4);
  EXPECT_EQ(r.suggested_order, 6);
  EXPECT_EQ(r.hankel_singular_values.size(), 20);
  o.order = 21;  // more than the 2 x 10 block rows can hold
  EXPECT_THROW(era(y, 1e-3, o), Error);
  o.order = 8;  // beyond the numerical rank (6)
  EXPECT_THROW(era(y, 1e-3, o), InsufficientData);
  o.order = 0;
  o.block_rows = 20;
  o.block_columns = 11;  // needs Y_31
  EXPECT_THROW(era(y, 1e-3, o), Error);
}

// A state the noise hides: Markov parameters of the 6-state system plus white noise that
// lifts the 7th singular value (0 without noise) to about the 6th. Order 6 is then refused with
// the reason named; without noise, or without the check, it is realised.
TEST(Era, StateBelowTheNoiseFloorIsRefused) {
  std::mt19937_64 rng(44);
  const TrueSystem t = true_system(rng);
  auto y = markov_of(t.A, t.B, t.C, t.D, 30);
  EraOptions o;
  o.min_gap = 2.0;
  o.order = 6;
  const EraResult clean = era(y, 1e-3, o);
  EXPECT_LT(eigenvalue_error(t.A, clean.system.A), 1e-8);
  const double sv6 = clean.hankel_singular_values(5);
  for (std::size_t k = 1; k < y.size(); ++k) y[k] += random_matrix(2, 3, rng, sv6 / std::sqrt(30.0));
  const Eigen::VectorXd noisy = era(y, 1e-3).hankel_singular_values;
  ASSERT_LT(noisy(5), 2.0 * noisy(6));  // the 6th state is not clear of the noise
  try {
    era(y, 1e-3, o);
    FAIL() << "expected InsufficientData";
  } catch (const InsufficientData& e) {
    EXPECT_NE(std::string(e.what()).find("do not determine 6 states"), std::string::npos) << e.what();
  }
  o.min_gap = 0.0;
  EXPECT_EQ(era(y, 1e-3, o).system.states(), 6);
}

TEST(Era, SuggestedOrderIsTheLargestGap) {
  Eigen::VectorXd s(6);
  s << 10.0, 5.0, 4.0, 1e-3, 5e-4, 1e-4;
  EXPECT_EQ(suggest_order(s), 3);
  s << 10.0, 5.0, 4.0, 3.0, 0.0, 0.0;
  EXPECT_EQ(suggest_order(s), 4);
  // A numerical-noise tail below a bigger gap does not win (noise-free data through LS).
  s << 10.0, 5.0, 1e-7, 1e-8, 1e-20, 0.0;
  EXPECT_EQ(suggest_order(s), 2);
  s << 10.0, 1.0, 0.9, 0.8, 0.7, 0.6;
  EXPECT_EQ(suggest_order(s), 1);
  EXPECT_THROW(suggest_order(Eigen::VectorXd::Zero(3)), InsufficientData);
}

}  // namespace era_test
}  // namespace ambid::ident
