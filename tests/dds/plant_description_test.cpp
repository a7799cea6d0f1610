// The PlantDescription topic between the vendors: a description written before the reader
// exists reaches a late joiner of the other vendor (transient-local), only the latest per plant
// (keep-last 1 per instance); an oversized one is refused before write. Domains 134..137.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "dds/harness.hpp"

namespace ambid::bus::test {
namespace plant_description_test {

class DescriptionTopic : public testing::TestWithParam<VendorPair> {};

TEST_P(DescriptionTopic, LateJoinerGetsTheLatestDescriptionOfEveryPlant) {
  const int domain = 134 + (std::string(GetParam().writer) == "fastdds" ? 0 : 1);
  const auto from = make_bus(GetParam().writer, domain);
  const auto writer = from->writer<PlantDescription>();
  PlantDescription other = small<PlantDescription>(3);
  other.plant_id = "bearing-B";
  writer->write(small<PlantDescription>(1));
  writer->write(largest<PlantDescription>());
  writer->write(small<PlantDescription>(2));  // replaces 1 for bearing-A
  writer->write(other);
  const auto to = make_bus(GetParam().reader, domain);
  const auto reader = to->reader<PlantDescription>();
  std::vector<PlantDescription> got = collect(*reader, 4, std::chrono::milliseconds(3000));
  std::sort(got.begin(), got.end(), [](const auto& a, const auto& b) { return a.plant_id < b.plant_id; });
  std::vector<PlantDescription> want{largest<PlantDescription>(), small<PlantDescription>(2), other};
  std::sort(want.begin(), want.end(), [](const auto& a, const auto& b) { return a.plant_id < b.plant_id; });
  EXPECT_TRUE(same_messages(got, want)) << got.size() << " descriptions arrived";
}

TEST_P(DescriptionTopic, OversizedDescriptionIsRefusedBeforeWrite) {
  const int domain = 136 + (std::string(GetParam().writer) == "fastdds" ? 0 : 1);
  const auto from = make_bus(GetParam().writer, domain);
  const auto to = make_bus(GetParam().reader, domain);
  const auto reader = to->reader<PlantDescription>();
  const auto writer = from->writer<PlantDescription>();
  ASSERT_TRUE(eventually([&] { return matched(*writer, *reader); }));
  PlantDescription d = small<PlantDescription>(1);
  d.controller.inputs.push_back(text_of_length(limits::name_length + 1));
  EXPECT_THAT([&] { writer->write(d); },
              testing::ThrowsMessage<InvalidMessage>(
                  testing::StartsWith("PlantDescription.controller.inputs[1] is 33 characters, more than its bound")));
  d = small<PlantDescription>(1);
  d.controller.matrices.a = {65, 64, std::vector<double>(65 * 64)};
  EXPECT_THAT([&] { writer->write(d); },
              testing::ThrowsMessage<InvalidMessage>(testing::HasSubstr(
                  "PlantDescription.controller.matrices.a.values has 4160 entries, more than its bound of 4096")));
  d = small<PlantDescription>(1);
  d.controller.output_limits.rows = 2;  // one pair of values for two rows
  EXPECT_THAT([&] { writer->write(d); },
              testing::ThrowsMessage<InvalidMessage>(
                  testing::HasSubstr("PlantDescription.controller.output_limits.values has 2 entries, expected")));
  writer->write(small<PlantDescription>(1));
  EXPECT_TRUE(same_messages(collect(*reader, 2, std::chrono::milliseconds(1500)), {small<PlantDescription>(1)}));
}

INSTANTIATE_TEST_SUITE_P(Dds, DescriptionTopic,
                         testing::Values(VendorPair{"fastdds", "cyclone"}, VendorPair{"cyclone", "fastdds"}),
                         pair_name);

}  // namespace plant_description_test
}  // namespace ambid::bus::test
