// Cutting a record of reference steps into its settled levels (frequency_domain/
// settled_levels.hpp): a gap that steps through known levels, approaches each with a first-order
// transient and carries white noise; the levels, their spans and the steps against the schedule.
#include "identifier/frequency_domain/settled_levels.hpp"

#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace ambid::ident {
namespace settled_levels_test {

constexpr double kTs = 3.25e-3;
constexpr Eigen::Index kHold = 460;  // samples per level (1.5 s)

// Levels in m held kHold samples each, approached with a 50 ms time constant, 20 um noise.
Eigen::VectorXd stepped_gap(const std::vector<double>& levels, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 20e-6);
  Eigen::VectorXd x(Eigen::Index(levels.size()) * kHold);
  double state = levels.front();
  const double decay = std::exp(-kTs / 0.05);
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    state = levels[std::size_t(k / kHold)] + decay * (state - levels[std::size_t(k / kHold)]);
    x(k) = state + noise(rng);
  }
  return x;
}

TEST(SettledLevels, FindsTheScheduleAndGathersRepeatedVisits) {
  const std::vector<double> schedule = {0.014, 0.013, 0.015, 0.014, 0.0155};
  const SettledLevels found = find_settled_levels(stepped_gap(schedule, 3), kTs);
  ASSERT_EQ(found.steps.size(), 4u);
  for (std::size_t s = 0; s < found.steps.size(); ++s) {
    // The steps' largest difference of means lies within the transient (a few time constants).
    EXPECT_GE(found.steps[s], Eigen::Index(s + 1) * kHold);
    EXPECT_LT(found.steps[s], Eigen::Index(s + 1) * kHold + 40);
  }
  ASSERT_EQ(found.levels.size(), 4u);  // 14 mm twice
  const std::vector<double> means = {0.014, 0.013, 0.015, 0.0155};
  const Eigen::Index settle = std::lround(0.3 / kTs), window = std::lround(0.1 / kTs);
  for (std::size_t l = 0; l < means.size(); ++l) {
    SCOPED_TRACE(l);
    // 20 um over >= 250 samples: the mean within 2 um; the transient (50 ms) has died out.
    EXPECT_NEAR(found.levels[l].mean, means[l], 2e-6);
    for (const SettledSpan& span : found.levels[l].spans) {
      const Eigen::Index visit = span.first / kHold;
      EXPECT_DOUBLE_EQ(schedule[std::size_t(visit)], means[l]);
      EXPECT_GE(span.first, visit * kHold + settle);
      EXPECT_LE(span.first + span.samples, (visit + 1) * kHold);
      EXPECT_GT(span.samples, kHold - settle - window - 40);
    }
  }
  EXPECT_EQ(found.levels[0].spans.size(), 2u);
  EXPECT_NEAR(found.step, 0.02 * 0.014, 1e-5);  // 2 % of the median gap
}

TEST(SettledLevels, OneLevelWithoutStepsAndShortLevelsLeftOut) {
  const SettledLevels held = find_settled_levels(stepped_gap({0.014}, 4), kTs);
  EXPECT_TRUE(held.steps.empty());
  ASSERT_EQ(held.levels.size(), 1u);
  EXPECT_EQ(held.levels[0].spans[0].first, std::lround(0.3 / kTs));
  EXPECT_EQ(held.levels[0].samples(), kHold - std::lround(0.3 / kTs));
  SettledLevelOptions o;
  o.min_samples = kHold;  // no settled part is that long
  EXPECT_TRUE(find_settled_levels(stepped_gap({0.014, 0.015}, 5), kTs, o).levels.empty());
}

TEST(SettledLevels, BadInputIsNamed) {
  EXPECT_THROW(find_settled_levels(Eigen::VectorXd::Constant(100, 0.014), 0.0), Error);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(100, 0.014);
  x(5) = std::nan("");
  EXPECT_THROW(find_settled_levels(x, kTs), Error);
  SettledLevelOptions o;
  o.window = -1.0;
  EXPECT_THROW(find_settled_levels(Eigen::VectorXd::Constant(100, 0.014), kTs, o), Error);
}

}  // namespace settled_levels_test
}  // namespace ambid::ident
