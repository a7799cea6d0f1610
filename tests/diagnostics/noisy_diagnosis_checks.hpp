#pragma once
// What the offline-diagnosis tests at a real bearing's sensor noise share
// (noisy_diagnosis_slow_test.cpp): nominal records of one controller, then a
// record of the bearing with one element +10 %, through `ambid diagnose`'s code path.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "noisy_windows.hpp"
#include "plant_sim/amb1dof_parameters.hpp"

namespace ambid::diag::testing {

// 2 V PRBS (the level issue 13 allows for per-window checks), 0.5 s windows (the stack's).
inline constexpr double kDiagnosisAmplitude = 2.0, kDiagnosisWindow = 0.5, kRecordLength = 10.0;

struct NominalRun {
  std::vector<EstimateWindow> windows;
  std::size_t baseline_windows = 0;  // those of the first record
  EngineConfig config;
  double end = 0.0;
};

// `records` nominal records of kRecordLength under `controller`, the first the baseline.
inline NominalRun nominal_run(const std::string& controller, int records, std::uint64_t seed) {
  NominalRun run;
  for (int k = 0; k < records; ++k) {
    const NoisyWindows w = noisy_windows({controller, {}, kDiagnosisAmplitude, kRecordLength, seed + std::uint64_t(k)},
                                         kDiagnosisWindow, run.end);
    EXPECT_TRUE(w.windows.skipped.empty()) << w.windows.skipped.front().failure.message;
    if (k == 0) {
      run.baseline_windows = w.windows.windows.size();
      run.config = diagnose_config(w.record);
    }
    run.windows.insert(run.windows.end(), w.windows.windows.begin(), w.windows.windows.end());
    run.end = w.windows.time_to;
  }
  return run;
}

// The delay of the ERROR about `fault` (+10 %) after `run`, checked by detection_delay.
inline double fault_delay(const NominalRun& run, const std::string& controller, const ElementFault& fault,
                          std::uint64_t seed) {
  SCOPED_TRACE(controller + ", " + fault.parameter + " +10 %");
  const double value = 1.1 * sim::Amb1dofParameters::nominal().get(fault.parameter);
  const NoisyWindows w = noisy_windows(
      {controller, {{fault.parameter, value}}, kDiagnosisAmplitude, kRecordLength, seed}, kDiagnosisWindow, run.end);
  const double delay = detection_delay(run.windows, run.baseline_windows, w.windows.windows, run.end, fault, run.config,
                                       "noisy_" + controller + "_" + fault.parameter);
  std::printf("[ detection ] %s %s +10 %%: ERROR %.2f s of plant time after the change\n", controller.c_str(),
              fault.parameter.c_str(), delay);
  ::testing::Test::RecordProperty(controller + "_" + fault.parameter + "_delay_s", std::to_string(delay));
  return delay;
}

}  // namespace ambid::diag::testing
