#include "noisy_windows.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "diagnostics/fault_signatures.hpp"
#include "diagnostics/offline_diagnosis.hpp"
#include "synthetic_estimates.hpp"

namespace ambid::diag::testing {

NoisyWindows noisy_windows(const NoisyRecord& o, double window, double start) {
  test_support::Amb1dofRecordOptions r;
  r.controller = o.controller;
  r.true_parameters = o.true_parameters;
  r.amplitude = o.amplitude;
  r.duration = o.duration;
  r.settle = 0.0;
  r.position_noise = testing::kPositionNoise;  // qualified: a unity batch may see another file's kPositionNoise
  r.current_noise = testing::kCurrentNoise;
  r.clock_divider = test_support::prbs_clock_divider(o.controller);
  r.seed = o.seed;
  NoisyWindows out{test_support::simulate_amb1dof_record(r), {}};
  const Experiment& e = out.record.experiment;
  const auto samples = Eigen::Index(std::llround(window / e.sample_time));
  out.windows = identify_experiment_windows(e, samples, "pem", start, "bearing", Source::sim);
  return out;
}

EngineConfig diagnose_config(const test_support::Amb1dofRecord& record) {
  EngineConfig config;
  config.isolation.hypotheses = closed_loop_fault_hypotheses(record.experiment);
  return config;
}

}  // namespace ambid::diag::testing

namespace ambid::diag::testing {

const std::vector<ElementFault>& element_faults() {
  static const std::vector<ElementFault> faults = {{"R1", "coil_resistance", 1},
                                                   {"R2", "coil_resistance", 2},
                                                   {"kw1", "amplifier_gain", 1},
                                                   {"kw2", "amplifier_gain", 2}};
  return faults;
}

double detection_delay(const std::vector<EstimateWindow>& nominal, std::size_t baseline_windows,
                       const std::vector<EstimateWindow>& faulty, double change, const ElementFault& expected,
                       const EngineConfig& config, const std::string& store_name) {
  std::vector<EstimateWindow> windows = nominal;
  windows.insert(windows.end(), faulty.begin(), faulty.end());
  const OfflineDiagnosis d = diagnose_offline(windows, baseline_windows, fresh_store_path(store_name), config);
  double delay = std::numeric_limits<double>::infinity();
  for (const Alert& a : d.alerts) {
    SCOPED_TRACE(a.parameter + " " + std::string(to_string(a.level)) + " at t = " + std::to_string(a.time) + ": " +
                 a.message);
    EXPECT_GT(a.time, change) << "an alert before the change";
    if (a.level == Level::ok) continue;
    EXPECT_EQ(a.fault, expected.fault);
    EXPECT_EQ(a.channel, expected.channel);
    if (a.level == Level::error) delay = std::min(delay, a.time - change);
  }
  return delay;
}

}  // namespace ambid::diag::testing
