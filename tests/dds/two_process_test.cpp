// Every topic between two processes, for every writer/reader vendor pair: this process writes,
// a peer process (this program again) reads and checks. Domains 110..113.
#include <sstream>

#include <gtest/gtest.h>

#include "dds/harness.hpp"
#include "dds/peer.hpp"

namespace ambid::bus::test {
namespace two_process_test {

// The peer: "VENDOR DOMAIN" -> read every topic, expect round_trip_messages() of each.
TEST(TwoProcessPeer, ReadsEveryTopic) {
  const auto spec = peer_spec();
  if (!spec) GTEST_SKIP() << "runs only as the peer process of TwoProcess tests";
  std::istringstream in(*spec);
  std::string vendor;
  int domain = -1;
  in >> vendor >> domain;
  const auto bus = make_bus(vendor, domain);
  AllReaders readers(*bus);
  ASSERT_TRUE(eventually([&] { return readers.all_matched(); })) << "readers did not match";
  signal_ready();
  expect_all(readers);
}

class TwoProcess : public testing::TestWithParam<VendorPair> {};

TEST_P(TwoProcess, EveryTopicArrivesIntact) {
  const int domain = 110 + pair_index(GetParam());
  PeerProcess peer("TwoProcessPeer.ReadsEveryTopic", std::string(GetParam().reader) + " " + std::to_string(domain));
  const auto bus = make_bus(GetParam().writer, domain);
  AllWriters writers(*bus);
  ASSERT_TRUE(eventually([&] { return writers.all_matched(); })) << "writers did not match";
  // Both sides matched before anything is written (pitfall P4: volatile topics).
  ASSERT_TRUE(peer.wait_ready(patience)) << "peer never got ready";
  write_all(writers);
  EXPECT_EQ(peer.wait_exit(patience), 0) << "the peer did not receive everything intact";
}

INSTANTIATE_TEST_SUITE_P(Dds, TwoProcess, testing::ValuesIn(vendor_pairs), pair_name);

}  // namespace two_process_test
}  // namespace ambid::bus::test
