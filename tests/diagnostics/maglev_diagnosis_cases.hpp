#pragma once
// Maglev records diagnosed as `ambid diagnose` does (maglev_diagnosis_test.cpp and its slow
// test): records of the simulated rig (tests/support/maglev_records.hpp) cut into the family's
// 3 s windows, each identified by its grey-box fit (identify_experiment_windows), the first
// three records the baseline, fault isolation with the signatures of the records' loop.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "diagnostics/offline_diagnosis.hpp"
#include "plant_sim/maglev_parameters.hpp"
#include "plant_sim/maglev_rig.hpp"

namespace ambid::diag::maglev_cases {

inline constexpr const char* kMaglev = "maglev1coil_voltage";

struct Record {
  sim::MaglevParameters truth = sim::MaglevParameters::nominal();
  sim::MaglevRig rig;
};

struct Settings {
  double sample_time = 3.25e-3;
  Eigen::Index samples = 3000;
  int substeps = 20;
  double noise_scale = 1.0;    // of the rig's sensor noise (maglev_run_options)
  std::vector<double> levels;  // empty: the loop's default (13-16 mm)
};

// The rig's record of `r` (maglev_run_options: 5 um, 10 uA, w +-0.5 V) with these settings.
Experiment record_of(const Record& r, const Settings& s, std::uint64_t seed);

struct Diagnosis {
  OfflineDiagnosis offline;
  std::vector<double> window_ends;  // of every identified window, in order
  std::vector<double> record_ends;  // the end of each record's last window
  std::size_t baseline_windows = 0;
  std::size_t skipped = 0;
};

// The first three records are the baseline; windows of 3 s, laid end to end; the store under
// the test's directory named `name`.
Diagnosis diagnose(const std::vector<Experiment>& records, const std::string& name);

// One line per alert, for failure messages.
std::string alerts_text(const OfflineDiagnosis& d);

// Four nominal records and two of `fault` (seeds 1-6), of these settings with the levels
// 13-15.5 mm (with R +20 % the loop loses the body at 16 mm), diagnosed: every alert names
// `expected`; the first ERROR about each of `parameters` comes within `within` windows of the
// first faulty one (gtest failures otherwise).
void expect_isolated(const Record& fault, const std::string& name, const std::string& expected,
                     const std::vector<std::string>& parameters, std::size_t within, const Settings& s = {});

}  // namespace ambid::diag::maglev_cases
