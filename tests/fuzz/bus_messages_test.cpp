// Every bus message type under a few hundred mutated messages (bus_messages.hpp; the slow
// label runs 100 times more): each taken or refused with ambid::Error, and the mutations
// reach both outcomes. The list of types is the bus's own (message_list.hpp): a new message
// type without a fuzz target does not compile.
#include <gtest/gtest.h>

#include "fuzz/bus_messages.hpp"

namespace ambid::fuzz {
namespace bus_messages_test {

constexpr int kIterations = 400;

#define AMBID_FUZZ_TEST(Message, topic_name, qos_profile)                    \
  TEST(FuzzBus, Message) {                                                   \
    const FuzzCount c = fuzz_bus_message<bus::Message>(kIterations);         \
    EXPECT_EQ(c.accepted + c.refused, kIterations);                          \
    EXPECT_GT(c.refused, kIterations / 20) << "the mutations hardly matter"; \
    EXPECT_GT(c.accepted, kIterations / 20) << "nothing valid got through";  \
  }
AMBID_BUS_MESSAGES(AMBID_FUZZ_TEST)
#undef AMBID_FUZZ_TEST

}  // namespace bus_messages_test
}  // namespace ambid::fuzz
