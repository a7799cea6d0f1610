// The full sweep of audit_hidden_effect_test.cpp: for every effect, several drawn magnitudes,
// channels and seeds on 1-second records, and several clean records.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "audit_cases.hpp"
#include "diagnostics/audit.hpp"

namespace ambid::diag {
namespace audit_hidden_effect_slow_test {

constexpr int kDraws = 3;

class HiddenEffectSweep : public ::testing::TestWithParam<std::string> {};

TEST_P(HiddenEffectSweep, AuditNamesEveryDraw) {
  const auto names = sim::effect_names();
  const auto index = std::uint64_t(std::find(names.begin(), names.end(), GetParam()) - names.begin());
  for (int draw = 0; draw < kDraws; ++draw) {
    const std::uint64_t seed = 5000 + 100 * index + std::uint64_t(draw);
    const sim::Effect truth = testing::draw_effect(GetParam(), seed);
    const AuditResult r = run_audit(testing::simulate_hidden(truth, 1.0, seed));
    ASSERT_FALSE(r.findings.empty());
    const AuditFinding& best = r.findings.front();
    EXPECT_EQ(r.cause, truth.name) << "seed " << seed << " found " << best.effect.name << ": " << best.evidence;
    EXPECT_EQ(best.effect.channel, truth.channel) << "seed " << seed;
    EXPECT_LT(best.nrmse_total_after, 0.7 * r.baseline_total) << "seed " << seed << ": " << best.evidence;
    const double size = testing::effect_size(truth);
    EXPECT_NEAR(testing::effect_size(best.effect), size, 0.25 * std::abs(size)) << "seed " << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(Catalogue, HiddenEffectSweep, ::testing::ValuesIn(sim::effect_names()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

TEST(HiddenEffectSweep, CleanDataHasNoCause) {
  for (std::uint64_t seed : {11u, 12u, 13u, 14u}) {
    const AuditResult r = run_audit(testing::simulate_hidden({}, 1.0, seed));
    EXPECT_EQ(r.cause, "none") << "seed " << seed << ": " << r.findings.front().evidence;
  }
}

}  // namespace audit_hidden_effect_slow_test
}  // namespace ambid::diag
