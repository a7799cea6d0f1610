#pragma once
// Estimate windows of records ambid did not generate (tests/support/amb1dof_records.hpp: the
// nonlinear bearing by RK4 under the lqr, pid or observer loop) at a real bearing's sensor
// noise, identified as `ambid diagnose` identifies each experiment it is given
// (identify_experiment_windows, method pem).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "diagnostics/diagnostics_engine.hpp"
#include "diagnostics/experiment_windows.hpp"
#include "support/amb1dof_records.hpp"

namespace ambid::diag::testing {

inline constexpr double kPositionNoise = 1e-7, kCurrentNoise = 1e-3;  // 0.1 um on x, 1 mA on each current

struct NoisyRecord {
  std::string controller = "lqr";
  std::map<std::string, double> true_parameters;  // overrides of the nominal bearing
  double amplitude = 1.0;                         // V of PRBS on each input
  double duration = 10.0;                         // s; the record starts at the nominal operating point
  std::uint64_t seed = 1;
};

// The record (no settling part: the first window drops the family's settling_samples, as for any record
// `ambid diagnose` reads) and its windows of `window` s on a clock where it starts at `start`.
struct NoisyWindows {
  test_support::Amb1dofRecord record;
  ExperimentWindows windows;
};
NoisyWindows noisy_windows(const NoisyRecord& options, double window, double start);

// `ambid diagnose`'s engine configuration for the loop of `record`: the fault signatures of
// its plant and controller.
EngineConfig diagnose_config(const test_support::Amb1dofRecord& record);

}  // namespace ambid::diag::testing

namespace ambid::diag::testing {

// A +10 % fault of one element: the parameter it changes and the fault and channel an alert
// about it must name.
struct ElementFault {
  std::string parameter;
  std::string fault;
  int channel = 0;
};
// R1, R2 (coil_resistance), kw1, kw2 (amplifier_gain).
const std::vector<ElementFault>& element_faults();

// Offline diagnosis, as `ambid diagnose` runs it, of `nominal` windows (the first
// `baseline_windows` of them the baseline) followed by `faulty` ones whose record starts at
// `change`: when the first ERROR came, in plant seconds after the change (infinity when none),
// with every alert checked (gtest failures): none before the change, and every one after it
// naming `expected`'s fault and channel.
double detection_delay(const std::vector<EstimateWindow>& nominal, std::size_t baseline_windows,
                       const std::vector<EstimateWindow>& faulty, double change, const ElementFault& expected,
                       const EngineConfig& config, const std::string& store_name);

}  // namespace ambid::diag::testing
