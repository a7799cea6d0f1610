// Every topic, both vendors, one process: the largest allowed message and two small ones arrive
// intact for every writer/reader vendor pair, with the built-in loopback profile and with the
// deploy/dds profile files. Domains 100..105.
#include <gtest/gtest.h>

#include "dds/harness.hpp"

namespace ambid::bus::test {
namespace roundtrip_test {

void expect_round_trip(Bus& from, Bus& to) {
  AllReaders readers(to);
  AllWriters writers(from);
  ASSERT_TRUE(eventually([&] { return writers.all_matched() && readers.all_matched(); }))
      << "writers and readers did not match";
  write_all(writers);
  expect_all(readers);
}

class RoundTrip : public testing::TestWithParam<VendorPair> {};

TEST_P(RoundTrip, EveryTopicArrivesIntact) {
  const int domain = 100 + pair_index(GetParam());
  const auto from = make_bus(GetParam().writer, domain);
  const auto to = make_bus(GetParam().reader, domain);
  expect_round_trip(*from, *to);
}

INSTANTIATE_TEST_SUITE_P(Dds, RoundTrip, testing::ValuesIn(vendor_pairs), pair_name);

TEST(RoundTripProfileFiles, LoopbackFilesInteroperateBothWays) {
  const std::string dir = AMBID_SOURCE_DIR "/deploy/dds/";
  const auto fast = make_bus("fastdds", 104, dir + "fastdds-loopback.xml");
  const auto cyclone = make_bus("cyclone", 104, dir + "cyclone-loopback.xml");
  {
    SCOPED_TRACE("fastdds to cyclone");
    expect_round_trip(*fast, *cyclone);
  }
  {
    SCOPED_TRACE("cyclone to fastdds");
    expect_round_trip(*cyclone, *fast);
  }
}

TEST(RoundTripProfileFiles, FileProfileMeetsBuiltInProfile) {
  const auto file = make_bus("fastdds", 105, AMBID_SOURCE_DIR "/deploy/dds/fastdds-loopback.xml");
  const auto builtin = make_bus("cyclone", 105);
  expect_round_trip(*file, *builtin);
}

}  // namespace roundtrip_test
}  // namespace ambid::bus::test
