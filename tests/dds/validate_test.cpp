// The bound and layout checks every write goes through (no DDS involved), and the argument
// checks of make_bus.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dds/harness.hpp"
#include "services/bus/validate.hpp"

namespace ambid::bus::test {
namespace validate_test {

using testing::HasSubstr;

template <class Message>
std::string refusal(const Message& m) {
  try {
    validate(m);
  } catch (const InvalidMessage& e) {
    return e.what();
  }
  return "accepted";
}

template <class... Messages>
void expect_largest_and_small_valid(std::tuple<Messages...>*) {
  (
      [] {
        EXPECT_NO_THROW(validate(largest<Messages>())) << Topic<Messages>::name;
        EXPECT_NO_THROW(validate(small<Messages>(1))) << Topic<Messages>::name;
      }(),
      ...);
}

TEST(Validate, MessagesAtTheirBoundsPass) { expect_largest_and_small_valid(static_cast<AllMessages*>(nullptr)); }

TEST(Validate, StringOneOverItsBoundIsRefusedWithNameSizeBoundAndValue) {
  Alert a = small<Alert>(1);
  a.message = std::string(limits::text_length + 1, 'x');
  EXPECT_EQ(refusal(a),
            "Alert.message is 257 characters, more than its bound of 256 (\"" + std::string(40, 'x') + "...\")");
  a = small<Alert>(1);
  a.fault = text_of_length(limits::name_length + 1);
  EXPECT_THAT(refusal(a), HasSubstr("Alert.fault is 33 characters"));
  Health h = small<Health>(1);
  h.node = text_of_length(limits::id_length + 1);
  EXPECT_THAT(refusal(h), HasSubstr("Health.node is 65 characters"));
}

TEST(Validate, StringsInsideSequencesAreChecked) {
  PlantSamples p = small<PlantSamples>(1);
  p.y_names[2] = text_of_length(limits::name_length + 1);
  EXPECT_THAT(refusal(p), HasSubstr("PlantSamples.y_names[2] is 33 characters"));
  ExcitationCommand e = small<ExcitationCommand>(1);
  e.settings[1].name = text_of_length(limits::name_length + 1);
  EXPECT_THAT(refusal(e), HasSubstr("ExcitationCommand.settings[1].name is 33 characters"));
  FrequencyResponse f = small<FrequencyResponse>(1);
  f.peaks[0].output = text_of_length(limits::name_length + 1);
  EXPECT_THAT(refusal(f), HasSubstr("FrequencyResponse.peaks[0].output is 33 characters"));
  IdentifiedModel m = small<IdentifiedModel>(1);
  m.physical[0].name = text_of_length(limits::name_length + 1);
  EXPECT_THAT(refusal(m), HasSubstr("IdentifiedModel.physical[0].name is 33 characters"));
}

TEST(Validate, NulCharacterIsRefused) {
  PlantSourceCommand c = small<PlantSourceCommand>(1);
  c.target = std::string("run\0x", 5);
  EXPECT_THAT(refusal(c), HasSubstr("PlantSourceCommand.target holds a NUL character"));
}

TEST(Validate, SequenceOverItsBoundIsRefused) {
  ExcitationCommand e = small<ExcitationCommand>(1);
  e.frequencies.assign(limits::max_frequencies + 1, 1.0);
  EXPECT_EQ(refusal(e), "ExcitationCommand.frequencies has 2049 entries, more than its bound of 2048");
  PlantSamples p = small<PlantSamples>(1);
  p.u_names.assign(limits::max_channels + 1, "u");
  EXPECT_THAT(refusal(p), HasSubstr("PlantSamples.u_names has 17 entries"));
  IdentifiedModel m = small<IdentifiedModel>(1);
  m.continuous.a = {65, 64, std::vector<double>(65 * 64)};
  EXPECT_THAT(refusal(m), HasSubstr("IdentifiedModel.continuous.a.values has 4160 entries, more "
                                    "than its bound of 4096"));
}

TEST(Validate, FlattenedArraysMustMatchTheirDimensions) {
  PlantSamples p = small<PlantSamples>(1);
  p.y.pop_back();
  EXPECT_EQ(refusal(p), "PlantSamples.y has 5 entries, expected count x y_names = 2 x 3 = 6");
  IdentifiedModel m = small<IdentifiedModel>(1);
  m.discrete.b.cols = 3;
  EXPECT_THAT(refusal(m), HasSubstr("IdentifiedModel.discrete.b.values has 2 entries, expected "
                                    "rows x cols = 1 x 3 = 3"));
  FrequencyResponse f = small<FrequencyResponse>(1);
  f.im.push_back(0.0);
  EXPECT_THAT(refusal(f), HasSubstr("FrequencyResponse.im has 3 entries, expected outputs x "
                                    "inputs x frequencies = 1 x 1 x 2 = 2"));
}

TEST(Validate, EnumOutOfRangeIsRefused) {
  Alert a = small<Alert>(1);
  a.level = static_cast<AlertLevel>(4);
  EXPECT_EQ(refusal(a), "Alert.level has the out-of-range value 4");
  PlantSourceState s = small<PlantSourceState>(1);
  s.kind = static_cast<SourceKind>(3);
  EXPECT_THAT(refusal(s), HasSubstr("PlantSourceState.kind has the out-of-range value 3"));
}

TEST(MakeBus, RefusesWhatCannotWork) {
  EXPECT_THROW(make_bus("opendds", 100), Error);
  EXPECT_THROW(make_bus("cyclone", -1), Error);
  EXPECT_THROW(make_bus("fastdds", max_domain + 1), Error);
  EXPECT_THROW(make_bus("cyclone", 100, "/nonexistent/cyclone.xml"), Error);
}

TEST(QosTable, NamesAndSettings) {
  EXPECT_EQ(name(Topic<PlantSamples>::profile), "samples");
  EXPECT_EQ(name(Topic<PlantSourceCommand>::profile), "commands");
  EXPECT_EQ(name(Topic<Alert>::profile), "state");
  EXPECT_EQ(name(Topic<Health>::profile), "health");
  EXPECT_FALSE(qos(Profile::samples).transient_local);
  EXPECT_FALSE(qos(Profile::commands).transient_local);
  EXPECT_TRUE(qos(Profile::state).transient_local);
  EXPECT_TRUE(qos(Profile::health).transient_local);
  EXPECT_GT(qos(Profile::samples).deadline.count(), 0);
  EXPECT_GT(qos(Profile::health).liveliness.count(), 0);
}

}  // namespace validate_test
}  // namespace ambid::bus::test
