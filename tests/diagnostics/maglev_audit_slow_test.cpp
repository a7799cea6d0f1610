// The maglev audit at the rig's fastest sample time (1.3 ms, 3000 samples, 0.01 mm / 0.01 V /
// 0.01 mA logging, r reconstructed): a position reading one sample late is named with its
// delay, and a clean record gives cause "none" (maglev_audit_test.cpp has the 3.25 ms cases).
#include <gtest/gtest.h>

#include "diagnostics/audit.hpp"
#include "maglev_audit_cases.hpp"
#include "support/maglev_records.hpp"

namespace ambid::diag {
namespace maglev_audit_slow_test {

Experiment record_at_1_3_ms(const std::string& effect) {
  const testing::MaglevCase c = testing::maglev_case(effect);
  sim::MaglevRunOptions run = test_support::maglev_run_options(1.3e-3, 3000, 11);
  run.position_noise = 0.0;  // the logger's 0.01 mm is the noise
  return test_support::maglev_record(c.truth, c.rig, run);
}

TEST(MaglevAuditSweep, AReadingOneSampleLateIsNamedWithItsDelay) {
  const AuditResult r = run_audit(record_at_1_3_ms("sensor_delay"));
  ASSERT_FALSE(r.findings.empty());
  const AuditFinding& best = r.findings.front();
  EXPECT_EQ(r.cause, "sensor_delay") << best.evidence;
  EXPECT_NEAR(best.effect.at("delay"), 1.3e-3, 0.3 * 1.3e-3) << best.evidence;
  EXPECT_LT(best.nrmse_total_after, 0.75 * r.baseline_total) << best.evidence;
}

TEST(MaglevAuditSweep, ACleanRecordHasNoCause) {
  const AuditResult r = run_audit(record_at_1_3_ms("none"));
  EXPECT_EQ(r.cause, "none") << (r.findings.empty() ? "" : r.findings.front().evidence);
}

}  // namespace maglev_audit_slow_test
}  // namespace ambid::diag
