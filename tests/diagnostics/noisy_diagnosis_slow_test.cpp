// Offline diagnosis at a real bearing's sensor noise on records ambid did not generate
// (noisy_diagnosis_checks.hpp): every controller, every element +10 % (coil 1 under the LQR
// loop alone took 7 min on a loaded two-core machine); and an hour of nominal operation
// without a WARN or ERROR.
#include <gtest/gtest.h>

#include "diagnostics/offline_diagnosis.hpp"
#include "noisy_diagnosis_checks.hpp"
#include "synthetic_estimates.hpp"

namespace ambid::diag::testing {
namespace noisy_diagnosis_slow_test {

class NoisyDiagnosisPerController : public ::testing::TestWithParam<std::string> {};

TEST_P(NoisyDiagnosisPerController, EveryElementTenPercentIsAnErrorNamingItWithinTenSeconds) {
  const NominalRun run = nominal_run(GetParam(), 2, 51);
  std::uint64_t seed = 151;
  for (const ElementFault& fault : element_faults()) EXPECT_LE(fault_delay(run, GetParam(), fault, seed++), 10.0);
}

// Every controller of the records. LQR passes (ERROR after 1.0, 1.0, 0.5, 0.5 s for R1, R2,
// kw1, kw2, nothing else). PID passes since its records' PRBS is clocked every 30 samples
// (tests/support/amb1dof_records.hpp prbs_clock_divider): ERROR after 1.0, 1.0, 1.0, 0.5 s,
// nothing else (2026-12-03, 448 s on the loaded machine); with the PRBS clocked every sample
// one window of the R1 record read ks, kr1, kr2 about -102 % and other faults were named.
// Lead-lag passes the same way: ERROR after 1.0, 1.5, 1.0, 1.0 s, nothing false. Observer (all four records, failing
// before, not measured since): kr1, kr2 moved by -6..-12 % in the first seconds after the change (the softer loop
// settling to the fault's operating point), named rotor mass, force factor or both coils.
INSTANTIATE_TEST_SUITE_P(Controllers, NoisyDiagnosisPerController,
                         ::testing::ValuesIn(test_support::amb1dof_record_controllers()));

}  // namespace noisy_diagnosis_slow_test
}  // namespace ambid::diag::testing

namespace ambid::diag::testing {
namespace noisy_diagnosis_slow_test {

// An hour of the nominal bearing as the stack runs it (LQR loop, 1 V PRBS, 0.5 s windows,
// deploy/config/diagnostics.json: a baseline of 20 windows, ERROR after a step persisting 20)
// in records of 60 s: not one alert but OK.
TEST(NoisyDiagnosis, AnHourOfNominalOperationRaisesNoAlert) {
  std::vector<EstimateWindow> windows;
  double end = 0.0;
  std::size_t skipped = 0;
  EngineConfig config;
  for (std::uint64_t k = 0; end < 3600.0; ++k) {
    const NoisyWindows w = noisy_windows({"lqr", {}, 1.0, 60.0, 1000 + k}, kDiagnosisWindow, end);
    if (k == 0) config = diagnose_config(w.record);
    windows.insert(windows.end(), w.windows.windows.begin(), w.windows.windows.end());
    skipped += w.windows.skipped.size();
    end = w.windows.time_to;
  }
  EXPECT_EQ(skipped, 0u);
  config.policy.persist_windows = 20;
  config.policy.stale_timeout = 2.0;
  const OfflineDiagnosis d = diagnose_offline(windows, 20, fresh_store_path("nominal_hour"), config);
  for (const Alert& a : d.alerts)
    EXPECT_EQ(a.level, Level::ok) << a.parameter << " at t = " << a.time << " s: " << a.message;
  for (const auto& [key, level] : d.final_levels) EXPECT_EQ(level, Level::ok) << key.second;
}

}  // namespace noisy_diagnosis_slow_test
}  // namespace ambid::diag::testing
