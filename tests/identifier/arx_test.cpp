#include "identifier/time_domain/arx.hpp"

#include <random>
#include <string>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace arx_test {

using testing::random_matrix;

// y[k] = a1 y[k-1] + a2 y[k-2] + b0 u[k] + b1 u[k-1] + b2 u[k-2] + e[k], 2 outputs, 2 inputs.
struct TrueArx {
  Eigen::MatrixXd a1, a2, b0, b1, b2;
};

TrueArx true_arx() {
  TrueArx t;
  t.a1.resize(2, 2);
  t.a1 << 0.9, -0.2, 0.1, 0.5;
  t.a2.resize(2, 2);
  t.a2 << -0.3, 0.05, 0.0, -0.2;
  t.b0.resize(2, 2);
  t.b0 << 0.4, 0.0, -0.1, 0.2;
  t.b1.resize(2, 2);
  t.b1 << 1.0, 0.5, -0.3, 0.8;
  t.b2.resize(2, 2);
  t.b2 << 0.2, -0.1, 0.6, 0.3;
  return t;
}

Eigen::MatrixXd simulate_arx(const TrueArx& t, const Eigen::MatrixXd& u, const Eigen::MatrixXd& e) {
  Eigen::MatrixXd y = Eigen::MatrixXd::Zero(u.rows(), 2);
  for (Eigen::Index k = 0; k < u.rows(); ++k) {
    Eigen::VectorXd v = t.b0 * u.row(k).transpose() + e.row(k).transpose();
    if (k >= 1) v += t.a1 * y.row(k - 1).transpose() + t.b1 * u.row(k - 1).transpose();
    if (k >= 2) v += t.a2 * y.row(k - 2).transpose() + t.b2 * u.row(k - 2).transpose();
    y.row(k) = v.transpose();
  }
  return y;
}

TEST(Arx, BreaksLeaveOutTheEquationsAcrossAJoint) {
  // Two noise-free records of the same system joined end to end: with the joint declared a
  // break the coefficients are exact; without it the q equations across the joint spoil them.
  std::mt19937_64 rng(22);
  const TrueArx t = true_arx();
  const Eigen::MatrixXd u1 = random_matrix(300, 2, rng), u2 = random_matrix(200, 2, rng);
  Eigen::MatrixXd u(500, 2), y(500, 2);
  u << u1, u2;
  y << simulate_arx(t, u1, Eigen::MatrixXd::Zero(300, 2)), simulate_arx(t, u2, Eigen::MatrixXd::Zero(200, 2));
  ArxOptions o;
  o.order = 2;
  o.direct_term = true;
  EXPECT_GT((fit_arx(y, u, o).a[0] - t.a1).norm(), 1e-3);
  o.breaks = {300};
  const ArxModel m = fit_arx(y, u, o);
  EXPECT_LT((m.a[0] - t.a1).norm(), 1e-12);
  EXPECT_LT((m.b[2] - t.b2).norm(), 1e-12);
  EXPECT_EQ(m.fit.rows, 500 - 2 - 2);  // k = 2..499 without k = 300, 301
}

TEST(Arx, NoiseFreeMimoCoefficientsAreExact) {
  std::mt19937_64 rng(21);
  const TrueArx t = true_arx();
  const Eigen::MatrixXd u = random_matrix(500, 2, rng);
  const Eigen::MatrixXd y = simulate_arx(t, u, Eigen::MatrixXd::Zero(500, 2));
  ArxOptions o;
  o.order = 2;
  o.direct_term = true;
  const ArxModel m = fit_arx(y, u, o);
  ASSERT_EQ(m.a.size(), 2u);
  ASSERT_EQ(m.b.size(), 3u);
  EXPECT_LT((m.a[0] - t.a1).norm(), 1e-12);
  EXPECT_LT((m.a[1] - t.a2).norm(), 1e-12);
  EXPECT_LT((m.b[0] - t.b0).norm(), 1e-12);
  EXPECT_LT((m.b[1] - t.b1).norm(), 1e-12);
  EXPECT_LT((m.b[2] - t.b2).norm(), 1e-12);
  EXPECT_EQ(m.fit.rows, 498);
  EXPECT_EQ(m.a_regressor(1, 0), 2);
  EXPECT_EQ(m.b_regressor(2, 1), 2 + 4 + 3);
  // The residuals of the fit are the (zero) noise.
  EXPECT_LT(arx_residuals(m, y, y, u).norm(), 1e-10);
}

TEST(Arx, SecondaryTargetOnTheSameRegressors) {
  std::mt19937_64 rng(22);
  const TrueArx t = true_arx();
  const Eigen::MatrixXd u = random_matrix(400, 2, rng);
  const Eigen::MatrixXd y = simulate_arx(t, u, 0.1 * random_matrix(400, 2, rng));
  // z[k] = c1 y[k-1] + d2 u[k-2], exactly.
  Eigen::MatrixXd c1(1, 2), d2(1, 2);
  c1 << 0.7, -1.1;
  d2 << 0.25, 2.0;
  Eigen::MatrixXd z = Eigen::MatrixXd::Zero(400, 1);
  for (Eigen::Index k = 2; k < 400; ++k) z.row(k) = c1 * y.row(k - 1).transpose() + d2 * u.row(k - 2).transpose();
  ArxOptions o;
  o.order = 2;
  const ArxModel m = fit_arx(z, y, u, o);
  EXPECT_EQ(m.targets, 1);
  EXPECT_LT((m.a[0] - c1).norm(), 1e-12);
  EXPECT_LT(m.a[1].norm(), 1e-12);
  EXPECT_LT(m.b[1].norm(), 1e-12);
  EXPECT_LT((m.b[2] - d2).norm(), 1e-12);
  EXPECT_EQ(m.b[0].norm(), 0.0);
}

// The predicted coefficient covariance sigma^2 (Phi'Phi)^-1 against the spread of the
// estimates over independent noise realisations (same input, 400 runs).
TEST(Arx, CoefficientCovarianceMatchesMonteCarlo) {
  const Eigen::Index N = 2000;
  const int runs = 400;
  std::mt19937_64 rng(23);
  Eigen::MatrixXd u = random_matrix(N, 1, rng);
  const double a = 0.7, b = 1.5, sigma = 0.5;
  std::vector<Eigen::Vector2d> est;
  Eigen::Matrix2d predicted = Eigen::Matrix2d::Zero();
  for (int r = 0; r < runs; ++r) {
    const Eigen::MatrixXd e = random_matrix(N, 1, rng, sigma);
    Eigen::MatrixXd y(N, 1);
    y(0, 0) = e(0, 0);
    for (Eigen::Index k = 1; k < N; ++k) y(k, 0) = a * y(k - 1, 0) + b * u(k - 1, 0) + e(k, 0);
    ArxOptions o;
    o.order = 1;
    const ArxModel m = fit_arx(y, u, o);
    est.emplace_back(m.a[0](0, 0), m.b[1](0, 0));
    Eigen::Matrix2d c;
    c << m.covariance(0, 0, 0, 0), m.covariance(0, 0, 0, 1), m.covariance(0, 1, 0, 0), m.covariance(0, 1, 0, 1);
    predicted += c / runs;
    if (r == 0) {
      EXPECT_NEAR(m.a_standard_deviation(1)(0, 0), std::sqrt(c(0, 0)), 1e-15);
      EXPECT_NEAR(m.b_standard_deviation(1)(0, 0), std::sqrt(c(1, 1)), 1e-15);
    }
  }
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& v : est) mean += v / runs;
  Eigen::Matrix2d empirical = Eigen::Matrix2d::Zero();
  for (const auto& v : est) empirical += (v - mean) * (v - mean).transpose() / (runs - 1);
  // Unbiased within 4 standard errors of the mean.
  EXPECT_NEAR(mean(0), a, 4.0 * std::sqrt(predicted(0, 0) / runs));
  EXPECT_NEAR(mean(1), b, 4.0 * std::sqrt(predicted(1, 1) / runs));
  // Variances agree within 20 % (the sampling spread of a variance over 400 runs is ~7 %).
  EXPECT_NEAR(empirical(0, 0) / predicted(0, 0), 1.0, 0.2);
  EXPECT_NEAR(empirical(1, 1) / predicted(1, 1), 1.0, 0.2);
  const double rho_e = empirical(0, 1) / std::sqrt(empirical(0, 0) * empirical(1, 1));
  const double rho_p = predicted(0, 1) / std::sqrt(predicted(0, 0) * predicted(1, 1));
  EXPECT_NEAR(rho_e, rho_p, 0.15);
  ::testing::Test::RecordProperty("var_ratio_a", testing::sci(empirical(0, 0) / predicted(0, 0)));
  ::testing::Test::RecordProperty("var_ratio_b", testing::sci(empirical(1, 1) / predicted(1, 1)));
}

TEST(Arx, TooShortRecordIsInsufficientData) {
  std::mt19937_64 rng(24);
  ArxOptions o;
  o.order = 3;
  o.direct_term = true;
  // 2 outputs, 2 inputs, q = 3: 2 + 12 = 14 regressors, needs more than 17 samples.
  try {
    fit_arx(random_matrix(17, 2, rng), random_matrix(17, 2, rng), o);
    FAIL() << "expected InsufficientData";
  } catch (const InsufficientData& e) {
    EXPECT_NE(std::string(e.what()).find("14 regressors"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("got 17"), std::string::npos) << e.what();
  }
}

TEST(Arx, UnexcitedInputIsNamed) {
  std::mt19937_64 rng(25);
  Eigen::MatrixXd u = random_matrix(300, 2, rng);
  u.col(1).setZero();
  const Eigen::MatrixXd y = simulate_arx(true_arx(), u, 0.1 * random_matrix(300, 2, rng));
  ArxOptions o;
  o.order = 2;
  o.input_symbol = "r";
  try {
    fit_arx(y, u, o);
    FAIL() << "expected InsufficientData";
  } catch (const InsufficientData& e) {
    EXPECT_NE(std::string(e.what()).find("r2[k-1] is identically zero"), std::string::npos) << e.what();
  }
}

TEST(Arx, OverParameterisedNoiseFreeDataAreRankDeficient) {
  // A first-order SISO system fitted with order 3 from noise-free data: y[k-2], y[k-3] add no
  // information beyond u (the state is fixed by y[k-1]).
  std::mt19937_64 rng(26);
  const Eigen::MatrixXd u = random_matrix(300, 1, rng);
  Eigen::MatrixXd y = Eigen::MatrixXd::Zero(300, 1);
  for (Eigen::Index k = 1; k < 300; ++k) y(k, 0) = 0.8 * y(k - 1, 0) + u(k - 1, 0);
  ArxOptions o;
  o.order = 3;
  try {
    fit_arx(y, u, o);
    FAIL() << "expected InsufficientData";
  } catch (const InsufficientData& e) {
    EXPECT_NE(std::string(e.what()).find("rank deficient"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("2 directions"), std::string::npos) << e.what();
  }
}

TEST(Arx, BadArgumentsAreErrors) {
  ArxOptions o;
  o.order = 0;
  EXPECT_THROW(fit_arx(Eigen::MatrixXd::Ones(50, 1), Eigen::MatrixXd::Ones(50, 1), o), Error);
  o.order = 1;
  EXPECT_THROW(fit_arx(Eigen::MatrixXd::Ones(50, 1), Eigen::MatrixXd::Ones(49, 1), o), Error);
}

}  // namespace arx_test
}  // namespace ambid::ident
