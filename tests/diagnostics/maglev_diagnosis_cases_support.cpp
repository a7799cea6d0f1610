#include "diagnostics/maglev_diagnosis_cases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "diagnostics/experiment_windows.hpp"
#include "diagnostics/plant_families.hpp"
#include "diagnostics/synthetic_estimates.hpp"
#include "support/maglev_records.hpp"

namespace ambid::diag::maglev_cases {

namespace maglev_diagnosis_cases_support {

// The levels of the faulty records: with R +20 % the loop loses the body at the 16 mm level.
const std::vector<double> kLowLevels = {0.014, 0.013, 0.015, 0.0145, 0.0155, 0.0135};

}  // namespace maglev_diagnosis_cases_support
using namespace maglev_diagnosis_cases_support;

Experiment record_of(const Record& r, const Settings& s, std::uint64_t seed) {
  sim::MaglevRunOptions run = test_support::maglev_run_options(s.sample_time, s.samples, seed);
  run.substeps = s.substeps;
  run.position_noise *= s.noise_scale;
  run.current_noise *= s.noise_scale;
  if (!s.levels.empty()) run.levels = s.levels;
  return test_support::maglev_record(r.truth, r.rig, run);
}

// The first three records are the baseline; windows of 3 s, laid end to end.
Diagnosis diagnose(const std::vector<Experiment>& records, const std::string& name) {
  Diagnosis d;
  std::vector<EstimateWindow> windows;
  double start = 0.0;
  const MonitoredFamily& family = monitored_family(kMaglev, "test");
  for (std::size_t k = 0; k < records.size(); ++k) {
    const Experiment& e = records[k];
    const auto samples = Eigen::Index(std::lround(family.window / e.sample_time));
    ExperimentWindows w =
        identify_experiment_windows(e, samples, std::string(family.window_method), start, "rig-1", Source::sim);
    start = w.time_to;
    d.record_ends.push_back(w.time_to);
    d.skipped += w.skipped.size();
    if (k < 3) d.baseline_windows += w.windows.size();
    for (const EstimateWindow& x : w.windows) d.window_ends.push_back(x.time);
    windows.insert(windows.end(), w.windows.begin(), w.windows.end());
  }
  EngineConfig config;
  config.isolation.family = kMaglev;
  config.isolation.hypotheses = fault_hypotheses(records.front());
  d.offline = diagnose_offline(windows, d.baseline_windows, testing::fresh_store_path(name), config);
  return d;
}

std::string alerts_text(const OfflineDiagnosis& d) {
  std::string s;
  for (const Alert& a : d.alerts)
    s += "  t " + std::to_string(a.time) + " " + std::string(to_string(a.level)) + " " + a.fault + " " + a.parameter +
         ": " + a.message + "\n";
  return s;
}

// Three nominal baseline records and one nominal record after them (seeds 1-4), then two of `fault`.
namespace maglev_diagnosis_cases_support {

std::vector<Experiment> with_fault(const Record& fault, const Settings& s) {
  std::vector<Experiment> records;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) records.push_back(record_of(Record{}, s, seed));
  for (std::uint64_t seed = 5; seed <= 6; ++seed) records.push_back(record_of(fault, s, seed));
  return records;
}

// The windows from the first of the faulty records (the fifth) to the first ERROR about
// `parameter`, both included; nullopt when there is none.
std::optional<std::size_t> windows_to_error(const Diagnosis& d, const std::string& parameter) {
  const double fault_start = d.record_ends.at(3);
  for (const Alert& a : d.offline.alerts) {
    if (a.level != Level::error || a.parameter != parameter) continue;
    return std::size_t(std::count_if(d.window_ends.begin(), d.window_ends.end(),
                                     [&](double t) { return t > fault_start && t <= a.time + 1e-9; }));
  }
  return std::nullopt;
}

}  // namespace maglev_diagnosis_cases_support
using namespace maglev_diagnosis_cases_support;

void expect_isolated(const Record& fault, const std::string& name, const std::string& expected,
                     const std::vector<std::string>& parameters, std::size_t within, const Settings& s) {
  Settings settings = s;
  settings.levels = kLowLevels;
  const std::vector<Experiment> records = with_fault(fault, settings);
  const Diagnosis d = diagnose(records, name);
  const std::string text = alerts_text(d.offline);
  for (const std::string& p : parameters) {
    const std::optional<std::size_t> n = windows_to_error(d, p);
    ASSERT_TRUE(n.has_value()) << p << "\n" << text;
    EXPECT_GE(*n, 1u) << p << " raised before the fault\n" << text;
    EXPECT_LE(*n, within) << p << "\n" << text;
  }
  for (const Alert& a : d.offline.alerts) EXPECT_EQ(a.fault, expected) << text;
}

}  // namespace ambid::diag::maglev_cases
