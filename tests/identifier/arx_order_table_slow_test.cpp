// The table of identifier/time_domain/ARX_ORDER.md: the worst error of v1..v9 (and of R1, R2,
// kw1, kw2, which scale v5, v7, v8, v9) of okid, projection and closed-loop against the window
// length and the ARX order, at 0.1 um on x and 1 mA on each current with a 2 V PRBS, on the
// nonlinear bearing integrated with 10 sub-steps per sample, under the LQR observer controller
// and the decentralised PID. Prints the markdown; run
//   build/tests/identifier_slow_tests --gtest_filter='ArxOrderTable.*'
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "amb1dof_truth.hpp"
#include "arx_order_cases.hpp"
#include "core/error.hpp"
#include "identifier/identify_experiment.hpp"

namespace ambid::ident {
namespace arx_order_table_slow_test {

const std::vector<double> kWindows = {0.5, 1.0, 2.0, 4.0, 8.0};
const std::vector<Eigen::Index> kOrders = {8, 16, 32, 64, 0};  // 0: the default that grows
const std::vector<std::string> kMethods = {"okid", "projection", "closed-loop"};
const std::vector<std::string> kControllers = {"lqr", "pid"};

std::string cell(const testing::ArxCaseResult& r) {
  if (!r.error.empty()) return "fails";
  char b[48];
  std::snprintf(b, sizeof b, "%.3g (%.3g)", 100 * r.worst, 100 * r.worst_physical);
  return b;
}

TEST(ArxOrderTable, WorstErrorAgainstWindowAndOrder) {
  std::map<std::string, std::string> reached;  // method / controller -> first window at 1 %
  std::vector<std::string> failures;
  for (const std::string& controller : kControllers) {
    std::printf("\n#### %s controller: worst v1..v9 %% (worst of R1, R2, kw1, kw2 %%)\n\n", controller.c_str());
    for (const std::string& method : kMethods) {
      std::printf("| %s | ", method.c_str());
      for (const Eigen::Index q : kOrders) std::printf(q ? "q = %lld | " : "default q | ", static_cast<long long>(q));
      std::printf("\n|---|");
      for (std::size_t i = 0; i < kOrders.size(); ++i) std::printf("---|");
      std::printf("\n");
      double best_last = 1e9;
      for (const double window : kWindows) {
        const testing::ArxCase c = testing::arx_case(controller, window, 1e-7, 1e-3);
        std::printf("| %g s | ", window);
        for (const Eigen::Index q : kOrders) {
          const testing::ArxCaseResult r = testing::identify_case(c, method, q);
          if (!r.error.empty())
            failures.push_back(controller + " " + method + " " + std::to_string(window) + " s q " +
                               std::to_string(r.order) + ": " + r.error);
          std::printf("%s%s | ", cell(r).c_str(), q ? "" : (" q " + std::to_string(r.order)).c_str());
          const std::string key = method + " / " + controller;
          if (r.error.empty() && r.worst <= 0.01 && !reached.count(key)) reached[key] = std::to_string(window) + " s";
          if (window == kWindows.back() && r.error.empty()) best_last = std::min(best_last, r.worst);
        }
        std::printf("\n");
        std::fflush(stdout);
      }
      const std::string key = method + " / " + controller;
      if (!reached.count(key)) {
        char b[96];
        std::snprintf(b, sizeof b, "not within %g s (best %.3g %% at %g s)", kWindows.back(), 100 * best_last,
                      kWindows.back());
        reached[key] = b;
      }
      std::printf("\n");
    }
    // The nonlinearity floor: the same at 2 s without noise.
    std::printf("Noise free, 2 s (the floor the bearing's nonlinearity at 2 V sets):\n\n");
    const testing::ArxCase quiet = testing::arx_case(controller, 2.0, 0.0, 0.0);
    for (const std::string& method : kMethods) {
      std::printf("- %s:", method.c_str());
      for (const Eigen::Index q : kOrders) {
        const testing::ArxCaseResult r = testing::identify_case(quiet, method, q);
        std::printf(" q %lld %s;", static_cast<long long>(r.order), cell(r).c_str());
      }
      std::printf("\n");
    }
  }
  std::printf("\nWorst error at or below 1 %% first at:\n\n");
  for (const auto& [key, window] : reached) std::printf("- %s: %s\n", key.c_str(), window.c_str());
  for (const auto& f : failures) std::printf("failed: %s\n", f.c_str());
}

}  // namespace arx_order_table_slow_test
}  // namespace ambid::ident
