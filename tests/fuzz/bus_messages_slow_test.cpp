// The bus messages' fuzz targets (bus_messages_test.cpp) with 40 000 inputs each.
#include <gtest/gtest.h>

#include "fuzz/bus_messages.hpp"

namespace ambid::fuzz {
namespace bus_messages_slow_test {

constexpr int kIterations = 40000;

#define AMBID_FUZZ_TEST(Message, topic_name, qos_profile) \
  TEST(FuzzBusLong, Message) { EXPECT_GT(fuzz_bus_message<bus::Message>(kIterations).refused, 0); }
AMBID_BUS_MESSAGES(AMBID_FUZZ_TEST)
#undef AMBID_FUZZ_TEST

}  // namespace bus_messages_slow_test
}  // namespace ambid::fuzz
