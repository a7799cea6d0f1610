// Maglev diagnosis on records the identifier was not tuned on (maglev_diagnosis_cases.hpp):
// other sample times (the rig's 1.5 and 4 ms), a coarser and a finer integrator (4 and 100
// RK4 steps per sample instead of 20), twice the rig's sensor noise. The baseline is of the
// same settings (one rig); nominal records raise nothing and R +20 % is an ERROR in its first
// window. ~45 s on the loaded 2-core machine: slow.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "diagnostics/maglev_diagnosis_cases.hpp"

namespace ambid::diag {
namespace maglev_diagnosis_slow_test {

using namespace maglev_cases;

TEST(MaglevDiagnosisSettings, OtherSampleTimesIntegratorStepsAndNoise) {
  std::vector<Settings> cases(5);
  cases[0].sample_time = 1.5e-3;
  cases[0].samples = 6000;  // 9 s
  cases[1].sample_time = 4e-3;
  cases[1].samples = 2250;  // 9 s
  cases[2].substeps = 4;
  cases[3].substeps = 100;
  cases[4].noise_scale = 2.0;
  for (std::size_t c = 0; c < cases.size(); ++c) {
    SCOPED_TRACE("case " + std::to_string(c));
    Record fault;
    fault.truth.R *= 1.2;
    expect_isolated(fault, "maglev_settings_" + std::to_string(c), "coil_resistance", {"R"}, 1, cases[c]);
    Settings nominal = cases[c];
    std::vector<Experiment> records;
    for (std::uint64_t seed = 11; seed <= 16; ++seed) records.push_back(record_of(Record{}, nominal, seed));
    const Diagnosis d = diagnose(records, "maglev_settings_nominal_" + std::to_string(c));
    EXPECT_TRUE(d.offline.alerts.empty()) << alerts_text(d.offline);
  }
}

}  // namespace maglev_diagnosis_slow_test
}  // namespace ambid::diag
