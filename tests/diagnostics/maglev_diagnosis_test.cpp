// Diagnosis of the single-coil maglev end to end, as `ambid diagnose` runs it: records of the
// simulated rig (tests/support/maglev_records.hpp: its PID with every clamp, reference steps
// held 1.5 s, uniform w of +-0.5 V not logged, 5 um sensor noise on y, 10 uA on the logged
// current, 0.01 mm / 0.01 V / 0.01 mA logging) cut into the family's 3 s windows, each
// identified by the grey-box fit (identify_experiment_windows), the first three records the
// baseline (9 windows), fault isolation with the signatures of the records' loop
// (maglev_fault_signatures.hpp).
//   - nominal records (six more seeds, levels 13-16 mm): no alert at all;
//   - coil resistance +20 %, amplifier gain -15 %, sensor offset +0.3 mm: an ERROR naming the
//     fault (coil_resistance on R; amplifier_gain on R and L: in the first faulty window;
//     sensor_offset on Km: within four);
//   (records at other sample times, integrator steps and noise: maglev_diagnosis_slow_test.cpp);
//   - the signatures against what the grey-box fit's structure implies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "diagnostics/maglev_diagnosis_cases.hpp"
#include "diagnostics/maglev_fault_signatures.hpp"
#include "diagnostics/plant_families.hpp"

namespace ambid::diag {
namespace maglev_diagnosis_test {

using namespace maglev_cases;

TEST(MaglevDiagnosis, NominalRecordsAtTheRigsNoiseRaiseNothing) {
  std::vector<Experiment> records;
  for (std::uint64_t seed = 1; seed <= 9; ++seed) records.push_back(record_of(Record{}, Settings{}, seed));
  const Diagnosis d = diagnose(records, "maglev_nominal");
  EXPECT_EQ(d.skipped, 0u);
  EXPECT_EQ(d.baseline_windows, 9u);  // 3 records of 9.75 s: 3 windows of 3 s each
  EXPECT_EQ(d.window_ends.size(), 27u);
  EXPECT_TRUE(d.offline.alerts.empty()) << alerts_text(d.offline);
  // The baseline the grey-box fit reads against the truth (the published parameters).
  const sim::MaglevParameters truth = sim::MaglevParameters::nominal();
  EXPECT_NEAR(d.offline.baselines.at({"rig-1", "R"}).mean / truth.R, 1.0, 0.002);
  EXPECT_NEAR(d.offline.baselines.at({"rig-1", "L"}).mean / truth.L, 1.0, 0.01);
  EXPECT_NEAR(d.offline.baselines.at({"rig-1", "n_x"}).mean / truth.n_x, 1.0, 0.01);
  EXPECT_NEAR(d.offline.baselines.at({"rig-1", "n_i"}).mean / truth.n_i, 1.0, 0.01);
  EXPECT_NEAR(d.offline.baselines.at({"rig-1", "Km"}).mean / truth.Km, 1.0, 0.1);
}

TEST(MaglevDiagnosis, CoilResistanceUpTwentyPercentIsAnErrorInTheFirstWindow) {
  Record fault;
  fault.truth.R *= 1.2;
  expect_isolated(fault, "maglev_r", "coil_resistance", {"R"}, 1);
}

TEST(MaglevDiagnosis, AmplifierGainDownFifteenPercentIsAnErrorInTheFirstWindow) {
  Record fault;
  fault.truth.kw *= 0.85;  // the fit takes kw as known: R and L read 1/0.85 = +17.6 %
  expect_isolated(fault, "maglev_kw", "amplifier_gain", {"R", "L"}, 1);
}

// Km scatters 2-5 % per window: the CUSUM needs a few windows of -26 % (measured: the 4th).
TEST(MaglevDiagnosis, SensorOffsetIsAnErrorWithinFourWindows) {
  Record fault;
  fault.rig.sensor_offset = 3e-4;  // 0.3 mm: Km reads about -26 %, n_x +2.2 %
  expect_isolated(fault, "maglev_offset", "sensor_offset", {"Km"}, 4);
}

// The signatures of the default loop against what the grey-box fit's structure implies: it
// takes kw and m as known, so an amplifier gain reads R, L as kw_nominal / kw (d log = -1)
// and a heavier body as a weaker Km; R, L, Km move alone; a sensor offset delta shifts the gap
// the law sees, so the fitted stiffness n_x g / x0 holds n_x (x0 + delta) / x0 (d log n_x per
// relative offset: 1). A sensor gain scales the acceleration the fit sees (both exponents up)
// while the equilibrium currents across the levels pin n_x / n_i: the two move alike.
TEST(MaglevDiagnosis, SignaturesFollowTheGreyBoxStructure) {
  const std::vector<FaultHypothesis>& h = default_maglev_fault_hypotheses();
  for (const FaultHypothesis& x : h) {
    std::printf("%-20s", x.fault.c_str());
    for (const std::string& p : monitored_parameters(kMaglev)) std::printf(" %s %+8.3f", p.c_str(), x.signature.at(p));
    std::printf("\n");
  }
  auto of = [&](const std::string& fault) {
    const auto it = std::find_if(h.begin(), h.end(), [&](const auto& x) { return x.fault == fault; });
    EXPECT_NE(it, h.end()) << fault;
    return it->signature;
  };
  const auto R = of("coil_resistance"), kw = of("amplifier_gain"), L = of("magnetic_saturation"),
             Km = of("force_factor"), offset = of("sensor_offset"), gain = of("sensor_gain");
  for (const std::string& p : monitored_parameters(kMaglev)) {
    SCOPED_TRACE(p);
    EXPECT_NEAR(R.at(p), p == "R" ? 1.0 : 0.0, 0.01);
    EXPECT_NEAR(L.at(p), p == "L" ? 1.0 : 0.0, 0.01);
    EXPECT_NEAR(Km.at(p), p == "Km" ? 1.0 : 0.0, 0.02);
    EXPECT_NEAR(kw.at(p), p == "R" || p == "L" ? -1.0 : 0.0, 0.02);
  }
  EXPECT_NEAR(offset.at("n_x"), 1.0, 0.15);
  EXPECT_LT(offset.at("Km"), -5.0);  // Km = m g x0^n_x / i0^n_i carries x0^n_x
  EXPECT_NEAR(offset.at("R"), 0.0, 0.01);
  EXPECT_GT(gain.at("n_x"), 0.1);
  EXPECT_NEAR(gain.at("n_x"), gain.at("n_i"), 0.1);
  EXPECT_NEAR(gain.at("R"), 0.0, 0.01);
}

}  // namespace maglev_diagnosis_test
}  // namespace ambid::diag
