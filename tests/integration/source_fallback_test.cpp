// Issue 18: a source that fails after it was accepted (here a simulation whose excitation,
// within the configured limits, drives the rotor into the bearing from its next record on)
// stops cleanly: the plant daemon announces it (PlantSourceState), sets Health ERROR, raises an
// ERROR alert source_failed and falls back to the source before it, whose samples flow again.
// The plant daemon is a real process on its own domain; the excitation command comes over the
// bus from this test, as the frf daemon sends it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "services/bus/make_bus.hpp"
#include "stack_support.hpp"

namespace ambid::testing {
namespace source_fallback_test {

using ::testing::HasSubstr;

constexpr int kDomain = 210;

TEST(SourceFallback, ASourceFailingAtRuntimeFallsBackToThePreviousOneAndAlerts) {
  Stack stack("stack_source_fallback", kDomain);
  const std::string quiet = std::string(AMBID_SOURCE_DIR) + "/tests/integration/scenarios/quiet-bearing.json";
  // Amplitudes up to 1e5 V pass the plant daemon's limit: the board would refuse them, the
  // simulation diverges.
  std::ofstream(stack.dir() / "plant.json") << R"({"source": "sim", "target": ")" << quiet
                                            << R"(", "batch_samples": 500, "speed": 10, "max_amplitude": 1e5})";
  const std::string second = (stack.dir() / "second.json").string();
  std::ofstream(second) << R"({"name": "second", "plant": "amb1dof_voltage", "controller": "lqr",
    "excitation": "prbs", "amplitude": 1.0, "position_noise": 1e-9, "current_noise": 1e-6, "duration": 1.0,
    "sample_time": 1e-4, "seed": 7})";
  stack.start("plant");
  const CommandResult swap = stack.ambid("source set sim " + second);
  ASSERT_EQ(swap.status, 0) << swap.output << stack.log("plant");
  ASSERT_THAT(swap.output, HasSubstr("source swapped"));

  // Accepted (build_scenario takes it), fatal to the next simulated record.
  auto bus = bus::make_bus("cyclone", kDomain);
  auto commands = bus->writer<bus::ExcitationCommand>();
  bus::ExcitationCommand excite;
  excite.plant_id = "bearing-1";
  excite.seq = 1;
  excite.kind = "prbs";
  excite.amplitude = 1e4;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(15);
  while (stack.log("plant").find("excitation prbs accepted") == std::string::npos) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << stack.log("plant");
    commands->write(excite);  // until the plant's reader has matched this writer
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  }

  const CommandResult alert = stack.ambid("alerts --until ERROR:source --timeout 20");
  ASSERT_EQ(alert.status, 0) << alert.output << stack.log("plant");
  EXPECT_THAT(alert.output, HasSubstr("source_failed"));
  EXPECT_THAT(alert.output, HasSubstr("second.json failed"));
  EXPECT_THAT(alert.output, HasSubstr("back to the previous source"));
  EXPECT_THAT(stack.log("plant"), HasSubstr("resumed after the failure of the source that replaced it"));

  // Still alive, back on the first source, its Health says what happened, and samples flow.
  std::this_thread::sleep_for(std::chrono::seconds(1));
  ASSERT_TRUE(stack.running("plant")) << stack.log("plant");
  const CommandResult status = stack.ambid("status --wait 2 --expect plant");
  EXPECT_THAT(status.output, HasSubstr("source sim " + quiet)) << status.output;
  EXPECT_THAT(status.output, HasSubstr("ERROR source " + second + " failed")) << status.output;
  const std::string stem = (stack.dir() / "after").string();
  const CommandResult record = stack.ambid("record --out " + stem + " --duration 0.2");
  EXPECT_EQ(record.status, 0) << record.output;
  EXPECT_THAT(record.output, HasSubstr("2000 samples"));
  EXPECT_TRUE(stack.running("plant")) << stack.log("plant");
}

}  // namespace source_fallback_test
}  // namespace ambid::testing
