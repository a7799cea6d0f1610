// The audit finds an effect hidden in simulated data while the sidecar stays nominal: for each
// of the eleven effects, one case drawn at a moderate magnitude with sensor noise (short
// records; audit_hidden_effect_slow_test.cpp runs more draws on longer ones). Clean data
// gives cause "none".
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "audit_cases.hpp"
#include "diagnostics/audit.hpp"

namespace ambid::diag {
namespace audit_hidden_effect_test {

class HiddenEffect : public ::testing::TestWithParam<std::string> {};

void expect_found(const sim::Effect& truth, const Experiment& data) {
  const AuditResult r = run_audit(data);
  ASSERT_FALSE(r.findings.empty());
  const AuditFinding& best = r.findings.front();
  EXPECT_EQ(r.cause, truth.name) << "found " << best.effect.name << ": " << best.evidence;
  EXPECT_EQ(best.effect.channel, truth.channel);
  EXPECT_LT(best.nrmse_total_after, 0.7 * r.baseline_total) << best.evidence;
  // The fitted size agrees with the hidden one.
  const double size = testing::effect_size(truth);
  EXPECT_NEAR(testing::effect_size(best.effect), size, 0.25 * std::abs(size)) << best.evidence;
}

TEST_P(HiddenEffect, AuditNamesItAndTheExtendedModelPredictsBetter) {
  const auto names = sim::effect_names();
  const std::uint64_t seed = 1000 + std::uint64_t(std::find(names.begin(), names.end(), GetParam()) - names.begin());
  const sim::Effect truth = testing::draw_effect(GetParam(), seed);
  expect_found(truth, testing::simulate_hidden(truth, 0.6, seed));
}

INSTANTIATE_TEST_SUITE_P(Catalogue, HiddenEffect, ::testing::ValuesIn(sim::effect_names()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

TEST(HiddenEffect, CleanDataHasNoCause) {
  const AuditResult r = run_audit(testing::simulate_hidden({}, 0.6, 77));
  EXPECT_EQ(r.cause, "none");
  ASSERT_FALSE(r.findings.empty());
  EXPECT_GT(r.findings.front().nrmse_total_after, 0.9 * r.baseline_total);
}

}  // namespace audit_hidden_effect_test
}  // namespace ambid::diag
