// Many bearings, one service (issue 14): eight simulated bearings on one domain, each its own
// plant daemon; two identifier processes dividing the fleet by their "plants" lists (four each,
// one on Cyclone DDS, one on Fast DDS, each reading the other's models: deploy/dds/
// cyclone-loopback.xml says what that needed) and one diagnostics daemon serving "all". Every bearing is identified (R1
// near its truth in the trend store, which names the plant of each estimate); a coil fault on one bearing alerts that
// bearing only. Domain 222; 30-90 s (slow). A plant id served twice: fleet_stack_test.cpp.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>

#include "diagnostics/trend_store.hpp"
#include "fleet_support.hpp"

namespace ambid::testing {
namespace fleet_stack_slow_test {

using ::testing::HasSubstr;
using ::testing::Not;

constexpr int kBearings = 8;

TEST(FleetStack, EightBearingsTwoIdentifiersOneDiagnosticsFaultAlertsOnlyItsBearing) {
  constexpr int domain = 222;
  Stack stack("fleet", domain);
  // The stack harness's learning (40 windows, 14 records of 1 s at real time) and persistence:
  // a baseline of fewer windows misjudges the spread of nearly noise-free estimates.
  std::ofstream(stack.dir() / "diagnostics.json")
      << R"({"plants": "all", "store": ")" << stack.store().string()
      << R"(", "learning_windows": 40, "persist_windows": 20, "stale_timeout": 2.0, "silence": 6.0})";
  stack.start("diagnostics");
  start_identifier(stack, "identifier-a", plant_list(1, 4), domain, "cyclone");
  start_identifier(stack, "identifier-b", plant_list(5, 8), domain, "fastdds");
  for (int k = 1; k <= kBearings; ++k) start_plant(stack, k, domain);

  // Every bearing identified: its baseline learned (at most 90 s), the mean of its stored R1
  // the truth 17.5 ohm within 2.5 % (one window scatters ~3 %).
  auto learned = [&] {
    const diag::TrendStore store(stack.store(), diag::OpenMode::read_only);
    for (int k = 1; k <= kBearings; ++k)
      if (!store.baseline(bearing(k), "R1")) return false;
    return true;
  };
  for (int s = 0; s < 90 && !(std::filesystem::exists(stack.store()) && learned()); ++s)
    std::this_thread::sleep_for(std::chrono::seconds(1));
  {
    const diag::TrendStore store(stack.store(), diag::OpenMode::read_only);
    for (int k = 1; k <= kBearings; ++k) {
      ASSERT_TRUE(store.baseline(bearing(k), "R1")) << bearing(k) << "\n" << stack.log("diagnostics");
      const auto history = store.history(bearing(k), "R1");
      ASSERT_GE(history.size(), 40u) << bearing(k);
      double sum = 0.0;
      for (const auto& e : history) sum += e.value;
      EXPECT_NEAR(sum / double(history.size()), 17.5, 0.025 * 17.5) << bearing(k);
    }
  }
  // Each identifier served its own four and nothing else.
  for (const auto& [name, served, other] : {std::tuple{"identifier-a", 1, 5}, std::tuple{"identifier-b", 5, 1}}) {
    const std::string log = stack.log(name);
    for (int k = served; k < served + 4; ++k) EXPECT_THAT(log, HasSubstr("serving plant " + bearing(k) + "\n"));
    for (int k = other; k < other + 4; ++k) EXPECT_THAT(log, Not(HasSubstr(bearing(k)))) << log;
    EXPECT_THAT(log, Not(HasSubstr("served twice"))) << log;
  }

  // bearing-6 (served by identifier-b) gets a coil 1 at +20 %.
  const std::string hot = fleet_scenario(stack, 6, R"( "true_parameters": {"R1": 21.0},)");
  const CommandResult swap = stack.ambid("source set sim " + hot + " --plant-id " + bearing(6));
  ASSERT_EQ(swap.status, 0) << swap.output;
  const CommandResult error = stack.ambid("alerts --until ERROR:R1 --timeout 60 --plant-id " + bearing(6));
  ASSERT_EQ(error.status, 0) << error.output << stack.log("diagnostics");
  EXPECT_THAT(error.output, HasSubstr("ERROR  bearing-6  R1  coil_resistance (channel 1)"));
  std::this_thread::sleep_for(std::chrono::seconds(2));
  // Every fault alert (WARN, ERROR) of the fleet is about bearing-6. STALE and history_gap
  // elsewhere are no fault: on this shared machine at load ~20 an identifier can fall behind by
  // more than the 2 s stale timeout (it did, for three bearings of both identifiers in one run)
  // and miss samples, which it then reports (WARN samples history_gap, 0.55 s on the four
  // bearings of one identifier in one run).
  const CommandResult all = stack.ambid("alerts --all-plants --wait 2");
  std::istringstream lines(all.output);
  int raised = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.find("  WARN  ") == std::string::npos && line.find("  ERROR  ") == std::string::npos) continue;
    if (line.find("  history_gap  ") != std::string::npos) continue;
    ++raised;
    EXPECT_THAT(line, HasSubstr("  bearing-6  ")) << all.output;
  }
  EXPECT_GE(raised, 1) << all.output;
}

}  // namespace fleet_stack_slow_test
}  // namespace ambid::testing
