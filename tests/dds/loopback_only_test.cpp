// Nothing leaves loopback: while both vendors discover each other and exchange every topic, a
// packet socket watches every interface of this host (dds/packet_capture.hpp). No UDP packet
// from or to the test domain's ports may appear on any interface but lo, none is multicast, and
// lo must carry the exchange (proof that the capture works). Needs CAP_NET_RAW; skipped without.
// Domains 160..161.
#include <chrono>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "dds/harness.hpp"
#include "dds/packet_capture.hpp"

namespace ambid::bus::test {
namespace loopback_only_test {

void exchange_both_ways(Bus& fast, Bus& cyclone) {
  for (auto [from, to] : {std::pair{&fast, &cyclone}, std::pair{&cyclone, &fast}}) {
    AllReaders readers(*to);
    AllWriters writers(*from);
    ASSERT_TRUE(eventually([&] { return writers.all_matched() && readers.all_matched(); }));
    write_all(writers);
    expect_all(readers);
  }
}

void expect_nothing_left_loopback(int domain, const std::string& fast_profile, const std::string& cyclone_profile) {
  ambid::test::PacketCapture capture(domain);
  if (!capture.available()) GTEST_SKIP() << "no packet socket (needs CAP_NET_RAW)";
  {
    const auto fast = make_bus("fastdds", domain, fast_profile);
    const auto cyclone = make_bus("cyclone", domain, cyclone_profile);
    exchange_both_ways(*fast, *cyclone);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // goodbyes
  capture.stop();
  EXPECT_GT(capture.on_loopback(), 0) << "the capture saw nothing at all";
  EXPECT_EQ(capture.dropped(), 0u) << "the capture dropped packets: the result is incomplete";
  EXPECT_EQ(capture.multicast(), 0);
  EXPECT_TRUE(capture.elsewhere().empty())
      << capture.elsewhere().size() << " packets left loopback, first: " << capture.elsewhere().front();
}

TEST(LoopbackOnly, BuiltInProfilesSendNothingElsewhere) {
  expect_nothing_left_loopback(160, std::string(loopback_profile), std::string(loopback_profile));
}

TEST(LoopbackOnly, ProfileFilesSendNothingElsewhere) {
  const std::string dir = AMBID_SOURCE_DIR "/deploy/dds/";
  expect_nothing_left_loopback(161, dir + "fastdds-loopback.xml", dir + "cyclone-loopback.xml");
}

}  // namespace loopback_only_test
}  // namespace ambid::bus::test
