// A message that breaks a bound is refused by write() before anything reaches the wire, with
// either vendor writing; nothing truncated arrives, and the writer stays usable. Domains 130..133.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dds/harness.hpp"

namespace ambid::bus::test {
namespace bounds_test {

class Bounds : public testing::TestWithParam<VendorPair> {};

TEST_P(Bounds, OversizedStringIsRefusedBeforeWrite) {
  const int domain = 130 + (std::string(GetParam().writer) == "fastdds" ? 0 : 1);
  const auto from = make_bus(GetParam().writer, domain);
  const auto to = make_bus(GetParam().reader, domain);
  const auto reader = to->reader<Alert>();
  const auto writer = from->writer<Alert>();
  ASSERT_TRUE(eventually([&] { return matched(*writer, *reader); }));

  Alert oversized = small<Alert>(1);
  oversized.plant_id = text_of_length(limits::id_length + 1);
  try {
    writer->write(oversized);
    FAIL() << "an oversized plant_id was written";
  } catch (const InvalidMessage& e) {
    EXPECT_THAT(e.what(), testing::StartsWith("Alert.plant_id is 65 characters, more than its bound of 64"));
  }
  writer->write(small<Alert>(2));
  EXPECT_TRUE(same_messages(collect(*reader, 2, std::chrono::milliseconds(1500)), {small<Alert>(2)}));
}

TEST_P(Bounds, OversizedSequenceIsRefusedBeforeWrite) {
  const int domain = 132 + (std::string(GetParam().writer) == "fastdds" ? 0 : 1);
  const auto from = make_bus(GetParam().writer, domain);
  const auto to = make_bus(GetParam().reader, domain);
  const auto reader = to->reader<PlantSamples>();
  const auto writer = from->writer<PlantSamples>();
  ASSERT_TRUE(eventually([&] { return matched(*writer, *reader); }));

  PlantSamples oversized = largest<PlantSamples>();
  oversized.count += 1;
  oversized.y.resize(oversized.y.size() + limits::max_channels, 0.0);
  EXPECT_THROW(writer->write(oversized), InvalidMessage);
  writer->write(small<PlantSamples>(1));
  EXPECT_TRUE(same_messages(collect(*reader, 2, std::chrono::milliseconds(1500)), {small<PlantSamples>(1)}));
}

INSTANTIATE_TEST_SUITE_P(Dds, Bounds,
                         testing::Values(VendorPair{"fastdds", "cyclone"}, VendorPair{"cyclone", "fastdds"}),
                         pair_name);

}  // namespace bounds_test
}  // namespace ambid::bus::test
