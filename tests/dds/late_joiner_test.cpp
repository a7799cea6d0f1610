// Transient-local topics give a late joiner the writer's history (depth per instance, also with
// a Cyclone writer: pitfall P5); volatile topics give it nothing. Domains 120..127.
#include <thread>

#include <gtest/gtest.h>

#include "dds/harness.hpp"

namespace ambid::bus::test {
namespace late_joiner_test {

// small(1..n) on one instance and largest() on another; what a late joiner must get is the last
// `depth` small ones and largest().
template <class Message>
struct History {
  std::vector<Message> written;
  std::vector<Message> kept;

  explicit History(int n) {
    const int depth = qos(Topic<Message>::profile).depth;
    for (int k = 1; k <= n; ++k) {
      written.push_back(small<Message>(k));
      if (k > n - depth) kept.push_back(written.back());
    }
    written.push_back(largest<Message>());
    kept.push_back(largest<Message>());
  }
};

template <class Message>
void expect_late_joiner_gets_history(Bus& from, const std::string& reader_vendor, int domain) {
  SCOPED_TRACE(Topic<Message>::name);
  const History<Message> history(qos(Topic<Message>::profile).depth + 2);
  const auto writer = from.writer<Message>();
  for (const auto& m : history.written) writer->write(m);
  const auto late = make_bus(reader_vendor, domain);  // joins after everything was written
  const auto reader = late->reader<Message>();
  const auto got = collect(*reader, history.kept.size());
  EXPECT_TRUE(same_messages(got, history.kept))
      << "the late joiner got " << got.size() << " of " << history.kept.size() << " messages";
}

class LateJoiner : public testing::TestWithParam<VendorPair> {};

TEST_P(LateJoiner, GetsTheHistoryOfEveryStateTopic) {
  const int domain = 120 + pair_index(GetParam());
  const auto from = make_bus(GetParam().writer, domain);
  expect_late_joiner_gets_history<PlantSourceState>(*from, GetParam().reader, domain);
  expect_late_joiner_gets_history<IdentifiedModel>(*from, GetParam().reader, domain);
  expect_late_joiner_gets_history<FrequencyResponse>(*from, GetParam().reader, domain);
  expect_late_joiner_gets_history<Alert>(*from, GetParam().reader, domain);
  expect_late_joiner_gets_history<Health>(*from, GetParam().reader, domain);
}

TEST_P(LateJoiner, GetsNoOldCommands) {
  const int domain = 124 + pair_index(GetParam());
  const auto from = make_bus(GetParam().writer, domain);
  const auto writer = from->writer<ExcitationCommand>();
  writer->write(small<ExcitationCommand>(1));
  const auto late = make_bus(GetParam().reader, domain);
  const auto reader = late->reader<ExcitationCommand>();
  ASSERT_TRUE(eventually([&] { return matched(*writer, *reader); }));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_TRUE(reader->take().empty());
  writer->write(small<ExcitationCommand>(2));
  EXPECT_TRUE(same_messages(collect(*reader, 1), {small<ExcitationCommand>(2)}));
}

INSTANTIATE_TEST_SUITE_P(Dds, LateJoiner, testing::ValuesIn(vendor_pairs), pair_name);

}  // namespace late_joiner_test
}  // namespace ambid::bus::test
