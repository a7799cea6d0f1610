// Issue 18 soak: the stack's closed-loop windows reported no uncertainty (sigma 0), so the
// diagnostics judged every window by the scatter of the baseline's windows. That scatter goes
// as 1 / excitation amplitude (R1 of 0.25 s windows, quiet bearing, PRBS: sd 0.83 ohm at 1 V,
// 1.55 at 0.5 V, 3.7 at 0.2 V), and the soak's swaps and excitation commands (0.05-0.5 V) after
// a baseline learned at 1 V raised ~50 false WARN/ERROR in 300 s of plant time. With the
// identifier's `jackknife` key every window says how uncertain it is. Domain 231.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <thread>
#include <vector>

#include "diagnostics/trend_store.hpp"
#include "stack_support.hpp"

namespace ambid::testing {
namespace identifier_uncertainty_test {

TEST(IdentifierUncertainty, ClosedLoopWindowsCarryTheirJackknifeSigma) {
  Stack stack("stack_identifier_jackknife", 231);
  std::ofstream(stack.dir() / "identifier.json")
      << R"({"window": 0.25, "settle": 0.25, "method": "closed-loop", "jackknife": 4})";
  for (const char* d : {"diagnostics", "identifier", "plant"}) stack.start(d);
  std::this_thread::sleep_for(std::chrono::seconds(6));
  ASSERT_TRUE(stack.running("identifier")) << stack.log("identifier");
  const auto r1 = diag::TrendStore(stack.store(), diag::OpenMode::read_only).history("bearing-1", "R1");
  ASSERT_GE(r1.size(), 20u) << stack.log("identifier");
  double mean = 0.0;
  std::vector<double> sigmas;
  for (const auto& e : r1) {
    mean += e.value / double(r1.size());
    sigmas.push_back(e.sigma);
  }
  double variance = 0.0;
  for (const auto& e : r1) variance += (e.value - mean) * (e.value - mean) / double(r1.size() - 1);
  std::sort(sigmas.begin(), sigmas.end());
  EXPECT_GT(sigmas.front(), 0.0);
  // Honest: the median sigma within a factor 2 of the windows' scatter (0.5-0.8 ohm at 1 V).
  const double median = sigmas[sigmas.size() / 2];
  EXPECT_GT(median, 0.5 * std::sqrt(variance));
  EXPECT_LT(median, 2.0 * std::sqrt(variance));
}

}  // namespace identifier_uncertainty_test
}  // namespace ambid::testing
