// The gain drift test (diagnostics/audit/audit_gain_drift.hpp) on records it did not generate
// (tests/support/amb1dof_effect_records.hpp: RK4 with 50 sub-steps, four controllers, 0.1 um /
// 1 mA coloured noise, a process force): an amplifier gain varying by +-12-16 % over 0.3-0.5 s is
// found with its channel, a constant gain error (however wrong the checked model) is no drift
// and its per-part fits average to it, clean records give no drift.
#include <cmath>

#include <gtest/gtest.h>

#include "audit_independent_cases.hpp"
#include "core/error.hpp"
#include "diagnostics/audit/audit_gain_drift.hpp"

namespace ambid::diag {
namespace audit_gain_drift_test {

constexpr double kAlpha = 0.001;

GainDrift drift_of(const Experiment& measured) {
  const Eigen::Index N = measured.samples();
  return gain_drift_test(measured, measured.y_deviation(), {}, replay_outputs(measured, {}, N), Segment{0, N, {}},
                         false, 8, kAlpha);
}

TEST(AuditGainDrift, AVaryingAmplifierGainIsFoundWithItsChannel) {
  struct Case {
    const char* controller;
    int channel;
    double amplitude, period;
  };
  for (const Case c : {Case{"lqr", 2, 0.12, 0.32}, Case{"observer", 1, 0.16, 0.5}, Case{"pid", 2, 0.14, 0.4}}) {
    test_support::EffectRecordOptions o = testing::realistic_record(c.controller, 5100);
    o.out_of_catalogue.gain_drift_channel = c.channel;
    o.out_of_catalogue.gain_drift = c.amplitude;
    o.out_of_catalogue.gain_drift_period = c.period;
    const GainDrift d = drift_of(test_support::simulate_effect_record(o));
    ASSERT_TRUE(d.determinable) << d.reason;
    EXPECT_TRUE(d.varies) << c.controller << ": p " << d.p_value;
    EXPECT_EQ(d.channel, c.channel) << c.controller;
    // The per-part gains swing by about the drift's amplitude (part means of a sine: less).
    for (const GainDriftChannel& a : d.channels)
      if (a.channel == c.channel) {
        EXPECT_GT(a.gain.maxCoeff() - a.gain.minCoeff(), 0.5 * c.amplitude) << c.controller;
        EXPECT_LT(a.gain.maxCoeff() - a.gain.minCoeff(), 2.5 * c.amplitude) << c.controller;
      }
  }
}

TEST(AuditGainDrift, AConstantGainErrorIsNoDriftAndThePartsAverageToIt) {
  for (const char* controller : {"lqr", "leadlag"}) {
    test_support::EffectRecordOptions o = testing::realistic_record(controller, 5200);
    o.effects = {sim::make_effect("amplifier_gain", {{"channel", 1}, {"dkw", 0.3}})};
    const GainDrift d = drift_of(test_support::simulate_effect_record(o));
    ASSERT_TRUE(d.determinable) << d.reason;
    EXPECT_FALSE(d.varies) << controller << ": p " << d.p_value;
    ASSERT_EQ(d.channels.size(), 2u);
    const GainDriftChannel& a = d.channels.front();
    ASSERT_EQ(a.channel, 1);
    const Eigen::ArrayXd w = a.se.array().square().inverse();
    EXPECT_NEAR((w * a.gain.array()).sum() / w.sum(), 0.3, 0.06) << controller << ": " << a.gain.transpose();
  }
}

TEST(AuditGainDrift, CleanRecordsFromEveryControllerDoNotDrift) {
  const auto& controllers = test_support::effect_record_controllers();
  for (std::uint64_t s = 0; s < 8; ++s) {
    const std::string& controller = controllers[s % controllers.size()];
    const GainDrift d = drift_of(test_support::simulate_effect_record(testing::realistic_record(controller, 5300 + s)));
    ASSERT_TRUE(d.determinable) << d.reason;
    EXPECT_FALSE(d.varies) << controller << " seed " << 5300 + s << ": p " << d.p_value;
  }
}

TEST(AuditGainDrift, RefusesBadArgumentsAndSaysWhenItCannotTell) {
  const Experiment measured = test_support::simulate_effect_record(testing::realistic_record("lqr", 5400));
  const Eigen::Index N = measured.samples();
  const Eigen::MatrixXd y = measured.y_deviation(), model = replay_outputs(measured, {}, N);
  EXPECT_THROW(gain_drift_test(measured, y, {}, model, Segment{0, N, {}}, false, 2, kAlpha), Error);
  EXPECT_THROW(gain_drift_test(measured, y, {}, model, Segment{0, N, {}}, false, 8, 1.0), Error);
  const GainDrift rounded = gain_drift_test(measured, y, {}, model, Segment{0, N, {}}, true, 8, kAlpha);
  EXPECT_FALSE(rounded.determinable);
  EXPECT_FALSE(rounded.varies);
  const GainDrift short_parts = gain_drift_test(measured, y, {}, model, Segment{0, N, {}}, false, 60, kAlpha);
  EXPECT_FALSE(short_parts.determinable) << "parts of " << N / 61 << " samples";
}

}  // namespace audit_gain_drift_test
}  // namespace ambid::diag
