// A writer process that dies without a word (SIGKILL) is reported as liveliness_lost by the
// readers of the other process within about its lease (samples 2 s, health 3 s), for every
// vendor pair: how a silent daemon becomes a STALE alert. Domains 152..155.
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "dds/harness.hpp"
#include "dds/peer.hpp"

namespace ambid::bus::test {
namespace liveliness_test {

// The peer: "VENDOR DOMAIN" -> write PlantSamples and Health every 200 ms, as a daemon would,
// until killed. (Writing once right after the writers matched could race the readers' side of
// the match: pitfall P4.)
TEST(LivelinessPeer, WritesUntilKilled) {
  const auto spec = peer_spec();
  if (!spec) GTEST_SKIP() << "runs only as the peer process of Liveliness tests";
  std::istringstream in(*spec);
  std::string vendor;
  int domain = -1;
  in >> vendor >> domain;
  const auto bus = make_bus(vendor, domain);
  const auto samples = bus->writer<PlantSamples>();
  const auto health = bus->writer<Health>();
  ASSERT_TRUE(eventually([&] { return samples->matched() > 0 && health->matched() > 0; }));
  for (int k = 1; k * std::chrono::milliseconds(200) < patience; ++k) {
    samples->write(small<PlantSamples>(k));
    health->write(small<Health>(k));
    if (k == 1) signal_ready();
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  FAIL() << "was not killed";
}

class Liveliness : public testing::TestWithParam<VendorPair> {};

TEST_P(Liveliness, KilledWriterIsReportedLost) {
  const int domain = 152 + pair_index(GetParam());
  const auto bus = make_bus(GetParam().reader, domain);
  const auto samples = bus->reader<PlantSamples>();
  const auto health = bus->reader<Health>();
  EventLog samples_log(*samples);
  EventLog health_log(*health);
  PeerProcess peer("LivelinessPeer.WritesUntilKilled", std::string(GetParam().writer) + " " + std::to_string(domain));
  ASSERT_TRUE(peer.wait_ready(patience)) << "peer never got ready";
  ASSERT_EQ(collect(*samples, 1).size(), 1u);
  ASSERT_EQ(collect(*health, 1).size(), 1u);
  ASSERT_TRUE(eventually([&] { return samples_log.saw(StatusKind::alive); }));
  ASSERT_TRUE(eventually([&] { return health_log.saw(StatusKind::alive); }));
  EXPECT_FALSE(samples_log.saw(StatusKind::liveliness_lost)) << "lost while the writer lived";

  peer.kill();
  const auto killed = std::chrono::steady_clock::now();
  const auto limit = qos(Profile::health).liveliness + std::chrono::seconds(3);
  EXPECT_TRUE(eventually([&] { return samples_log.saw(StatusKind::liveliness_lost); }, limit));
  EXPECT_TRUE(eventually([&] { return health_log.saw(StatusKind::liveliness_lost); }, limit));
  RecordProperty(
      "lost_after_ms",
      static_cast<int>(
          std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - killed).count()));
}

INSTANTIATE_TEST_SUITE_P(Dds, Liveliness, testing::ValuesIn(vendor_pairs), pair_name);

}  // namespace liveliness_test
}  // namespace ambid::bus::test
