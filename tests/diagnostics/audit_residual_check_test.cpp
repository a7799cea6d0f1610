// The residual check (audit_residual_check.hpp) against its stated false-rejection rate on
// noise it knows nothing of (white, strongly coloured, any level), and its power on a residual
// that holds a little of r through an unknown filter.
#include <cmath>
#include <iostream>
#include <random>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "diagnostics/audit/audit_residual_check.hpp"

namespace ambid::diag {
namespace audit_residual_check_test {

constexpr Eigen::Index kSamples = 4000;  // a validation segment of the audit tests

// Two PRBS excitations (clock of 3 samples, +-1 V).
Eigen::MatrixXd prbs(std::mt19937_64& rng) {
  Eigen::MatrixXd r(kSamples, 2);
  std::bernoulli_distribution coin(0.5);
  for (Eigen::Index j = 0; j < 2; ++j)
    for (Eigen::Index k = 0; k < kSamples; ++k) r(k, j) = k % 3 == 0 ? (coin(rng) ? 1.0 : -1.0) : r(k - 1, j);
  return r;
}

// Three residual columns: white, AR(2) with a resonance (coloured like a closed loop's noise
// response), and AR(1) with pole 0.95; levels 1e-7, 1e-3, 3e-3.
Eigen::MatrixXd noise(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd e = Eigen::MatrixXd::Zero(kSamples, 3);
  for (Eigen::Index k = 0; k < kSamples; ++k) {
    e(k, 0) = 1e-7 * n(rng);
    e(k, 1) = 1e-3 * n(rng) + (k >= 2 ? 1.6 * e(k - 1, 1) - 0.8 * e(k - 2, 1) : 0.0);
    e(k, 2) = 3e-3 * n(rng) + (k >= 1 ? 0.95 * e(k - 1, 2) : 0.0);
  }
  return e;
}

TEST(AuditResidualCheck, NoiseIndependentOfRIsRejectedAtTheStatedRate) {
  std::mt19937_64 rng(4242);
  constexpr int kTrials = 300;
  constexpr double kAlpha = 0.05;
  int rejected = 0;
  double coherence_z = 0.0;
  for (int t = 0; t < kTrials; ++t) {
    const Eigen::MatrixXd r = prbs(rng);
    const ResidualCheck c = residual_check(noise(rng), r, kAlpha);
    ASSERT_TRUE(c.determinable);
    rejected += c.consistent ? 0 : 1;
    coherence_z += c.coherence_z.mean() / kTrials;
  }
  std::cerr << rejected << " of " << kTrials << " rejected at alpha " << kAlpha << ", mean coherence z " << coherence_z
            << "\n";
  // Bonferroni makes the rate at most alpha: 15 expected at 5 % if exact; 27 or more would
  // happen with probability < 0.2 % at 5 %.
  EXPECT_LE(rejected, 26);
  EXPECT_GE(rejected, 2);  // not a check that can never reject
  EXPECT_NEAR(coherence_z, 0.0, 0.2);
}

TEST(AuditResidualCheck, ResidualDrivenByRFailsIt) {
  std::mt19937_64 rng(77);
  const Eigen::MatrixXd r = prbs(rng);
  Eigen::MatrixXd e = noise(rng);
  // r2 through a lag of 5 samples, about 30 % of the position noise in rms: a wrong plant.
  double lagged = 0.0;
  for (Eigen::Index k = 0; k < kSamples; ++k) {
    lagged += (r(k, 1) - lagged) / 5.0;
    e(k, 0) += 0.6e-7 * lagged;
  }
  const ResidualCheck c = residual_check(e, r, 0.01);
  EXPECT_FALSE(c.consistent) << "p " << c.p_value << ", coherence " << c.coherence_mean.transpose();
  EXPECT_LT(c.coherence_p[0], 1e-4);
  EXPECT_GT(c.coherence_p[1], 1e-3);  // the other outputs stay clean
}

TEST(AuditResidualCheck, ShortSegmentsAreNotDeterminableAndBadInputIsAnError) {
  std::mt19937_64 rng(1);
  const Eigen::MatrixXd r = prbs(rng), e = noise(rng);
  const ResidualCheck c = residual_check(e.topRows(500), r.topRows(500), 0.01);
  EXPECT_FALSE(c.determinable);
  EXPECT_TRUE(c.consistent);
  EXPECT_FALSE(c.reason.empty());
  EXPECT_THROW(residual_check(e, r.topRows(100), 0.01), Error);
  EXPECT_THROW(residual_check(e, r, 1.5), Error);
}

}  // namespace audit_residual_check_test
}  // namespace ambid::diag
