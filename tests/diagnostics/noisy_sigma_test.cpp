// Issue 18 item 8, a nominal stack's false drift WARN: the detectors on nominal windows whose
// reported sigmas are themselves noisy estimates. pem's per-window sigmas on the stack's 0.5 s
// windows scatter by 16-24 % (cv) about their median while the windows' real precision barely
// does (baseline.hpp). Here, the pessimistic end: every window equally precise (errors
// N(0, s)), reported sigmas s * exp(N(0, 0.22)) independent of the errors. The statistics the
// alarms threshold must stay standard normal: the CUSUM's z and the slope test's T. Weighted by
// the raw 1/sigma^2 (before the floor of baseline.hpp) this test measured sd 1.10 for T and
// 1.02 for z; floored, 0.93 and 0.91.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "diagnostics/monitor/baseline.hpp"
#include "diagnostics/monitor/change_detection.hpp"

namespace ambid::diag {
namespace noisy_sigma_test {

TEST(NoisyReportedSigmas, DetectorStatisticsOfNominalWindowsStayStandardNormal) {
  std::mt19937_64 rng(18);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double truth = 17.5, s = 0.25, sigma_scatter = 0.22;
  auto window = [&] { return std::pair{truth + s * normal(rng), s * std::exp(sigma_scatter * normal(rng))}; };
  std::vector<double> values, sigmas;
  for (int i = 0; i < 400; ++i) {
    const auto [v, sigma] = window();
    values.push_back(v);
    sigmas.push_back(sigma);
  }
  const Baseline b = learn_baseline(values, sigmas);
  SlopeTest slope(SlopeConfig{});
  double z2 = 0.0, t2 = 0.0;
  int zn = 0, tn = 0;
  for (int i = 0; i < 20000; ++i) {
    const auto [v, sigma] = window();
    const double z = b.z(v, sigma);
    z2 += z * z;
    ++zn;
    slope.update(0.5 * i, v, b.sigma_eff(sigma));
    if (!slope.ready()) continue;
    t2 += slope.statistic() * slope.statistic();
    ++tn;
  }
  const double z_sd = std::sqrt(z2 / zn), t_sd = std::sqrt(t2 / tn);
  RecordProperty("z_sd", std::to_string(z_sd));
  RecordProperty("slope_statistic_sd", std::to_string(t_sd));
  // ~1200 independent stretches of 50 windows: the sd of T is known to ~2 %.
  EXPECT_LT(t_sd, 1.05);
  EXPECT_GT(t_sd, 0.85);  // not made blind either
  EXPECT_LT(z_sd, 1.03);
  EXPECT_GT(z_sd, 0.85);
}

}  // namespace noisy_sigma_test
}  // namespace ambid::diag
