// diagnostics: feed windows of estimated parameters to the diagnostics engine — a nominal
// bearing while the baseline is learned, then coil 1 resistance 20 % up — and print the alerts.
//   diagnose_windows TREND_DB     (a SQLite file; created when missing)
#include <iostream>
#include <random>

#include "diagnostics/diagnostics_engine.hpp"
#include "diagnostics/identified_estimates.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: diagnose_windows TREND_DB\n";
    return 2;
  }
  ambid::diag::TrendStore store(argv[1]);
  ambid::diag::DiagnosticsEngine engine(store);
  const std::map<std::string, double> nominal{{"R1", 17.5},  {"R2", 17.5},  {"kw1", 50.0}, {"kw2", 50.0},
                                              {"kr1", 10.0}, {"kr2", 10.0}, {"ks", -3e5}};
  std::mt19937 random(1);
  std::normal_distribution<double> scatter(0.0, 0.002);  // 0.2 % window-to-window scatter
  for (int k = 1; k <= 120; ++k) {
    std::map<std::string, double> physical;
    for (const auto& [name, value] : nominal) physical[name] = value * (1.0 + scatter(random));
    if (k > 80) physical["R1"] *= 1.2;  // the coil heats up
    for (const ambid::diag::Alert& alert :
         engine.process(ambid::diag::estimate_window(physical, {}, 0.25 * k, "bearing-1", ambid::diag::Source::sim)))
      std::cout << "t=" << alert.time << " s " << to_string(alert.level) << " " << alert.parameter << ": "
                << alert.message << "\n";
  }
}
