#pragma once
// Estimate windows from simulated experiments: each window is a closed-loop simulation of the
// nonlinear amb1dof_voltage bearing (plant_sim scenario, observer/LQR/integral controller, PRBS
// on both inputs, seeded sensor noise) with the true parameters of that window, run for
// `settle` seconds so the loop reaches the operating point the fault gives it, then `window`
// seconds that are identified (identify_experiment, method closed-loop: no sigmas) and turned into an estimate
// window. Window n ends at time (n + 1) * window.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "diagnostics/diagnostics_engine.hpp"
#include "diagnostics/estimate.hpp"

namespace ambid::diag::testing {

struct SimulatedBearing {
  std::string plant_id = "bearing-A";
  std::uint64_t seed = 1;        // window n uses seed + n
  double window = 0.25;          // s identified
  double settle = 0.25;          // s simulated before it
  double amplitude = 1.0;        // PRBS level per input (V)
  double position_noise = 1e-9;  // m, std of the x sensor
  double current_noise = 1e-6;   // A, std of the i1, i2 sensors
  // Relative change of each true parameter in window n ({"R1", 0.2}: R1 20 % above nominal).
  std::function<std::map<std::string, double>(std::size_t)> change = [](std::size_t) {
    return std::map<std::string, double>{};
  };

  EstimateWindow estimate(std::size_t n) const;
};

// Windows 0 .. windows-1 of `bearing` through an engine with `config` on a fresh store.
struct SimulatedSequence {
  std::vector<Alert> alerts;
  std::vector<EstimateWindow> windows;
};
SimulatedSequence run_simulated_sequence(const SimulatedBearing& bearing, std::size_t windows,
                                         const std::string& store_name, const EngineConfig& config);

bool raised(const Alert& a);                                    // WARN or ERROR
std::string describe_alerts(const std::vector<Alert>& alerts);  // one JSON line each

}  // namespace ambid::diag::testing
