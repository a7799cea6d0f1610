// The audit on records it did not generate (tests/support/amb1dof_effect_records.hpp: the
// plant and effects written again, RK4 with 50 sub-steps, four controllers, coloured sensor
// noise of 0.1 um / 1 mA, a process force): every effect at a moderate size, drawn, is named
// with its channel (or, for the pairs the audit cannot tell apart at this noise, listed at
// accepted_causes(), its partner: never an unrelated cause); clean records from every
// controller give "none".
// audit_independent_slow_test.cpp: false acceptance over 100 clean records, detection
// probability against size.
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "audit_independent_cases.hpp"
#include "diagnostics/audit.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::diag {
namespace audit_independent_test {

class IndependentTruth : public ::testing::TestWithParam<std::string> {};

TEST_P(IndependentTruth, AuditNamesTheEffectAndItsChannel) {
  const std::string name = GetParam();
  const auto names = testing::independent_effect_names();
  const auto index = std::uint64_t(std::find(names.begin(), names.end(), name) - names.begin());
  for (std::uint64_t draw = 0; draw < 2; ++draw) {
    sim::Effect truth;
    const test_support::EffectRecordOptions o =
        testing::hidden_effect_record(name, 4100 + 17 * index + draw, index + draw, truth);
    const AuditResult r = run_audit(test_support::simulate_effect_record(o));
    ASSERT_FALSE(r.findings.empty());
    const AuditFinding& best = r.findings.front();
    std::string hidden = o.controller + ", hidden";
    for (const auto& [key, value] : truth.parameters) hidden += " " + key + "=" + std::to_string(value);
    if (name == "flexible_mode") {  // found 4 of 6 times at this size: never another cause
      EXPECT_TRUE(r.cause == name || r.cause == "none")
          << hidden << ": found " << best.effect.name << ": " << best.evidence;
      continue;
    }
    const auto accepted = testing::accepted_causes(name);
    const auto in_group = [&](const std::string& effect) {
      return std::find(accepted.begin(), accepted.end(), effect) != accepted.end();
    };
    // "unexplained" (the residual check finds the extended model short of noise) is no false
    // cause when the best candidate is the effect or its partner.
    EXPECT_TRUE(in_group(r.cause) || (r.cause == "unexplained" && in_group(best.effect.name)))
        << hidden << ": cause " << r.cause << ", found " << best.effect.name << ": " << best.evidence;
    if (name == "force_factor" && best.effect.name == name && best.effect.channel != truth.channel) {
      // Only the ratio K1 / K2 shows at this noise (it sets the bias currents' balance): K2 x
      // 1.163 was found as K1 x 0.861. The other coil is named with the same ratio.
      EXPECT_NEAR((1.0 + best.effect.at("dratio")) * (1.0 + truth.at("dratio")), 1.0, 0.05) << hidden;
    } else {
      EXPECT_EQ(best.effect.channel, truth.channel) << hidden;
    }
    if (r.cause == name) {  // the fitted size within 35 % of the truth's (an independent plant)
      EXPECT_NEAR(testing::relative_size(best.effect), testing::relative_size(truth),
                  0.35 * testing::relative_size(truth))
          << hidden << ": " << best.evidence;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Catalogue, IndependentTruth, ::testing::ValuesIn(testing::independent_effect_names()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

// Saturation by another curve (phi = a_s tanh(a / a_s), i_sat 1.2 A) than the catalogue's is
// still magnetic_saturation, not a sensor gain: the misses of the first independent suite.
TEST(IndependentTruth, SaturationOfAnotherCurveIsNotASensorGain) {
  for (const std::string controller : {"lqr", "pid"}) {
    test_support::EffectRecordOptions o = testing::realistic_record(controller, 4300);
    o.effects = {sim::Effect{"magnetic_saturation", 0, {{"i_sat", 1.2}}}};
    const AuditResult r = run_audit(test_support::simulate_effect_record(o));
    EXPECT_EQ(r.cause, "magnetic_saturation") << controller << ": " << r.findings.front().evidence;
  }
}

// The generator and the audit's replay (Amb1dofExtended in run_closed_loop) are two
// implementations of EFFECTS.md: noise-free, with the same controller and r, every effect at
// its catalogue scale (a mode at 1.3 kHz) comes out the same within 1e-3 of the effect itself
// (measured: 2e-9 to 7e-4; before the replay's sub-step rule the mode was 0.14 off, before its
// Hermite interpolation a delay of half a sample 0.017).
TEST(IndependentTruth, NoiseFreeRecordsAgreeWithTheAuditsReplay) {
  test_support::EffectRecordOptions o;
  o.duration = 0.3;
  o.amplitude = 0.5;
  o.position_noise = o.current_noise = o.force_noise = 0.0;
  const Eigen::MatrixXd clean = test_support::simulate_effect_record(o).y_deviation();
  for (const auto& spec : sim::effect_catalogue()) {
    std::map<std::string, double> values;
    for (const auto& p : spec.parameters)
      if (p.switches) values[p.name] = p.scale;
    if (spec.name == "flexible_mode") values["f"] = 1300.0;
    if (spec.has_channel) values["channel"] = 2;
    o.effects = {sim::make_effect(spec.name, values)};
    const Eigen::MatrixXd independent = test_support::simulate_effect_record(o).y_deviation();
    sim::ScenarioOptions s;
    s.duration = o.duration;
    s.amplitude = o.amplitude;
    s.seed = o.seed;
    s.effects = o.effects;
    const Eigen::MatrixXd replayed = sim::simulate_scenario(s).y_deviation();
    for (Eigen::Index j = 0; j < clean.cols(); ++j) {
      const double effect = (independent.col(j) - clean.col(j)).norm();
      ASSERT_GT(effect, 0.0) << spec.name;
      EXPECT_LT((independent.col(j) - replayed.col(j)).norm(), 1e-3 * effect) << spec.name << " output " << j;
    }
  }
}

// Mismatches outside the catalogue are not forced onto it: the nominal model is rejected but
// the cause is "unexplained" (experiment-format.md), never a catalogue effect. Needs the
// residual check of branch audit-accept, which brings force_factor into the catalogue with it.
// One out-of-catalogue mismatch per controller (index c of effect_record_controllers()).
AuditResult audit_out_of_catalogue(int c, std::string& what, std::string& controller) {
  const auto& controllers = test_support::effect_record_controllers();
  test_support::EffectRecordOptions o = testing::realistic_record(controllers[std::size_t(c)], 4700 + std::uint64_t(c));
  test_support::OutOfCatalogue& x = o.out_of_catalogue;
  if (c == 0) x.inductance_error = 0.05, x.inductance_channel = 2, what = "Ls2 +5 %";
  if (c == 1) x.sensor_offset = 5e-6, what = "sensor offset 5 um";
  if (c == 2) x.modes = {{0.3, 650.0, 0.015}, {0.3, 1500.0, 0.01}}, what = "two flexible modes";
  if (c == 3) x.gain_drift = 0.1, x.gain_drift_period = 0.5, what = "amplifier 1 gain +-10 % at 2 Hz";
  controller = o.controller;
  return run_audit(test_support::simulate_effect_record(o));
}

TEST(IndependentTruth, OutOfCatalogueMismatchesAreUnexplained) {
  for (int c : {0, 2, 3}) {
    std::string what, controller;
    const AuditResult r = audit_out_of_catalogue(c, what, controller);
    ASSERT_FALSE(r.findings.empty());
    // Two modes: the catalogue's one mode is a fair first cause.
    const bool fair = r.cause == "unexplained" || r.cause == "none" || (c == 2 && r.cause == "flexible_mode");
    EXPECT_TRUE(fair) << what << " (" << controller << "): named " << r.cause << ": " << r.findings.front().evidence;
  }
}

// A 5 um sensor offset under the observer loop was named force_factor channel 2 (z 131): the
// integral loop holds the sensor at zero, so the rotor sits 5 um off centre and the bias currents
// shift, which one coil's force factor also explains. The audit's foils (audit_foils.hpp) fit the
// offset itself (5.1 um), force_factor beats it by z 1.3 only (below foil_margin 1.5: the two
// differ only in their dynamics, near the noise), so the cause is unexplained; the inductance
// foils find nothing (z below the acceptance threshold).
TEST(IndependentTruth, ASensorOffsetIsNotNamedAsACatalogueCause) {
  std::string what, controller;
  const AuditResult r = audit_out_of_catalogue(1, what, controller);
  ASSERT_FALSE(r.findings.empty());
  EXPECT_EQ(r.cause, "unexplained") << what << " (" << controller << "): " << r.findings.front().evidence;
  EXPECT_EQ(r.foil_beats_cause, "position sensor offset");
  for (const FoilFinding& f : r.foils) {
    if (f.name == "position sensor offset")
      EXPECT_NEAR(f.value, 5e-6, 0.25e-6);
    else
      EXPECT_LT(f.test.z, r.z_threshold) << f.name << " " << f.value;
  }
}

TEST(IndependentTruth, CleanRecordsFromEveryControllerHaveNoCause) {
  const auto& controllers = test_support::effect_record_controllers();
  int named = 0;
  for (std::uint64_t s = 0; s < 12; ++s) {
    const std::string& controller = controllers[s % controllers.size()];
    const AuditResult r =
        run_audit(test_support::simulate_effect_record(testing::realistic_record(controller, 4500 + s)));
    ASSERT_FALSE(r.findings.empty());
    if (r.cause != "none") ++named;
    EXPECT_EQ(r.cause, "none") << controller << " seed " << 4500 + s << ": " << r.findings.front().evidence;
    EXPECT_GT(r.findings.front().nrmse_total_after, 0.95 * r.baseline_total) << controller;
  }
  EXPECT_EQ(named, 0);
}

}  // namespace audit_independent_test
}  // namespace ambid::diag
