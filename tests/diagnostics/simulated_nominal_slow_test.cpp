// 1000 nominal windows identified from simulated experiments with sensor noise
// (simulated_windows.hpp): the diagnostics raise no WARN and no ERROR. The 150-window version
// runs in CI (simulated_sequence_test.cpp).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "diagnostics/diagnostics_engine.hpp"
#include "diagnostics/simulated_windows.hpp"
#include "diagnostics/synthetic_estimates.hpp"

namespace ambid::diag {
namespace simulated_nominal_slow_test {

TEST(SimulatedNominal, NoAlertIn1000Windows) {
  testing::SimulatedBearing bearing;
  bearing.seed = 8000;
  TrendStore store(testing::fresh_store_path("sim_nominal_1000"));
  DiagnosticsEngine engine(store);  // default configuration: 50 learning windows
  std::size_t raised = 0;
  for (std::size_t n = 0; n < 1000; ++n)
    for (const Alert& a : engine.process(bearing.estimate(n))) {
      const bool bad = a.level == Level::warn || a.level == Level::error;
      EXPECT_FALSE(bad) << to_json(a).dump();
      raised += bad ? 1 : 0;
    }
  EXPECT_EQ(raised, 0u);
  EXPECT_EQ(store.history("bearing-A", "R1").size(), 1000u);
}

}  // namespace simulated_nominal_slow_test
}  // namespace ambid::diag
