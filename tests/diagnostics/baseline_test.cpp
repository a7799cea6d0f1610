#include "diagnostics/monitor/baseline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/error.hpp"

namespace ambid::diag {
namespace baseline_test {

struct Sample {
  std::vector<double> values, sigmas;
};

Sample gaussian(std::size_t n, double mean, double true_sigma, double reported_sigma, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, true_sigma);
  Sample s;
  for (std::size_t i = 0; i < n; ++i) {
    s.values.push_back(mean + noise(rng));
    s.sigmas.push_back(reported_sigma);
  }
  return s;
}

TEST(Baseline, HonestSigmasNeedNoExtraSpread) {
  const Sample s = gaussian(400, 17.5, 0.1, 0.1, 1);
  const Baseline b = learn_baseline(s.values, s.sigmas);
  EXPECT_EQ(b.origin, BaselineOrigin::learned);
  EXPECT_EQ(b.windows, 400u);
  EXPECT_NEAR(b.mean, 17.5, 3 * 0.1 / 20);
  EXPECT_DOUBLE_EQ(b.reported_sigma, 0.1);
  // The MAD estimate has a relative sd of about 1.17/sqrt(400) = 6 %: tau is at most
  // sqrt(1.12^2 - 1) ~ 0.5 sigma at 2 sd.
  EXPECT_LT(b.extra_spread, 0.05);
  EXPECT_NEAR(b.mean_sigma, 0.1 / 20, 0.1 * 0.1 / 20 + 1e-12);
  EXPECT_NEAR(b.sigma_eff(0.1), 0.1, 0.012);
}

TEST(Baseline, ScatterBeyondTheReportedSigmaWidensSigmaEff) {
  // The identifier claims 0.05 but the estimates scatter by 0.1: tau = sqrt(0.1^2 - 0.05^2).
  const Sample s = gaussian(400, 17.5, 0.1, 0.05, 2);
  const Baseline b = learn_baseline(s.values, s.sigmas);
  EXPECT_NEAR(b.extra_spread, std::sqrt(0.1 * 0.1 - 0.05 * 0.05), 0.015);
  EXPECT_NEAR(b.sigma_eff(0.05), 0.1, 0.012);
  EXPECT_NEAR(b.mean_sigma, 0.1 / 20, 0.0006);
  EXPECT_NEAR(b.z(17.5 + 0.3, 0.05), (17.5 + 0.3 - b.mean) / b.sigma_eff(0.05), 1e-12);
}

TEST(Baseline, RobustToAnOutlier) {
  Sample s = gaussian(50, 1.0, 0.002, 0.002, 3);
  const Baseline clean = learn_baseline(s.values, s.sigmas);
  s.values[10] = 1.5;  // one wild window
  const Baseline with_outlier = learn_baseline(s.values, s.sigmas);
  EXPECT_NEAR(with_outlier.extra_spread, clean.extra_spread, 0.0005);  // scatter barely moves
  EXPECT_NEAR(with_outlier.mean - clean.mean, 0.5 / 50, 1e-3);         // the mean does
}

TEST(Baseline, Given) {
  const Baseline b = given_baseline(490.0, 2.0);
  EXPECT_EQ(b.origin, BaselineOrigin::given);
  EXPECT_DOUBLE_EQ(b.mean_sigma, 0.0);
  EXPECT_DOUBLE_EQ(b.sigma_eff(1.5), 2.5);
  EXPECT_DOUBLE_EQ(b.relative_change(539.0), 0.1);
  EXPECT_THROW(given_baseline(0.0), Error);
  EXPECT_THROW(given_baseline(1.0, -1.0), Error);
}

TEST(Baseline, RefusesBadInput) {
  const std::vector<double> four{1, 2, 3, 4};
  EXPECT_THROW(learn_baseline(four, four), InsufficientData);
  const std::vector<double> v{1, 2, 3, 4, 5}, bad_sigma{1, 1, -1, 1, 1}, short_sigma{1, 1};
  EXPECT_THROW(learn_baseline(v, bad_sigma), Error);
  EXPECT_THROW(learn_baseline(v, short_sigma), Error);
  // No sigmas (0): the scatter is the whole sigma_eff, learned from >= 6 scattering windows.
  const std::vector<double> no_sigma5(5, 0.0), no_sigma6(6, 0.0), six{1, 2, 3, 4, 5, 6}, flat(6, 2.0);
  EXPECT_THROW(learn_baseline(v, no_sigma5), InsufficientData);
  EXPECT_THROW(learn_baseline(flat, no_sigma6), InsufficientData);
  const Baseline b = learn_baseline(six, no_sigma6);
  EXPECT_DOUBLE_EQ(b.extra_spread, 1.4826 * 1.5);  // MAD of 1..6 about median 3.5 is 1.5
  EXPECT_DOUBLE_EQ(b.sigma_eff(0.0), b.extra_spread);
  const std::vector<double> nan{1, 2, std::nan(""), 4, 5};
  EXPECT_THROW(learn_baseline(nan, v), Error);
}

}  // namespace baseline_test
}  // namespace ambid::diag
