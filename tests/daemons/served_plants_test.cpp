// Which plants a daemon serves ("plants" in its config) and how a plant served twice shows.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "services/daemons/foreign_models.hpp"
#include "services/daemons/served_plants.hpp"

namespace ambid::daemons {
namespace served_plants_test {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

ServedPlants served(const char* json) { return ServedPlants(nlohmann::json::parse(json), "bearing-1", "test config"); }

TEST(ServedPlants, NoListServesThePlantOfTheCommandLine) {
  const ServedPlants s = served("{}");
  EXPECT_TRUE(s.single());
  EXPECT_TRUE(s.serves("bearing-1"));
  EXPECT_FALSE(s.serves("bearing-2"));
}

TEST(ServedPlants, AListServesExactlyItsPlants) {
  const ServedPlants s = served(R"({"plants": ["b", "a"]})");
  EXPECT_FALSE(s.single());
  EXPECT_FALSE(s.all());
  EXPECT_TRUE(s.serves("a"));
  EXPECT_TRUE(s.serves("b"));
  EXPECT_FALSE(s.serves("bearing-1"));  // the command line's plant is not added
  EXPECT_EQ(s.describe(), "plants a, b");
}

TEST(ServedPlants, AllServesAnyPlantId) {
  const ServedPlants s = served(R"({"plants": "all"})");
  EXPECT_TRUE(s.all());
  EXPECT_TRUE(s.serves("anything"));
  EXPECT_TRUE(s.listed().empty());
}

TEST(ServedPlants, RefusesWhatIsNoListOfDistinctIds) {
  EXPECT_THAT([] { served(R"({"plants": []})"); }, ThrowsMessage<Error>(HasSubstr("test config: plants must be")));
  EXPECT_THAT([] { served(R"({"plants": "some"})"); }, ThrowsMessage<Error>(HasSubstr("\"some\"")));
  EXPECT_THAT([] { served(R"({"plants": ["a", 3]})"); }, ThrowsMessage<Error>(HasSubstr("not a plant id")));
  EXPECT_THAT([] { served(R"({"plants": ["a", ""]})"); }, ThrowsMessage<Error>(HasSubstr("not a plant id")));
  EXPECT_THAT([] { served(R"({"plants": ["a", "a"]})"); }, ThrowsMessage<Error>(HasSubstr("'a' listed twice")));
  EXPECT_THAT([] { served(("{\"plants\": [\"" + std::string(65, 'x') + "\"]}").c_str()); },
              ThrowsMessage<Error>(HasSubstr("1 to 64 characters")));
}

bus::IdentifiedModel model(const std::string& plant, std::uint64_t seq, double time) {
  bus::IdentifiedModel m;
  m.plant_id = plant;
  m.seq = seq;
  m.time = time;
  return m;
}

TEST(ForeignModels, OwnModelsComingBackOnceAreNotForeign) {
  ForeignModels f;
  for (std::uint64_t k = 0; k < 5; ++k) f.published(model("a", k, 0.5 + 0.25 * double(k)));
  for (std::uint64_t k = 0; k < 5; ++k) EXPECT_FALSE(f.foreign(model("a", k, 0.5 + 0.25 * double(k))));
}

TEST(ForeignModels, AModelNotWrittenHereOrASecondCopyIsForeign) {
  ForeignModels f;
  f.published(model("a", 0, 0.5));
  EXPECT_TRUE(f.foreign(model("a", 1, 0.75)));  // another numbering
  EXPECT_TRUE(f.foreign(model("a", 0, 0.6)));   // another window
  EXPECT_TRUE(f.foreign(model("b", 0, 0.5)));   // another plant
  EXPECT_FALSE(f.foreign(model("a", 0, 0.5)));
  EXPECT_TRUE(f.foreign(model("a", 0, 0.5)));  // the same windows cut by a twin identifier
}

TEST(ForeignModels, RemembersOnlyTheNewestOwnModels) {
  ForeignModels f(2);
  for (std::uint64_t k = 0; k < 3; ++k) f.published(model("a", k, double(k)));
  EXPECT_TRUE(f.foreign(model("a", 0, 0.0)));  // forgotten: its echo cannot be told from another's
  EXPECT_FALSE(f.foreign(model("a", 2, 2.0)));
}

}  // namespace served_plants_test
}  // namespace ambid::daemons
