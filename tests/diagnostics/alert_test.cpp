#include "diagnostics/alert.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace ambid::diag {
namespace alert_test {

Alert example() {
  Alert a;
  a.time = 12.5;
  a.plant_id = "bearing-A";
  a.level = Level::warn;
  a.fault = "coil_resistance";
  a.channel = 1;
  a.parameter = "R1";
  a.value = 21.0;
  a.baseline = 17.5;
  a.message = "coil 1 resistance 20 % above baseline";
  return a;
}

std::string error_of(const nlohmann::json& j) {
  try {
    alert_from_json(j);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Alert, JsonAsTheContractShowsIt) {
  // experiment-format.md "Diagnosis", verbatim.
  const nlohmann::json contract = nlohmann::json::parse(R"({ "time": 12.5, "plant_id": "bearing-A", "level": "WARN",
      "fault": "coil_resistance", "channel": 1, "parameter": "R1", "value": 21.0,
      "baseline": 17.5, "message": "coil 1 resistance 20 % above baseline" })");
  EXPECT_EQ(to_json(example()), contract);
  EXPECT_EQ(alert_from_json(contract), example());
}

TEST(Alert, NullChannelAndBaseline) {
  Alert a = example();
  a.level = Level::stale;
  a.fault = "sensor_gain";
  a.channel.reset();
  a.baseline.reset();
  const nlohmann::json j = to_json(a);
  EXPECT_TRUE(j.at("channel").is_null());
  EXPECT_TRUE(j.at("baseline").is_null());
  EXPECT_EQ(j.at("level"), "STALE");
  EXPECT_EQ(alert_from_json(j), a);
}

TEST(Alert, Levels) {
  EXPECT_EQ(static_cast<int>(Level::ok), 0);  // ROS diagnostic_msgs values
  EXPECT_EQ(static_cast<int>(Level::stale), 3);
  for (Level l : {Level::ok, Level::warn, Level::error, Level::stale}) EXPECT_EQ(parse_level(to_string(l)), l);
  EXPECT_THROW(parse_level("warn"), Error);
}

TEST(Alert, RefusesWhatTheContractDoesNot) {
  nlohmann::json j = to_json(example());
  j.erase("baseline");
  EXPECT_EQ(error_of(j), "alert: missing key 'baseline'");
  j = to_json(example());
  j["fault"] = "bad_bearing";
  EXPECT_EQ(error_of(j), "alert: unknown fault 'bad_bearing'");
  j = to_json(example());
  j["channel"] = 0;
  EXPECT_EQ(error_of(j), "alert: 'channel' must be null or a positive integer, got 0");
  j = to_json(example());
  j["level"] = "FATAL";
  EXPECT_NE(error_of(j).find("unknown alert level 'FATAL'"), std::string::npos);
  j = to_json(example());
  j["value"] = "21";
  EXPECT_EQ(error_of(j), "alert: 'value' must be a number, got \"21\"");
  j = to_json(example());
  j["extra"] = "kept out";
  EXPECT_EQ(alert_from_json(j), example());  // unknown keys are ignored
}

}  // namespace alert_test
}  // namespace ambid::diag
