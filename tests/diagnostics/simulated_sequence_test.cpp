// The diagnostics engine on estimate windows identified from simulated experiments with
// sensor noise (simulated_windows.hpp): the truth is the fault the simulation was given.
#include <gtest/gtest.h>

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "diagnostics/diagnostics_engine.hpp"
#include "diagnostics/simulated_windows.hpp"
#include "diagnostics/synthetic_estimates.hpp"

namespace ambid::diag {
namespace {

constexpr std::size_t kLearning = 30;
constexpr std::size_t kChangeAt = 40;

EngineConfig config() {
  EngineConfig c;
  c.monitor.learning_windows = kLearning;
  return c;
}

struct Sequence {
  std::vector<Alert> alerts;
  std::vector<EstimateWindow> windows;
};

Sequence run(const testing::SimulatedBearing& bearing, std::size_t windows, const std::string& store_name) {
  TrendStore store(testing::fresh_store_path(store_name));
  DiagnosticsEngine engine(store, config());
  Sequence r;
  for (std::size_t n = 0; n < windows; ++n) {
    r.windows.push_back(bearing.estimate(n));
    for (Alert& a : engine.process(r.windows.back())) r.alerts.push_back(std::move(a));
  }
  return r;
}

bool raised(const Alert& a) { return a.level == Level::warn || a.level == Level::error; }

std::string describe(const std::vector<Alert>& alerts) {
  std::string text;
  for (const Alert& a : alerts) text += "\n  " + to_json(a).dump();
  return text;
}

struct StepCase {
  std::string parameter;
  std::string fault;
  int channel;
};
void PrintTo(const StepCase& c, std::ostream* os) { *os << c.parameter; }

class SimulatedStep : public ::testing::TestWithParam<StepCase> {};

// +20 % of one true parameter from window kChangeAt on: ERROR on that parameter with its
// fault and channel within 3 windows, and no WARN or ERROR naming any other fault or channel.
// The fault also moves the operating point: R1 +20 % lowers both bias currents by 4.5 %, so
// the identified ks falls ~8 % and kr1, kr2 ~4 % (fault_signatures_test.cpp); those alerts
// must name coil 1 resistance too (fault_isolation.hpp: the closed-loop signatures).
TEST_P(SimulatedStep, ErrorNamesTheFaultWithinAFewWindows) {
  const StepCase c = GetParam();
  testing::SimulatedBearing bearing;
  bearing.seed = 5000;
  bearing.change = [&](std::size_t n) {
    return n >= kChangeAt ? std::map<std::string, double>{{c.parameter, 0.2}} : std::map<std::string, double>{};
  };
  const Sequence r = run(bearing, kChangeAt + 8, "sim_step_" + c.parameter);
  std::optional<double> error_time;
  for (const Alert& a : r.alerts) {
    if (!raised(a)) continue;
    EXPECT_EQ(a.fault, c.fault) << describe(r.alerts);
    EXPECT_EQ(a.channel, c.channel) << describe(r.alerts);
    if (a.level == Level::error && a.parameter == c.parameter && !error_time) error_time = a.time;
  }
  ASSERT_TRUE(error_time) << describe(r.alerts);
  const double first_changed = r.windows[kChangeAt].time;
  EXPECT_LE(*error_time, first_changed + 2 * bearing.window + 1e-9) << describe(r.alerts);
  EXPECT_GE(*error_time, first_changed) << describe(r.alerts);
}

INSTANTIATE_TEST_SUITE_P(Faults, SimulatedStep,
                         ::testing::Values(StepCase{"R1", "coil_resistance", 1}, StepCase{"R2", "coil_resistance", 2},
                                           StepCase{"kw1", "amplifier_gain", 1},
                                           StepCase{"kw2", "amplifier_gain", 2}),
                         [](const ::testing::TestParamInfo<StepCase>& p) { return p.param.parameter; });

// R1 rising by 0.1 % of nominal per window from window kChangeAt on (+10 % 100 windows
// later): a WARN (or ERROR) on coil 1 resistance while the true rise is still below 10 %.
TEST(SimulatedDrift, SlowRiseOfR1WarnsBeforeTenPercent) {
  testing::SimulatedBearing bearing;
  bearing.seed = 6000;
  auto rise = [](std::size_t n) { return n < kChangeAt ? 0.0 : 0.001 * static_cast<double>(n - kChangeAt + 1); };
  bearing.change = [&](std::size_t n) { return std::map<std::string, double>{{"R1", rise(n)}}; };
  const Sequence r = run(bearing, kChangeAt + 100, "sim_drift_R1");
  std::optional<std::size_t> warned;
  for (std::size_t n = 0; n < r.windows.size() && !warned; ++n)
    for (const Alert& a : r.alerts)
      if (a.time == r.windows[n].time && raised(a) && a.parameter == "R1" && a.fault == "coil_resistance" &&
          a.channel == 1)
        warned = n;
  ASSERT_TRUE(warned) << describe(r.alerts);
  EXPECT_LT(rise(*warned), 0.10) << describe(r.alerts);
  ::testing::Test::RecordProperty("true_rise_at_warning", std::to_string(rise(*warned)));
}

// Nominal windows with noise: not one WARN or ERROR (the 1000-window version is in
// simulated_nominal_slow_test.cpp).
TEST(SimulatedNominal, NoAlertIn150Windows) {
  testing::SimulatedBearing bearing;
  bearing.seed = 7000;
  const Sequence r = run(bearing, 150, "sim_nominal_150");
  for (const Alert& a : r.alerts) EXPECT_FALSE(raised(a)) << describe(r.alerts);
}

}  // namespace
}  // namespace ambid::diag
