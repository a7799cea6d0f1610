// The maglev audit across the rig's sample times and several seeds (issue 16): each effect of
// the catalogue hidden in rig records (tests/support/maglev_records.hpp: the rig loop's own PID
// with clamps, RK4 with 20 sub-steps, uniform noise on u not logged and r reconstructed,
// 0.01 mm / 0.01 V / 0.01 mA logging, 3000 samples) is named with the validation NRMSE cut at
// least 2x, and a clean record gives cause "none". That target is open (DISABLED_: run with
// --gtest_also_run_disabled_tests to tabulate it); what the audit does today on the cases
// measured (seed 11) is held by MaglevAuditToday below. Each case prints one row:
//   MAGLEV-AUDIT effect delay_samples ts_ms seed cause baseline extended cut best FINDING nrmse z
// (extended: the accepted effects' validation NRMSE, the nominal's when none is accepted; best:
// the first finding of round 1, accepted or not).
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "diagnostics/audit.hpp"
#include "maglev_audit_cases.hpp"
#include "support/maglev_records.hpp"

namespace ambid::diag {
namespace maglev_audit_sweep_slow_test {

struct SweepCase {
  std::string effect;  // the catalogue's name, or "none"
  int delay = 0;       // samples, for sensor_delay
  double ts = 0.0;     // s
  std::uint64_t seed = 0;
};

std::string name_of(const ::testing::TestParamInfo<SweepCase>& info) {
  const SweepCase& c = info.param;
  return c.effect + (c.delay ? "_" + std::to_string(c.delay) : "") + "_" +
         std::to_string(int(std::lround(c.ts * 1e6))) + "us_seed" + std::to_string(c.seed);
}

std::vector<SweepCase> cases(const std::vector<std::string>& effects) {
  std::vector<SweepCase> out;
  for (const auto& effect : effects)
    for (const int delay : effect == "sensor_delay" ? std::vector<int>{1, 2} : std::vector<int>{0})
      for (const double ts : {1.3e-3, 1.5e-3, 3.25e-3, 4e-3})
        for (const std::uint64_t seed : {11u, 12u, 13u}) out.push_back({effect, delay, ts, seed});
  return out;
}

struct Audited {
  AuditResult result;
  double extended = 0.0;  // nrmse_total of the extended model (the nominal one for "none")
};

Audited audit(const SweepCase& c) {
  testing::MaglevCase m = testing::maglev_case(c.effect);
  if (c.delay) m.rig.sensor_delay = c.delay;
  sim::MaglevRunOptions run = test_support::maglev_run_options(c.ts, 3000, c.seed);
  run.position_noise = 0.0;  // the logger's 0.01 mm is the noise
  const Experiment e = test_support::maglev_record(m.truth, m.rig, run);
  Audited a{run_audit(e), 0.0};
  a.extended = nrmse(a.result.measured, a.result.extended, a.result.validation).mean();
  const AuditFinding* best = a.result.findings.empty() ? nullptr : &a.result.findings.front();
  std::printf("MAGLEV-AUDIT %-22s %d %5.2f %3d %-22s %.5f %.5f %6.2f best %-22s %.5f z %.1f\n", c.effect.c_str(),
              c.delay, c.ts * 1e3, int(c.seed), a.result.cause.c_str(), a.result.baseline_total, a.extended,
              a.result.baseline_total / a.extended, best ? best->effect.name.c_str() : "-",
              best ? best->nrmse_total_after : 0.0, best ? best->test.z : 0.0);
  return a;
}

class HiddenEffect : public ::testing::TestWithParam<SweepCase> {};

TEST_P(HiddenEffect, DISABLED_IsNamedWithTheValidationErrorHalved) {
  const SweepCase& c = GetParam();
  const Audited a = audit(c);
  const std::string evidence = a.result.findings.empty() ? "" : a.result.findings.front().evidence;
  EXPECT_EQ(a.result.cause, c.effect) << evidence;
  EXPECT_LT(a.extended, 0.5 * a.result.baseline_total) << evidence;
  if (c.effect == "sensor_delay" && a.result.cause == c.effect) {
    EXPECT_NEAR(a.result.extended_effects.front().at("delay"), c.delay * c.ts, 0.3 * c.ts) << evidence;
  }
}

INSTANTIATE_TEST_SUITE_P(
    MaglevAuditSweep, HiddenEffect,
    ::testing::ValuesIn(cases({"sensor_nonlinearity", "force_law", "actuator_quantisation", "sensor_delay"})), name_of);

class CleanRecord : public ::testing::TestWithParam<SweepCase> {};

TEST_P(CleanRecord, DISABLED_HasNoCause) {
  const Audited a = audit(GetParam());
  EXPECT_EQ(a.result.cause, "none") << (a.result.findings.empty() ? "" : a.result.findings.front().evidence);
}

INSTANTIATE_TEST_SUITE_P(MaglevAuditSweep, CleanRecord, ::testing::ValuesIn(cases({"none"})), name_of);

// Today, at seed 11: at 3.25 ms the hidden effect is named; at 1.3 and 1.5 ms it is the best
// finding with the validation NRMSE cut `min_cut` or more, but the cause is "unexplained": the
// replay within half a step of the logged 0.01 mm runs open loop and rides the dead zone's edge,
// where the derivative gain (77 V/mm at 1.3 ms) turns micrometres into a current residual of
// about 6 % that is coherent with r, so the residual check rejects every model. A DAC of
// 0.35 V is not found (its candidate cuts nothing: the replay's command chatters across the
// steps), and the clean record at 1.3 ms is "unexplained" for the same reason.
struct TodayCase {
  SweepCase sweep;
  std::string cause, best;  // best: the first finding, "" when none is expected
  double min_cut = 0.0;     // baseline / best finding's validation NRMSE
};

class MaglevAuditToday : public ::testing::TestWithParam<TodayCase> {};

TEST_P(MaglevAuditToday, HoldsTheMeasuredOutcome) {
  const TodayCase& c = GetParam();
  const Audited a = audit(c.sweep);
  ASSERT_FALSE(a.result.findings.empty());
  const AuditFinding& best = a.result.findings.front();
  EXPECT_EQ(a.result.cause, c.cause) << best.evidence;
  if (!c.best.empty()) {
    EXPECT_EQ(best.effect.name, c.best) << best.evidence;
    EXPECT_GT(a.result.baseline_total / best.nrmse_total_after, c.min_cut) << best.evidence;
  }
}

std::string today_name(const ::testing::TestParamInfo<TodayCase>& info) {
  return name_of({info.param.sweep, info.index});
}

INSTANTIATE_TEST_SUITE_P(
    Seed11, MaglevAuditToday,
    ::testing::Values(TodayCase{{"sensor_nonlinearity", 0, 1.3e-3, 11}, "unexplained", "sensor_nonlinearity", 4.0},
                      TodayCase{{"sensor_nonlinearity", 0, 1.5e-3, 11}, "unexplained", "sensor_nonlinearity", 4.0},
                      TodayCase{
                          {"sensor_nonlinearity", 0, 3.25e-3, 11}, "sensor_nonlinearity", "sensor_nonlinearity", 10.0},
                      TodayCase{{"force_law", 0, 1.3e-3, 11}, "unexplained", "force_law", 9.0},
                      TodayCase{{"force_law", 0, 1.5e-3, 11}, "unexplained", "force_law", 9.0},
                      TodayCase{{"force_law", 0, 3.25e-3, 11}, "force_law", "force_law", 15.0},
                      TodayCase{{"sensor_delay", 1, 1.3e-3, 11}, "unexplained", "sensor_delay", 1.7},
                      TodayCase{{"actuator_quantisation", 0, 3.25e-3, 11}, "none", "", 0.0},
                      TodayCase{{"none", 0, 1.3e-3, 11}, "unexplained", "", 0.0},
                      TodayCase{{"none", 0, 3.25e-3, 11}, "none", "", 0.0}),
    today_name);

}  // namespace maglev_audit_sweep_slow_test
}  // namespace ambid::diag
