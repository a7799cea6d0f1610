// The diagnostics engine on estimate windows identified from simulated experiments with
// sensor noise (simulated_windows.hpp): the truth is the fault the simulation was given.
// Steps of single faults are in simulated_step_test.cpp.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "diagnostics/diagnostics_engine.hpp"
#include "diagnostics/simulated_windows.hpp"

namespace ambid::diag {
namespace simulated_sequence_test {

using testing::describe_alerts;
using testing::raised;

constexpr std::size_t kLearning = 30;
constexpr std::size_t kChangeAt = 40;

EngineConfig config() {
  EngineConfig c;
  c.monitor.learning_windows = kLearning;
  return c;
}

// R1 rising by 0.1 % of nominal per window from window kChangeAt on (+10 % 100 windows
// later): a WARN (or ERROR) on coil 1 resistance while the true rise is still below 10 %.
TEST(SimulatedDrift, SlowRiseOfR1WarnsBeforeTenPercent) {
  testing::SimulatedBearing bearing;
  bearing.seed = 6000;
  auto rise = [](std::size_t n) { return n < kChangeAt ? 0.0 : 0.001 * static_cast<double>(n - kChangeAt + 1); };
  bearing.change = [&](std::size_t n) { return std::map<std::string, double>{{"R1", rise(n)}}; };
  const auto r = testing::run_simulated_sequence(bearing, kChangeAt + 100, "sim_drift_R1", config());
  std::optional<std::size_t> warned;
  for (std::size_t n = 0; n < r.windows.size() && !warned; ++n)
    for (const Alert& a : r.alerts)
      if (a.time == r.windows[n].time && raised(a) && a.parameter == "R1" && a.fault == "coil_resistance" &&
          a.channel == 1)
        warned = n;
  ASSERT_TRUE(warned) << describe_alerts(r.alerts);
  EXPECT_LT(rise(*warned), 0.10) << describe_alerts(r.alerts);
  // Whatever else the rise moves (the bias currents) is named after coil 1 too.
  for (const Alert& a : r.alerts)
    if (raised(a)) {
      EXPECT_EQ(a.fault, "coil_resistance") << describe_alerts(r.alerts);
      EXPECT_EQ(a.channel, 1) << describe_alerts(r.alerts);
    }
  ::testing::Test::RecordProperty("true_rise_at_warning", std::to_string(rise(*warned)));
}

// Nominal windows with noise: not one WARN or ERROR (the 1000-window version is in
// simulated_nominal_slow_test.cpp).
TEST(SimulatedNominal, NoAlertIn150Windows) {
  testing::SimulatedBearing bearing;
  bearing.seed = 7000;
  const auto r = testing::run_simulated_sequence(bearing, 150, "sim_nominal_150", config());
  for (const Alert& a : r.alerts) EXPECT_FALSE(raised(a)) << describe_alerts(r.alerts);
}

}  // namespace simulated_sequence_test
}  // namespace ambid::diag
