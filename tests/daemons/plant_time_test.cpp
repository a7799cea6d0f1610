// The diagnostics daemon's plant clock (issue 18): a replay of models already seen is skipped;
// a restarted plant (its clock back near 0) continues the history one window after the last
// model instead of being discarded until its new clock passes the old maximum.
#include "services/daemons/plant_time.hpp"

#include <gtest/gtest.h>

namespace ambid::daemons {
namespace plant_time_test {

TEST(PlantTime, SkipsReplaysAndContinuesAfterARestart) {
  PlantTime clock;
  for (double t = 0.5; t <= 120.0; t += 0.25) ASSERT_TRUE(clock.accept(t, 0.25));
  EXPECT_DOUBLE_EQ(*clock.last(), 120.0);
  for (double t = 118.25; t <= 120.0; t += 0.25) EXPECT_FALSE(clock.accept(t, 0.25)) << t;  // a replayed history

  const auto first = clock.accept(0.5, 0.25);  // the restarted plant's first model
  ASSERT_TRUE(first);
  EXPECT_TRUE(first->after_restart);
  EXPECT_DOUBLE_EQ(first->time, 120.25);
  const auto next = clock.accept(0.75, 0.25);
  ASSERT_TRUE(next);
  EXPECT_FALSE(next->after_restart);
  EXPECT_DOUBLE_EQ(next->time, 120.5);
  EXPECT_FALSE(clock.accept(0.5, 0.25));  // replays of the new epoch are skipped too
  EXPECT_FALSE(clock.accept(0.75, 0.25));
  EXPECT_DOUBLE_EQ(*clock.last(), 120.5);
}

}  // namespace plant_time_test
}  // namespace ambid::daemons
