// The stack at a real bearing's sensor noise, configured as deploy/config runs it: the bearing
// of tests/integration/scenarios/noisy-bearing.json (0.1 um on x, 1 mA on each current, 1 V
// PRBS, 10 s records), rpem published every 0.5 s (each record's first 0.25 s dropped), the deploy
// diagnostics settings. The source is swapped to the same bearing with R1 +10 %
// (noisy-coil1-hot10.json), or with kw2 +10 % (noisy-amp2-strong10.json): the ERROR naming that
// element must come within 10 s of plant time after the swap, and no alert but OK before it. Slow label: it needs the
// identifier to keep up with real time at half speed, which pem (~0.6 s of CPU per 0.5 s window) did not on a two-core
// machine shared with eight builds (22 windows in 150 s; STALE alerts).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "diagnostics/trend_store.hpp"
#include "stack_support.hpp"

namespace ambid::testing {
namespace stack_noise_slow_test {

using ::testing::HasSubstr;

const std::string scenarios = std::string(AMBID_SOURCE_DIR) + "/tests/integration/scenarios/";

// The number after `key` in `text` from `from` on (NaN when absent).
double number_after(const std::string& text, const std::string& key, std::size_t from = 0) {
  const auto at = text.find(key, from);
  return at == std::string::npos ? std::nan("") : std::stod(text.substr(at + key.size()));
}

// The plant at `speed` times real time (0.5: room for a loaded machine; pem, deployed before,
// took ~0.6 s of CPU per 0.5 s window), the identifier and diagnostics daemons as deploy/config.
void configure_noisy_stack(const Stack& stack, double speed) {
  std::ofstream(stack.dir() / "plant.json")
      << R"({"source": "sim", "target": ")" << scenarios << R"(noisy-bearing.json", "batch_samples": 500, "speed": )"
      << speed << "}";
  const std::filesystem::path deploy = std::filesystem::path(AMBID_SOURCE_DIR) / "deploy" / "config";
  std::ofstream(stack.dir() / "identifier.json") << std::ifstream(deploy / "identifier.json").rdbuf();
  std::ifstream diagnostics(deploy / "diagnostics.json");
  std::stringstream text;
  text << diagnostics.rdbuf();
  std::string config = text.str();
  const std::string store_key = R"("runs/stack/trend.sqlite")";
  config.replace(config.find(store_key), store_key.size(), "\"" + stack.store().string() + "\"");
  std::ofstream(stack.dir() / "diagnostics.json") << config;
}

// The stack on the nominal bearing for the baseline (20 windows of 0.5 s) and 20 windows after
// it, then swapped to `scenario`: the ERROR on `parameter` naming `cause` within 10 s of plant
// time after the swap, and no alert but OK before it, every one after it naming `cause`.
void fault_is_an_error_within_ten_seconds(const std::string& name, int domain, const std::string& scenario,
                                          const std::string& parameter, const std::string& cause) {
  Stack stack(name, domain);
  configure_noisy_stack(stack, 0.5);
  for (const char* d : {"diagnostics", "identifier", "plant"}) stack.start(d);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(150);
  std::size_t stored = 0;
  while (stored < 40 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::seconds(1));
    if (std::filesystem::exists(stack.store()))
      stored = diag::TrendStore(stack.store(), diag::OpenMode::read_only).history("bearing-1", "R1").size();
  }
  ASSERT_GE(stored, 40u) << stack.log("identifier") << stack.log("diagnostics");
  const CommandResult swap = stack.ambid("source set sim " + scenarios + scenario);
  ASSERT_EQ(swap.status, 0) << swap.output;
  const double change = number_after(swap.output, "plant time ");
  ASSERT_TRUE(std::isfinite(change)) << swap.output;
  const CommandResult error = stack.ambid("alerts --until ERROR:" + parameter + " --timeout 60");
  ASSERT_EQ(error.status, 0) << error.output << stack.log("diagnostics");
  const auto line = error.output.find("ERROR  bearing-1  " + parameter + "  " + cause);
  ASSERT_NE(line, std::string::npos) << error.output;
  const double detected = number_after(error.output, "t=", error.output.rfind('\n', line) + 1);
  ::testing::Test::RecordProperty("detection_delay_plant_s", std::to_string(detected - change));
  EXPECT_GT(detected, change) << error.output;
  EXPECT_LE(detected - change, 10.0) << "swap at plant time " << change << " s\n" << error.output;
  const CommandResult all = stack.ambid("alerts --wait 1");
  std::istringstream lines(all.output);
  for (std::string l; std::getline(lines, l);) {
    if (l.rfind("t=", 0) != 0 || l.find("  OK   ") != std::string::npos) continue;
    EXPECT_GT(number_after(l, "t="), change) << l;
    EXPECT_THAT(l, HasSubstr(cause));
  }
}

// R1 +10 % (noisy-coil1-hot10.json). Measured with the daemon's 3-window confirmation: the
// ERROR 3.25 s of plant time after the swap (3 runs, 2026-12-03; 2.2 s before it).
TEST(StackAtSensorNoise, ATenPercentCoilFaultIsAnErrorWithinTenSecondsOfPlantTime) {
  fault_is_an_error_within_ten_seconds("stack_noise_coil1", 195, "noisy-coil1-hot10.json", "R1",
                                       "coil_resistance (channel 1)");
}

// kw2 +10 % (noisy-amp2-strong10.json): the other element and the other channel. Domain 72.
TEST(StackAtSensorNoise, ATenPercentAmplifierFaultIsAnErrorWithinTenSecondsOfPlantTime) {
  fault_is_an_error_within_ten_seconds("stack_noise_amp2", 72, "noisy-amp2-strong10.json", "kw2",
                                       "amplifier_gain (channel 2)");
}

// Issue 18 item 8: a nominal stack left running raised a WARN ("rotor mass ... drifting -3.9 %
// over the last 50 windows") that cleared 6 s later. The deployed stack at 10x real time for
// 300 s of plant time (the item's 5 minutes; 30 10-s records, each restarting the estimator's
// predictor after its settle): no WARN or ERROR about the bearing, and most of the plant time
// identified. Before the continuous estimator held its theta per window (2026-12-03) it was
// disabled: the relaxed per-sample rpem read R1, R2 +1.5 to +2.2 % above the baseline learned
// in the first 10 s (its bias, not the detectors), and with alerts confirmed over 3 windows it
// raised 10 WARN/ERROR R1 or R2 steps from 76.7 s on. Measured with the held theta: no alert in
// 328 s of plant time (623 windows) in 5 runs; in 1 of them, at load 4.7 on the 2-core VM, the
// windows covered 79.7 % of the span (the 80 % check failed: the identifier, two estimators at
// 10x real time, ~0.47 of a core, fell behind).
TEST(StackAtSensorNoise, ANominalBearingRaisesNoAlertInFiveMinutesOfPlantTime) {
  Stack stack("stack_noise_nominal", 179);
  configure_noisy_stack(stack, 10.0);
  for (const char* d : {"diagnostics", "identifier", "plant"}) stack.start(d);
  std::this_thread::sleep_for(std::chrono::seconds(33));  // ~300 s of plant time after the start
  for (const char* d : {"diagnostics", "identifier", "plant"}) EXPECT_TRUE(stack.running(d)) << d;
  const diag::TrendStore store(stack.store(), diag::OpenMode::read_only);
  const auto r1 = store.history("bearing-1", "R1");
  ASSERT_GE(r1.size(), 2u) << stack.log("identifier");
  RecordProperty("plant_seconds", std::to_string(r1.back().time));
  RecordProperty("windows", std::to_string(r1.size()));
  EXPECT_GE(r1.back().time, 250.0);
  EXPECT_GE(double(r1.size()) * 0.5, 0.8 * (r1.back().time - r1.front().time)) << "windows missing";
  // Every alert the diagnostics daemon stored, not only the last few the bus keeps.
  for (const diag::Alert& a : store.latest_alerts(100000, "bearing-1"))
    if ((a.level == diag::Level::warn || a.level == diag::Level::error) && a.fault != "history_gap")
      ADD_FAILURE() << "false alert at plant time " << a.time << ": " << a.parameter << " " << a.message;
}

}  // namespace stack_noise_slow_test
}  // namespace ambid::testing
