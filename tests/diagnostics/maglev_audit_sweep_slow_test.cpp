// The maglev audit across the rig's sample times (issue 16): each effect of the catalogue hidden
// in a rig record (maglev_audit_cases.hpp; tests/support/maglev_records.hpp: the rig loop's own
// PID with clamps, RK4 with 20 sub-steps of the true plant where the replay takes steps of
// 0.2 L/R, uniform noise on u not logged and r reconstructed, 0.01 mm / 0.01 V / 0.01 mA
// logging, 3000 samples, seed 11) is named, and a clean record gives cause "none", at 1.3, 1.5,
// 3.25 and 4 ms. Each case prints one row of the table
//   MAGLEV-AUDIT effect ts_ms seed cause baseline extended cut best FINDING nrmse z
// (extended: the accepted effects' validation NRMSE, the nominal's when none is accepted; cut:
// baseline / extended; best: the first finding of round 1, accepted or not):
//   build/tests/diagnostics_slow_tests --gtest_filter='MaglevAuditSweep*' | grep MAGLEV-AUDIT
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "diagnostics/audit.hpp"
#include "maglev_audit_cases.hpp"
#include "support/maglev_records.hpp"

namespace ambid::diag {
namespace {

struct SweepCase {
  std::string effect;  // the catalogue's name, or "none"
  double ts = 0.0;     // s
  std::uint64_t seed = 0;
};

std::string name_of(const ::testing::TestParamInfo<SweepCase>& info) {
  const SweepCase& c = info.param;
  return c.effect + "_" + std::to_string(int(std::lround(c.ts * 1e6))) + "us_seed" + std::to_string(c.seed);
}

std::vector<SweepCase> cases() {
  std::vector<std::string> effects = {"none"};
  for (const auto& e : testing::maglev_case_effects()) effects.push_back(e);
  std::vector<SweepCase> out;
  for (const auto& effect : effects)
    for (const double ts : {1.3e-3, 1.5e-3, 3.25e-3, 4e-3}) out.push_back({effect, ts, 11u});
  return out;
}

struct Audited {
  AuditResult result;
  double extended = 0.0;  // nrmse_total of the extended model (the nominal one for "none")
};

Audited audit(const SweepCase& c) {
  const testing::MaglevCase m = testing::maglev_case(c.effect);
  sim::MaglevRunOptions run = test_support::maglev_run_options(c.ts, 3000, c.seed);
  run.position_noise = 0.0;  // the logger's 0.01 mm is the noise
  Audited a{run_audit(testing::maglev_case_record(m, run)), 0.0};
  a.extended = nrmse(a.result.measured, a.result.extended, a.result.validation).mean();
  const AuditFinding* best = a.result.findings.empty() ? nullptr : &a.result.findings.front();
  std::printf("MAGLEV-AUDIT %-22s %5.2f %3d %-22s %.5f %.5f %6.2f best %-22s %.5f z %.1f\n", c.effect.c_str(),
              c.ts * 1e3, int(c.seed), a.result.cause.c_str(), a.result.baseline_total, a.extended,
              a.result.baseline_total / a.extended, best ? best->effect.name.c_str() : "-",
              best ? best->nrmse_total_after : 0.0, best ? best->test.z : 0.0);
  return a;
}

class MaglevAuditSweep : public ::testing::TestWithParam<SweepCase> {};

TEST_P(MaglevAuditSweep, NamesTheHiddenEffect) {
  const SweepCase& c = GetParam();
  const Audited a = audit(c);
  const std::string evidence = a.result.findings.empty() ? "" : a.result.findings.front().evidence;
  EXPECT_EQ(a.result.cause, c.effect) << evidence;
}

INSTANTIATE_TEST_SUITE_P(Seed11, MaglevAuditSweep, ::testing::ValuesIn(cases()), name_of);

}  // namespace
}  // namespace ambid::diag
