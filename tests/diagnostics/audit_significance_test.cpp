// The audit's acceptance rule against its own null hypothesis: with coloured, cross-correlated
// noise and a fixed candidate change d, the improvement statistic z is standard normal (mean
// 0, spread 1, the 1 % tail holds about 1 %), a real change of the same size is found, and
// the Bonferroni threshold is the normal quantile.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "diagnostics/audit/audit_significance.hpp"

namespace ambid::diag {
namespace audit_significance_test {

constexpr Eigen::Index kSamples = 2000;

// Two outputs of AR(1) noise (pole 0.9, strongly coloured), the second partly the first.
Eigen::MatrixXd coloured_noise(std::uint64_t seed, double level) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd n(kSamples, 2);
  double a = 0.0, b = 0.0;
  for (Eigen::Index k = 0; k < kSamples; ++k) {
    a = 0.9 * a + normal(rng);
    b = 0.9 * b + normal(rng);
    n(k, 0) = level * a;
    n(k, 1) = level * (0.6 * a + 0.8 * b);
  }
  return n;
}

// The nominal response and a candidate's change: slow sinusoids, as a model change looks.
Eigen::MatrixXd response(double scale) {
  Eigen::MatrixXd y(kSamples, 2);
  for (Eigen::Index k = 0; k < kSamples; ++k) {
    y(k, 0) = scale * std::sin(0.013 * double(k));
    y(k, 1) = scale * std::cos(0.021 * double(k) + 0.4);
  }
  return y;
}

TEST(AuditSignificance, UnderTheNullZIsStandardNormal) {
  const Eigen::MatrixXd nominal = 5.0 * response(1.0), extended = nominal + 0.05 * response(1.0);
  const Segment all{0, kSamples};
  constexpr int kSeeds = 300;
  double sum = 0.0, sum2 = 0.0;
  int above = 0;
  for (int s = 0; s < kSeeds; ++s) {
    const ImprovementTest t =
        improvement_test(nominal + coloured_noise(std::uint64_t(s) + 1, 1.0), nominal, extended, all, 100);
    sum += t.z;
    sum2 += t.z * t.z;
    above += t.z > acceptance_threshold(0.05, 1) ? 1 : 0;
  }
  const double mean = sum / kSeeds, sd = std::sqrt(sum2 / kSeeds - mean * mean);
  EXPECT_NEAR(mean, 0.0, 0.2);  // 3.5 standard errors of a mean of 300
  EXPECT_NEAR(sd, 1.0, 0.15);   // white-noise formulas would give sd ~ 4 with this colour
  EXPECT_LE(above, 30);         // expected 15 of 300 at 5 %
  EXPECT_GE(above, 4);
}

TEST(AuditSignificance, ARealChangeIsFoundAndAnOvershootIsNoReduction) {
  const Eigen::MatrixXd nominal = 5.0 * response(1.0), change = 2.0 * response(1.0);  // z about 9
  const Eigen::MatrixXd measured = nominal + change + coloured_noise(7, 1.0);
  const ImprovementTest right = improvement_test(measured, nominal, nominal + change, {0, kSamples}, 100);
  EXPECT_GT(right.z, acceptance_threshold(0.01, 10));
  EXPECT_GT(right.reduction, 0.0);
  EXPECT_LT(right.p_value, 1e-4);
  // Three times the change points the right way but predicts worse.
  const ImprovementTest over = improvement_test(measured, nominal, nominal + 3.0 * change, {0, kSamples}, 100);
  EXPECT_LT(over.reduction, 0.0);
  EXPECT_THROW(improvement_test(measured, nominal, nominal, {0, kSamples + 1}, 10), Error);
}

TEST(AuditSignificance, ThresholdIsTheBonferroniNormalQuantile) {
  EXPECT_NEAR(acceptance_threshold(0.05, 1), 1.6448536, 1e-6);
  EXPECT_NEAR(acceptance_threshold(0.01, 5), 2.8781617, 1e-6);  // upper 0.2 % point
  EXPECT_THROW(acceptance_threshold(0.0, 5), Error);
  EXPECT_THROW(acceptance_threshold(0.1, 0), Error);
}

}  // namespace audit_significance_test
}  // namespace ambid::diag
