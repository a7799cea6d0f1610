// No traffic of the whole service leaves loopback: plant, identifier and diagnostics daemons
// as processes on their default (loopback) profile, one of each vendor pair across the hops,
// plus operator commands (`status`, `source set`), while a packet socket watches every
// interface of this host (dds/packet_capture.hpp). Every UDP packet of the domain's ports must
// be on lo (and lo must carry the run: proof that the capture works), none multicast.
// Needs CAP_NET_RAW; skipped without. Domain 190.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "dds/packet_capture.hpp"
#include "stack_support.hpp"

namespace ambid::testing {
namespace stack_loopback_test {

using ::testing::HasSubstr;

TEST(StackLoopback, WholeStackAndOperatorCommandsSendNothingOffLoopback) {
  constexpr int domain = 190;
  ambid::test::PacketCapture capture(domain);
  if (!capture.available()) GTEST_SKIP() << "no packet socket (needs CAP_NET_RAW)";
  {
    Stack stack("stack_loopback", domain,
                {{"plant", "fastdds"}, {"identifier", "cyclone"}, {"diagnostics", "fastdds"}});
    // At real time: the capture must see every packet of the sample stream (checked below).
    std::ofstream(stack.dir() / "plant.json")
        << R"({"source": "sim", "target": ")" << AMBID_SOURCE_DIR
        << R"(/tests/integration/scenarios/quiet-bearing.json", "batch_samples": 500, "speed": 1})";
    for (const char* d : {"diagnostics", "identifier", "plant"}) stack.start(d);
    std::this_thread::sleep_for(std::chrono::seconds(3));
    const CommandResult status = stack.ambid("status --wait 2");
    EXPECT_THAT(status.output, HasSubstr("identifier")) << status.output;
    EXPECT_THAT(status.output, HasSubstr("diagnostics")) << status.output;
    const CommandResult swap = stack.ambid("source set sim " + std::string(AMBID_SOURCE_DIR) +
                                           "/tests/integration/scenarios/quiet-coil1-hot.json");
    EXPECT_EQ(swap.status, 0) << swap.output;
  }  // every daemon stopped (SIGTERM): their goodbyes are captured too
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  capture.stop();
  EXPECT_GT(capture.on_loopback(), 100) << "the capture saw (almost) nothing of the run";
  EXPECT_EQ(capture.dropped(), 0u) << "the capture dropped packets: the result is incomplete";
  EXPECT_EQ(capture.multicast(), 0);
  EXPECT_TRUE(capture.elsewhere().empty())
      << capture.elsewhere().size() << " packets left loopback, first: " << capture.elsewhere().front();
}

}  // namespace stack_loopback_test
}  // namespace ambid::testing
