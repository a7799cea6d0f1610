// Samples where a controller clamp acted are not exogenous (experiment-format.md): the audit
// leaves them out of every fit, score and statistic and reports how many. Shown by garbage: a
// record with a hidden sensor gain whose amplifier limit is set so that it marks the 24
// largest commands of u1; the measured outputs at exactly those samples are then replaced by
// values far outside the record. Whatever is there must change nothing the audit computes
// (NRMSE, fitted effect, z, residual check, correlation with r, spectra), while the
// same garbage unmarked moves the nominal NRMSE.
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "audit_cases.hpp"
#include "core/controller_replay.hpp"
#include "diagnostics/audit.hpp"

namespace ambid::diag {
namespace audit_clamps_test {

constexpr Eigen::Index kMarked = 24;

// The record with an upper limit on u1 at its kMarked-th largest command (it marks those
// samples) and none on u2.
Experiment with_limit(Experiment e) {
  std::vector<double> u1(e.u.col(0).data(), e.u.col(0).data() + e.samples());
  std::nth_element(u1.begin(), u1.begin() + (kMarked - 1), u1.end(), std::greater<>());
  e.controller->output_limits = {Limit{-INFINITY, u1[std::size_t(kMarked - 1)]}, Limit{}};
  return e;
}

// The outputs at the marked samples replaced by garbage (1 mm, 1 A off).
Experiment with_garbage(Experiment e, const std::vector<bool>& marked) {
  for (Eigen::Index k = 0; k < e.samples(); ++k)
    if (marked[std::size_t(k)]) e.y.row(k) += Eigen::RowVector3d(1e-3, 1.0, -1.0);
  return e;
}

void expect_same(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const char* what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  EXPECT_EQ((a - b).cwiseAbs().maxCoeff(), 0.0) << what;
}

TEST(AuditClamps, ClampedSamplesCountInNoStatistic) {
  const Experiment clean = with_limit(testing::simulate_hidden(testing::draw_effect("sensor_gain", 9), 0.4, 9));
  const ControllerReplay clamps = clamped_samples(clean);
  ASSERT_EQ(clamps.clamped_samples, kMarked);
  const Experiment garbage = with_garbage(clean, clamps.clamped);
  AuditOptions o;
  o.fitted_candidates = 2;
  o.max_effects = 1;
  const AuditResult a = run_audit(clean, o), b = run_audit(garbage, o);

  EXPECT_EQ(a.clamped_samples, kMarked);
  expect_same(a.baseline_nrmse, b.baseline_nrmse, "baseline NRMSE");
  ASSERT_EQ(a.findings.size(), b.findings.size());
  for (std::size_t i = 0; i < a.findings.size(); ++i) {
    EXPECT_EQ(a.findings[i].effect.parameters, b.findings[i].effect.parameters) << i;
    EXPECT_EQ(a.findings[i].test.z, b.findings[i].test.z) << i;
    EXPECT_EQ(a.findings[i].residual.p_value, b.findings[i].residual.p_value) << i;
  }
  EXPECT_EQ(a.cause, b.cause);
  EXPECT_EQ(a.cause, "sensor_gain");
  EXPECT_TRUE(a.nominal_check.determinable);
  EXPECT_LT(a.nominal_check.windows, a.validation.size() / a.nominal_check.window);  // windows left out
  expect_same(a.nominal_check.coherence_mean, b.nominal_check.coherence_mean, "residual check");
  expect_same(a.excitation_correlation, b.excitation_correlation, "correlation with r");
  expect_same(a.residual_nominal.power, b.residual_nominal.power, "residual spectrum");
  // The validation part (0.2 s) holds too few Welch segments without a marked sample for an
  // FRF: both are empty, or equal.
  ASSERT_EQ(a.frfs.ratio_nominal.lines(), b.frfs.ratio_nominal.lines());
  for (std::size_t l = 0; l < a.frfs.ratio_nominal.value.size(); ++l)
    EXPECT_EQ((a.frfs.ratio_nominal.value[l] - b.frfs.ratio_nominal.value[l]).cwiseAbs().maxCoeff(), 0.0) << l;

  const nlohmann::json j = audit_json(b, "run.json", "model-extended.json");
  EXPECT_EQ(j["clamped_samples"]["count"], kMarked);
  EXPECT_EQ(
      j["clamped_samples"]["estimation"].get<Eigen::Index>() + j["clamped_samples"]["validation"].get<Eigen::Index>(),
      kMarked);

  // Unmarked, the garbage is scored.
  Experiment unmarked = garbage;
  unmarked.controller->output_limits.clear();
  o.fitted_candidates = 1;
  const AuditResult c = run_audit(unmarked, o);
  EXPECT_EQ(c.clamped_samples, 0);
  EXPECT_GT(c.baseline_total, 2.0 * a.baseline_total);
}

}  // namespace audit_clamps_test
}  // namespace ambid::diag
