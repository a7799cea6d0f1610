#include "services/report/ticks.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "core/error.hpp"

namespace ambid::report {
namespace ticks_test {

using ::testing::DoubleNear;
using ::testing::ElementsAre;

TEST(LogTicks, DecadesRoundedOutwardsAndMinorTicksAtTwoToNine) {
  const Ticks ticks = log_ticks(3.0, 2500.0);
  EXPECT_DOUBLE_EQ(ticks.range.lo, 1.0);
  EXPECT_DOUBLE_EQ(ticks.range.hi, 1e4);
  EXPECT_THAT(ticks.major, ElementsAre(DoubleNear(1, 1e-12), DoubleNear(10, 1e-11), DoubleNear(100, 1e-10),
                                       DoubleNear(1000, 1e-9), DoubleNear(1e4, 1e-8)));
  EXPECT_THAT(ticks.labels, ElementsAre("1", "10", "100", "1000", "10000"));
  ASSERT_EQ(ticks.minor.size(), 4u * 8u);  // 2..9 in each of the four decades
  EXPECT_NEAR(ticks.minor.front(), 2.0, 1e-12);
  EXPECT_NEAR(ticks.minor.back(), 9000.0, 1e-9);
}

TEST(LogTicks, ExactDecadeBoundsAreNotWidened) {
  const Ticks ticks = log_ticks(0.1, 100.0);
  EXPECT_DOUBLE_EQ(ticks.range.lo, 0.1);
  EXPECT_DOUBLE_EQ(ticks.range.hi, 100.0);
  EXPECT_THAT(ticks.labels, ElementsAre("0.1", "1", "10", "100"));
}

TEST(LogTicks, ManyDecadesLabelEveryOtherDecadeAndUseExponents) {
  const Ticks ticks = log_ticks(1e-12, 1e8);  // 20 decades
  EXPECT_EQ(ticks.major.size(), 11u);
  EXPECT_EQ(ticks.labels.front(), "1e-12");
  EXPECT_EQ(ticks.labels.back(), "1e8");
}

TEST(LogTicks, FixedRangeWithinOneDecadeLabelsTwoAndFive) {
  const Ticks ticks = log_ticks_fixed(15.0, 90.0);
  EXPECT_THAT(ticks.major, ElementsAre(DoubleNear(20, 1e-12), DoubleNear(50, 1e-12)));
  EXPECT_THAT(ticks.labels, ElementsAre("20", "50"));
}

TEST(LogTicks, RejectsNonPositiveRange) {
  EXPECT_THROW(log_ticks(0.0, 10.0), Error);
  EXPECT_THROW(log_ticks(-1.0, 10.0), Error);
  EXPECT_THROW(log_ticks(1.0, std::numeric_limits<double>::quiet_NaN()), Error);
}

TEST(LinearTicks, NiceStepsCoverTheData) {
  const Ticks ticks = linear_ticks(-183.0, 12.0);
  EXPECT_DOUBLE_EQ(ticks.range.lo, -200.0);
  EXPECT_DOUBLE_EQ(ticks.range.hi, 50.0);
  EXPECT_THAT(ticks.labels, ElementsAre("-200", "-150", "-100", "-50", "0", "50"));
}

TEST(LinearTicks, SmallStepsGetDecimalsAndNoNegativeZero) {
  const Ticks ticks = linear_ticks(-0.26, 0.31);
  EXPECT_THAT(ticks.labels, ElementsAre("-0.3", "-0.2", "-0.1", "0.0", "0.1", "0.2", "0.3", "0.4"));
}

TEST(LinearTicks, ZeroWidthSpanIsWidened) {
  const Ticks ticks = linear_ticks(5.0, 5.0);
  EXPECT_LT(ticks.range.lo, 5.0);
  EXPECT_GT(ticks.range.hi, 5.0);
  EXPECT_GE(ticks.major.size(), 2u);
}

TEST(LinearTicks, FixedRangeKeepsBoundsExactly) {
  const Ticks ticks = linear_ticks_fixed(-7.0, 23.0);
  EXPECT_DOUBLE_EQ(ticks.range.lo, -7.0);
  EXPECT_DOUBLE_EQ(ticks.range.hi, 23.0);
  EXPECT_THAT(ticks.labels, ElementsAre("-5", "0", "5", "10", "15", "20"));
}

}  // namespace ticks_test
}  // namespace ambid::report
