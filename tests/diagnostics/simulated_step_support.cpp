#include "diagnostics/simulated_step.hpp"

#include <gtest/gtest.h>

#include <map>
#include <optional>

#include "diagnostics/simulated_windows.hpp"

namespace ambid::diag::testing {
namespace simulated_step_support {

constexpr std::size_t kLearning = 30;
constexpr std::size_t kStepAt = 40;

}  // namespace simulated_step_support
using namespace simulated_step_support;

void PrintTo(const StepCase& c, std::ostream* os) { *os << c.parameter; }

const std::vector<StepCase>& step_cases() {
  static const std::vector<StepCase> cases = {{"R1", "coil_resistance", 1},
                                              {"R2", "coil_resistance", 2},
                                              {"kw1", "amplifier_gain", 1},
                                              {"kw2", "amplifier_gain", 2}};
  return cases;
}

void check_step(const StepCase& c, double relative, std::uint64_t seed, std::size_t windows) {
  SimulatedBearing bearing;
  bearing.seed = seed;
  bearing.change = [&](std::size_t n) {
    return n >= kStepAt ? std::map<std::string, double>{{c.parameter, relative}} : std::map<std::string, double>{};
  };
  EngineConfig config;
  config.monitor.learning_windows = kLearning;
  const std::string what = c.parameter + " " + std::to_string(relative) + " seed " + std::to_string(seed);
  const SimulatedSequence r = run_simulated_sequence(bearing, kStepAt + windows + 5, "sim_step_" + c.parameter, config);
  std::optional<double> error_time;
  for (const Alert& a : r.alerts) {
    if (!raised(a)) continue;
    EXPECT_EQ(a.fault, c.fault) << what << describe_alerts(r.alerts);
    EXPECT_EQ(a.channel, c.channel) << what << describe_alerts(r.alerts);
    if (a.level == Level::error && a.parameter == c.parameter && !error_time) error_time = a.time;
  }
  ASSERT_TRUE(error_time) << what << describe_alerts(r.alerts);
  const double first_changed = r.windows[kStepAt].time;
  EXPECT_LE(*error_time, first_changed + static_cast<double>(windows - 1) * bearing.window + 1e-9)
      << what << describe_alerts(r.alerts);
  EXPECT_GE(*error_time, first_changed) << what << describe_alerts(r.alerts);
}

}  // namespace ambid::diag::testing
