// diagnostics: feed windows of estimated parameters to the diagnostics engine — the nominal
// amb1dof_voltage bearing's physical parameters with 0.2 % scatter while the baseline is learned,
// then coil 1 resistance 20 % up — and print the alerts.
//   diagnose_windows TREND_DB     (a SQLite file; created when missing)
#include <iostream>
#include <random>

#include "core/error.hpp"
#include "diagnostics/diagnostics_engine.hpp"
#include "diagnostics/identified_estimates.hpp"
#include "diagnostics/plant_families.hpp"
#include "plant_sim/amb1dof_parameters.hpp"
#include "plant_sim/amb1dof_physical.hpp"

int main(int argc, char** argv) try {
  if (argc != 2) {
    std::cerr << "usage: diagnose_windows TREND_DB\n";
    return 2;
  }
  ambid::diag::TrendStore store(argv[1]);
  ambid::diag::DiagnosticsEngine engine(store);
  const ambid::sim::Amb1dofParameters bearing = ambid::sim::Amb1dofParameters::nominal();
  const std::map<std::string, double> nominal =
      ambid::sim::amb1dof_physical_from_structure(ambid::sim::amb1dof_structure_parameters(bearing), bearing).to_map();
  std::mt19937 random(1);
  std::normal_distribution<double> scatter(0.0, 0.002);  // 0.2 % window-to-window scatter
  for (int k = 1; k <= 120; ++k) {
    std::map<std::string, double> physical;
    for (const std::string& name : ambid::diag::monitored_parameters("amb1dof_voltage"))
      physical[name] = nominal.at(name) * (1.0 + scatter(random));
    if (k > 80) physical["R1"] *= 1.2;  // the coil heats up
    for (const ambid::diag::Alert& alert : engine.process(ambid::diag::estimate_window(
             "amb1dof_voltage", physical, {}, 0.25 * k, "bearing-1", ambid::diag::Source::sim)))
      std::cout << "t=" << alert.time << " s " << to_string(alert.level) << " " << alert.parameter << ": "
                << alert.message << "\n";
  }
} catch (const ambid::Error& error) {
  std::cerr << "diagnose_windows: " << error.what() << "\n";
  return 1;
}
