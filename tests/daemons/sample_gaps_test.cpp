// The identifier's view of the plant's samples (issue 18): batches that never arrived are a
// gap of the right size; new records, sources and a restarted plant are not.
#include "services/daemons/sample_gaps.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ambid::daemons {
namespace sample_gaps_test {

constexpr double kT = 1e-4;
constexpr std::uint32_t kCount = 500;  // 0.05 s per batch

bus::PlantSamples batch(std::uint64_t seq, double t0) {
  bus::PlantSamples b;
  b.plant_id = "bearing-1";
  b.seq = seq;
  b.t0 = t0;
  b.sample_time = kT;
  b.count = kCount;
  return b;
}

TEST(SampleGaps, ConsecutiveBatchesAndNewRecordsOnTheSameClockAreNoGap) {
  SampleGaps gaps;
  // The plant's clock runs on across records: record 2 starts (seq 0) where record 1 ended.
  // t0 carries rounding of sums of sample times.
  for (std::uint64_t k = 0; k < 20; ++k) EXPECT_FALSE(gaps.check(batch(k, 0.05 * double(k) + 1e-13))) << k;
  EXPECT_FALSE(gaps.check(batch(0, 1.0)));
  EXPECT_FALSE(gaps.check(batch(1, 1.05)));
}

TEST(SampleGaps, BatchesNeverReceivedAreAGapOfTheirSamples) {
  SampleGaps gaps;
  ASSERT_FALSE(gaps.check(batch(0, 0.0)));
  ASSERT_FALSE(gaps.check(batch(1, 0.05)));
  // Batches 2 .. 7 were lost: 6 batches, 3000 samples, 0.1 to 0.4 s.
  const std::optional<SampleGap> gap = gaps.check(batch(8, 0.4));
  ASSERT_TRUE(gap);
  EXPECT_EQ(gap->batches, 6u);
  EXPECT_EQ(gap->samples, 3000u);
  EXPECT_NEAR(gap->from, 0.1, 1e-12);
  EXPECT_NEAR(gap->to, 0.4, 1e-12);
  EXPECT_NE(gap->message().find("missed 3000 samples"), std::string::npos) << gap->message();
  EXPECT_FALSE(gaps.check(batch(9, 0.45)));
}

TEST(SampleGaps, AGapAcrossARecordStartIsFoundByTheClock) {
  SampleGaps gaps;
  ASSERT_FALSE(gaps.check(batch(18, 0.9)));
  ASSERT_FALSE(gaps.check(batch(19, 0.95)));
  // The end of that record and the first two batches of the next never arrived.
  const std::optional<SampleGap> gap = gaps.check(batch(2, 1.1));
  ASSERT_TRUE(gap);
  EXPECT_EQ(gap->samples, 1000u);
  EXPECT_EQ(gap->batches, 0u);  // numbers restart with a record: only the clock tells
}

TEST(SampleGaps, ARestartedPlantWhoseClockStartsAgainIsNoGap) {
  SampleGaps gaps;
  ASSERT_FALSE(gaps.check(batch(40, 2.0)));
  EXPECT_FALSE(gaps.check(batch(0, 0.0)));
  EXPECT_FALSE(gaps.check(batch(1, 0.05)));
}

TEST(SampleGaps, MalformedBatchesAreIgnored) {
  SampleGaps gaps;
  ASSERT_FALSE(gaps.check(batch(0, 0.0)));
  bus::PlantSamples nan = batch(1, std::numeric_limits<double>::quiet_NaN());
  EXPECT_FALSE(gaps.check(nan));
  bus::PlantSamples no_time = batch(1, 0.05);
  no_time.sample_time = 0.0;
  EXPECT_FALSE(gaps.check(no_time));
  EXPECT_FALSE(gaps.check(batch(1, 0.05)));  // the state is where the last good batch left it
}

// A restarted plant (its clock back near 0) whose first batches this consumer missed: the gap
// is those batches on the new clock (measured in the soak before: "missed 0 samples (plant
// time 86.25 to 29.8 s, 71 batches)", a negative length).
TEST(SampleGaps, BatchesMissedAfterAPlantRestartAreAGapOnTheNewClock) {
  SampleGaps gaps;
  ASSERT_FALSE(gaps.check(batch(0, 80.0)));
  ASSERT_FALSE(gaps.check(batch(1, 80.05)));
  const std::optional<SampleGap> gap = gaps.check(batch(4, 0.2));  // batches 0 .. 3 of the new clock missed
  ASSERT_TRUE(gap);
  EXPECT_EQ(gap->batches, 4u);
  EXPECT_EQ(gap->samples, 2000u);
  EXPECT_NEAR(gap->from, 0.0, 1e-12);
  EXPECT_NEAR(gap->to, 0.2, 1e-12);
}

}  // namespace sample_gaps_test
}  // namespace ambid::daemons
