// A consumer's view of the identifier's model numbers (issue 18): a jump forward is the models
// it missed; a restarted identifier (numbers from 0 again) is no gap.
#include "services/daemons/model_gaps.hpp"

#include <gtest/gtest.h>

namespace ambid::daemons {
namespace model_gaps_test {

TEST(ModelGaps, CountsTheModelsNeverReceived) {
  ModelGaps gaps;
  EXPECT_EQ(gaps.missed(5), 0u);  // the first model seen: nothing known before it
  EXPECT_FALSE(gaps.restarted());
  EXPECT_EQ(gaps.missed(6), 0u);
  EXPECT_EQ(gaps.missed(436), 429u);  // stopped for a while: 7 ... 435 never arrived
  EXPECT_EQ(gaps.missed(437), 0u);
  EXPECT_FALSE(gaps.restarted());
  EXPECT_EQ(gaps.missed(0), 0u);  // the identifier restarted
  EXPECT_TRUE(gaps.restarted());
  EXPECT_EQ(gaps.missed(1), 0u);
  EXPECT_FALSE(gaps.restarted());
  EXPECT_EQ(gaps.missed(3), 1u);
}

}  // namespace model_gaps_test
}  // namespace ambid::daemons
