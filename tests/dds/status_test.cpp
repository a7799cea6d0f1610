// Status events, the same from both vendors: matched / unmatched, deadline missed on both ends
// (the samples profile has a 1 s deadline), and Bus::wait waking on data. Domains 140..151.
#include <gtest/gtest.h>

#include "dds/harness.hpp"

namespace ambid::bus::test {
namespace status_test {

class Status : public testing::TestWithParam<VendorPair> {};

TEST_P(Status, MatchedThenUnmatched) {
  const int domain = 140 + pair_index(GetParam());
  const auto from = make_bus(GetParam().writer, domain);
  const auto to = make_bus(GetParam().reader, domain);
  const auto writer = from->writer<Alert>();
  EventLog writer_log(*writer);
  auto reader = to->reader<Alert>();
  EventLog reader_log(*reader);
  EXPECT_TRUE(eventually([&] { return writer_log.saw(StatusKind::matched); }));
  EXPECT_TRUE(eventually([&] { return reader_log.saw(StatusKind::matched); }));
  EXPECT_EQ(writer->matched(), 1);
  reader.reset();
  EXPECT_TRUE(eventually([&] { return writer_log.saw(StatusKind::unmatched); }));
  EXPECT_EQ(writer->matched(), 0);
  EXPECT_EQ(writer_log.seen().back(), (StatusEvent{StatusKind::unmatched, 0}));
}

TEST_P(Status, DeadlineMissedOnBothEnds) {
  const int domain = 144 + pair_index(GetParam());
  const auto from = make_bus(GetParam().writer, domain);
  const auto to = make_bus(GetParam().reader, domain);
  const auto reader = to->reader<PlantSamples>();
  const auto writer = from->writer<PlantSamples>();
  ASSERT_TRUE(eventually([&] { return matched(*writer, *reader); }));
  EventLog writer_log(*writer);
  EventLog reader_log(*reader);
  writer->write(small<PlantSamples>(1));
  ASSERT_EQ(collect(*reader, 1).size(), 1u);
  // Then silence: the 1 s deadline passes.
  EXPECT_TRUE(eventually([&] { return reader_log.saw(StatusKind::deadline_missed); }));
  EXPECT_TRUE(eventually([&] { return writer_log.saw(StatusKind::deadline_missed); }));
}

TEST_P(Status, WaitWakesOnDataAndTimesOutWithout) {
  const int domain = 148 + pair_index(GetParam());
  const auto from = make_bus(GetParam().writer, domain);
  const auto to = make_bus(GetParam().reader, domain);
  const auto reader = to->reader<Health>();
  const auto writer = from->writer<Health>();
  ASSERT_TRUE(eventually([&] { return matched(*writer, *reader); }));
  while (to->wait(std::chrono::milliseconds(200))) reader->events();  // quiet now
  writer->write(small<Health>(1));
  EXPECT_TRUE(to->wait(patience));
  EXPECT_TRUE(same_messages(collect(*reader, 1), {small<Health>(1)}));
}

INSTANTIATE_TEST_SUITE_P(Dds, Status, testing::ValuesIn(vendor_pairs), pair_name);

}  // namespace status_test
}  // namespace ambid::bus::test
