// The running stack at a source swap (issues 13, 14), configured as deploy/config runs it (rpem
// published every 0.5 s, the deploy diagnostics, the plant at real time), over loopback:
// - the main job (scripts/run.sh): the simulated bearing of deploy/config/nominal-bearing.json,
//   then the same bearing with R1 +20 % (coil1-hot.json): the ERROR on R1 naming coil 1, and
//   every WARN or ERROR names coil 1 resistance (the fault moves the bias currents, so ks, kr1,
//   kr2 truly move too: -8.7 %, -4.5 %); before the swap nothing but OK. Before the first
//   estimates after a restart were held back (amb1dof_recursive_pem.hpp, restart()) the first
//   window after this swap read ks -50 % and raised a false ERROR "rotor mass"; after it, that
//   window read kr1 +36 %, kw1 -20 % (sigmas 1.6-1.8x the baseline's, judged) and raised a false
//   ERROR "rotor mass" on kr1, then "coil 1 force factor", in 4 runs of 5, until alerts were
//   confirmed over 3 windows (diagnostics' confirm_windows, alert_policy.hpp).
// - recordings of three controllers (lqr observer, pid, lead-lag) of the same bearing at the
//   stack's noise replayed with swaps between them: no WARN or ERROR (estimates that have not
//   converged after a swap are not judged: their sigma, diagnostics' unconverged_sigma_ratio).
// Slow label: each runs the plant at real time for ~30 s. Domains 60 and 61.
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
namespace stack_swap_slow_test {

using ::testing::HasSubstr;

const std::filesystem::path deploy = std::filesystem::path(AMBID_SOURCE_DIR) / "deploy" / "config";

// The identifier and diagnostics daemons as deploy/config, the trend store in the stack's folder.
void configure_deployed(const Stack& stack) {
  std::ofstream(stack.dir() / "identifier.json") << std::ifstream(deploy / "identifier.json").rdbuf();
  std::stringstream text;
  text << std::ifstream(deploy / "diagnostics.json").rdbuf();
  std::string config = text.str();
  const std::string store_key = R"("runs/stack/trend.sqlite")";
  config.replace(config.find(store_key), store_key.size(), "\"" + stack.store().string() + "\"");
  std::ofstream(stack.dir() / "diagnostics.json") << config;
}

std::size_t stored_windows(const Stack& stack) {
  if (!std::filesystem::exists(stack.store())) return 0;
  return diag::TrendStore(stack.store(), diag::OpenMode::read_only).history("bearing-1", "R1").size();
}

// Waits (at most 120 s) for `count` stored windows.
void wait_for_windows(const Stack& stack, std::size_t count) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (stored_windows(stack) < count && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ASSERT_GE(stored_windows(stack), count) << stack.log("identifier") << stack.log("diagnostics");
}

// The plant time a `source set` answer names.
double swap_time(const CommandResult& swap) {
  const auto at = swap.output.find("plant time ");
  return at == std::string::npos ? std::nan("") : std::stod(swap.output.substr(at + 11));
}

// The WARN and ERROR lines of `ambid alerts` (a history_gap is about the data, not the bearing:
// samples the identifier missed on a loaded machine).
std::vector<std::string> raised(const Stack& stack) {
  std::vector<std::string> out;
  std::istringstream lines(stack.ambid("alerts --wait 1").output);
  for (std::string l; std::getline(lines, l);)
    if ((l.find("  WARN  ") != std::string::npos || l.find("  ERROR  ") != std::string::npos) &&
        l.find("history_gap") == std::string::npos)
      out.push_back(l);
  return out;
}

TEST(StackSwap, TheMainJobsHotCoilIsAnErrorOnCoilOneOnly) {
  Stack stack("stack_swap_hot", 60);
  configure_deployed(stack);
  std::ofstream(stack.dir() / "plant.json") << std::ifstream(deploy / "plant.json").rdbuf();
  for (const char* d : {"diagnostics", "identifier", "plant"}) stack.start(d);
  wait_for_windows(stack, 22);  // scripts/run.sh: 20 learning windows and 2 more
  const CommandResult swap = stack.ambid("source set sim " + (deploy / "coil1-hot.json").string());
  ASSERT_EQ(swap.status, 0) << swap.output;
  const double swapped = swap_time(swap);
  ASSERT_TRUE(std::isfinite(swapped)) << swap.output;
  const CommandResult error = stack.ambid("alerts --until ERROR:R1 --timeout 60");
  ASSERT_EQ(error.status, 0) << error.output << stack.log("diagnostics");
  const auto line = error.output.find("ERROR  bearing-1  R1  coil_resistance (channel 1)");
  ASSERT_NE(line, std::string::npos) << error.output;
  // Within 10 s of plant time (issue 13); measured 2.75 s (2 runs) with the 3-window confirmation.
  const double detected = std::stod(error.output.substr(error.output.rfind("t=", line) + 2));
  RecordProperty("detection_delay_plant_s", std::to_string(detected - swapped));
  EXPECT_GT(detected, swapped) << error.output;
  EXPECT_LE(detected - swapped, 10.0) << "swap at plant time " << swapped << " s\n" << error.output;
  std::this_thread::sleep_for(std::chrono::seconds(3));  // 6 windows more
  const std::vector<std::string> lines = raised(stack);
  for (const std::string& l : lines) {
    EXPECT_GT(std::stod(l.substr(l.find("t=") + 2)), swapped) << l;
    EXPECT_THAT(l, HasSubstr("coil_resistance (channel 1)")) << l;
  }
  RecordProperty("alerts", ::testing::PrintToString(lines));
}

// A 10 s recording of `controller` at the stack's noise and excitation (nominal-bearing.json).
std::string record(const Stack& stack, const std::string& controller, int seed) {
  const SimRecording recording{.controller = controller, .seed = seed};
  const CommandResult r = record_sim(stack.dir(), recording);
  EXPECT_EQ(r.status, 0) << r.output;
  return sim_recording_file(stack.dir(), recording);
}

TEST(StackSwap, SwapsBetweenThreeControllersOfTheSameBearingRaiseNothing) {
  Stack stack("stack_swap_controllers", 61);
  configure_deployed(stack);
  const std::string lqr = record(stack, "lqr", 11), pid = record(stack, "pid", 12),
                    leadlag = record(stack, "leadlag", 13);
  std::ofstream(stack.dir() / "plant.json")
      << R"({"source": "replay", "target": ")" << lqr << R"(", "batch_samples": 500, "speed": 1})";
  for (const char* d : {"diagnostics", "identifier", "plant"}) stack.start(d);
  wait_for_windows(stack, 22);
  std::size_t windows = 22;
  for (const std::string& file : {pid, leadlag, lqr}) {
    const CommandResult swap = stack.ambid("source set replay " + file);
    ASSERT_EQ(swap.status, 0) << swap.output;
    windows += 10;
    wait_for_windows(stack, windows);  // 5 s of each loop
  }
  EXPECT_THAT(stack.log("diagnostics"), HasSubstr("the same bearing in another loop"));
  EXPECT_TRUE(raised(stack).empty()) << ::testing::PrintToString(raised(stack)) << stack.log("diagnostics");
  RecordProperty("diagnostics_log", stack.log("diagnostics"));
}

}  // namespace stack_swap_slow_test
}  // namespace ambid::testing
