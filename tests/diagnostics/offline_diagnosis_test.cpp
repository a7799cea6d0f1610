// diagnose_offline and estimate_window on synthetic windows (synthetic_estimates.hpp).
#include "diagnostics/offline_diagnosis.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "diagnostics/identified_estimates.hpp"
#include "diagnostics/plant_families.hpp"
#include "diagnostics/synthetic_estimates.hpp"

namespace ambid::diag {
namespace offline_diagnosis_test {

using testing::fresh_store_path;
using testing::SyntheticPlant;

TEST(OfflineDiagnosis, BaselineFromTheFirstWindowsThenAStepIsAnError) {
  SyntheticPlant plant("bearing-A", 31, 0.005);
  plant.change = [](const std::string& p, std::size_t n) { return p == "kw2" && n >= 12 ? 0.2 : 0.0; };
  const auto path = fresh_store_path("offline");
  // A stale file of an earlier run is replaced, not appended to.
  diagnose_offline(plant.windows(0, 20), 10, path);
  plant.rng.seed(31);
  const OfflineDiagnosis d = diagnose_offline(plant.windows(0, 20), 10, path);
  ASSERT_EQ(d.alerts.size(), 1u);
  EXPECT_EQ(d.alerts[0].parameter, "kw2");
  EXPECT_EQ(d.alerts[0].level, Level::error);
  EXPECT_EQ(d.alerts[0].fault, "amplifier_gain");
  EXPECT_EQ(d.alerts[0].channel, 2);
  EXPECT_DOUBLE_EQ(d.alerts[0].time, 12.0);
  const Baseline& b = d.baselines.at({"bearing-A", "kw2"});
  EXPECT_EQ(b.windows, 10u);
  EXPECT_NEAR(b.mean, 1.0, 3 * 0.005 / std::sqrt(10.0));
  EXPECT_EQ(d.final_levels.at({"bearing-A", "kw2"}), Level::error);
  EXPECT_EQ(d.final_levels.at({"bearing-A", "R1"}), Level::ok);
  EXPECT_EQ(TrendStore(path, OpenMode::read_only).history("bearing-A", "kw2").size(), 20u);
}

TEST(OfflineDiagnosis, TooFewWindowsAreRefused) {
  SyntheticPlant plant("bearing-A", 32, 0.005);
  const auto path = fresh_store_path("offline_bad");
  EXPECT_THROW(diagnose_offline(plant.windows(0, 20), 4, path), Error);   // baseline below 5
  EXPECT_THROW(diagnose_offline(plant.windows(0, 10), 10, path), Error);  // nothing after it
  EXPECT_THROW(diagnose_offline({}, 5, path), Error);
}

TEST(EstimateWindow, TakesTheMonitoredParametersWithTheirSigmas) {
  std::map<std::string, double> physical, sigma;
  for (const auto& [name, value] : testing::nominal_parameters()) {
    physical[name] = value;
    sigma[name] = 0.01 * value;
  }
  physical["kr1_emf"] = 490.0;  // not monitored: left out
  const EstimateWindow w = estimate_window("amb1dof_voltage", physical, sigma, 2.5, "bearing-A", Source::rig);
  ASSERT_EQ(w.estimates.size(), monitored_parameters("amb1dof_voltage").size());
  EXPECT_EQ(w.estimates[0].parameter, "R1");
  EXPECT_DOUBLE_EQ(w.estimates[0].value, 17.5);
  EXPECT_DOUBLE_EQ(w.estimates[0].sigma, 0.175);
  EXPECT_DOUBLE_EQ(w.time, 2.5);
  sigma.erase("ks");
  EXPECT_THROW(estimate_window("amb1dof_voltage", physical, sigma, 2.5, "bearing-A", Source::rig), Error);
  sigma["ks"] = -1.0;  // a sigma must be non-negative (0: not reported)
  EXPECT_THROW(estimate_window("amb1dof_voltage", physical, sigma, 2.5, "bearing-A", Source::rig), Error);
}

}  // namespace offline_diagnosis_test
}  // namespace ambid::diag
