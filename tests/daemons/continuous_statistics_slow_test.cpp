// The identifier daemon's default estimator (ContinuousEstimator: rpem, each window's own
// estimate about a held theta, its prior the long-memory estimate's information scaled by carry
// 0.1) on records it did
// not generate (tests/support/amb1dof_records.hpp: the NONLINEAR bearing, RK4 at 16 steps per
// sample, four controllers) at a real bearing's sensor noise (0.1 um on x, 1 mA on each
// current), 2 V PRBS clocked as the support's noisy records are (prbs_clock_divider: every
// 3 ms under the PID and lead-lag loops, whose stiff current loops follow the command to
// ~380 Hz, so R and L show only in what the excitation puts below that; clocked every sample
// there R1, R2 scattered 1.35-1.80 % per 1 s window), 64 s. For R1, R2, kw1, kw2 (v5, v7, v8,
// v9 against the true plant linearised where its loop settles), over the estimates published
// after the first kSkip s:
// - published every 1 s (issue 13: "per 1 s window at <= 2 V"): their scatter (one sigma,
//   relative) is at most 1 %; the median reported sigma is within a factor 1.5 of that
//   scatter; their mean within 3 standard errors plus 0.5 % of the truth. (The batch pem,
//   fitted on each 1 s window alone, scatters R1 0.84 %, R2 0.73 %, kw1 0.58 %, kw2 0.51 %
//   on the PID loop, its sigma 0.92-1.06 of that: what the data allow.)
// - published every 0.5 s (deploy/config/identifier.json): the sigma matches the scatter too,
//   and successive estimates are nearly independent, as the diagnostics' CUSUM assumes
//   (diagnostics/monitor/change_detection.hpp: its run lengths are for independent z): lag-1
//   correlation <= 0.3. Why 0.3: with carry 0.1 and a 1 s memory an estimate rests 6 % on the
//   samples before its window (0.1 e^-0.5 / (1 - 0.1 e^-0.5)), so v and w alone would give a
//   lag-1 correlation of ~0.06; the standard error of a lag-1 correlation of 120 estimates is
//   0.09, and 0.3 is 0.06 + 2.6 of them. The batch pem's independent windows give -0.2..+0.1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "identifier/identify_experiment.hpp"
#include "services/daemons/continuous_estimator.hpp"
#include "support/amb1dof_records.hpp"

namespace ambid::daemons {
namespace continuous_statistics_slow_test {

constexpr double kSkip = 4.0;                                        // s: the start from the nominal model
const std::vector<std::string> kChecked = {"v5", "v7", "v8", "v9"};  // R1, R2, kw1, kw2

constexpr double kMaxScatter = 0.01;  // one sigma, relative, per 1 s window (issue 13)

double mean(const std::vector<double>& x) {
  double s = 0.0;
  for (double v : x) s += v;
  return s / double(x.size());
}
double sd(const std::vector<double>& x) {
  const double m = mean(x);
  double s = 0.0;
  for (double v : x) s += (v - m) * (v - m);
  return std::sqrt(s / double(x.size() - 1));
}
double median(std::vector<double> x) {
  std::nth_element(x.begin(), x.begin() + std::ptrdiff_t(x.size() / 2), x.end());
  return x[x.size() / 2];
}
double lag1_correlation(const std::vector<double>& x) {
  const double m = mean(x);
  double c0 = 0.0, c1 = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) c0 += (x[k] - m) * (x[k] - m);
  for (std::size_t k = 1; k < x.size(); ++k) c1 += (x[k] - m) * (x[k - 1] - m);
  return c1 / c0;
}

// One parameter's published estimates, relative to the truth.
struct Series {
  std::vector<double> values, sigmas;
};

// The record's settled part in windows of `window` s through one default estimator; the
// estimates after kSkip s by parameter name.
std::map<std::string, Series> publish(const test_support::Amb1dofRecord& record, double window) {
  const Experiment& e = record.experiment;
  const auto per_window = Eigen::Index(std::lround(window / e.sample_time));
  ContinuousEstimator estimator;
  std::map<std::string, Series> out;
  std::uint64_t seq = 0;
  for (Eigen::Index begin = record.settled; begin + per_window <= e.samples(); begin += per_window) {
    const bus::IdentifiedModel m =
        estimator.identify(ident::experiment_segment(e, begin, begin + per_window), "p", seq++);
    if (m.time - e.t(record.settled) < kSkip) continue;
    for (const bus::Estimate& p : m.parameters) {
      const double truth = record.truth.at(p.name);
      out[p.name].values.push_back(p.value / truth - 1.0);
      out[p.name].sigmas.push_back(p.sigma / truth);
    }
  }
  return out;
}

class ContinuousStatistics : public ::testing::TestWithParam<std::string> {};

TEST_P(ContinuousStatistics, SigmaIsTheScatterOfThePublishedEstimates) {
  test_support::Amb1dofRecordOptions o;
  o.controller = GetParam();
  o.amplitude = 2.0;
  o.duration = 64.0;
  o.position_noise = 1e-7;
  o.current_noise = 1e-3;
  o.seed = 11;
  o.clock_divider = test_support::prbs_clock_divider(GetParam());
  const test_support::Amb1dofRecord record = test_support::simulate_amb1dof_record(o);
  const std::map<std::string, Series> second = publish(record, 1.0), half = publish(record, 0.5);
  for (const std::string& name : kChecked) {
    const Series& s = second.at(name);
    ASSERT_EQ(s.values.size(), 60u);
    const double scatter = sd(s.values), sigma = median(s.sigmas), bias = mean(s.values);
    RecordProperty(name + "_scatter_1s", std::to_string(scatter));
    RecordProperty(name + "_sigma_1s", std::to_string(sigma));
    EXPECT_LE(scatter, kMaxScatter) << name;
    EXPECT_LE(sigma, 1.5 * scatter) << name;
    EXPECT_GE(sigma, scatter / 1.5) << name;
    EXPECT_LE(std::abs(bias), 3.0 * scatter / std::sqrt(double(s.values.size())) + 0.005) << name;

    const Series& h = half.at(name);
    const double half_scatter = sd(h.values), half_sigma = median(h.sigmas), correlation = lag1_correlation(h.values);
    RecordProperty(name + "_scatter_0.5s", std::to_string(half_scatter));
    RecordProperty(name + "_sigma_0.5s", std::to_string(half_sigma));
    RecordProperty(name + "_lag1_0.5s", std::to_string(correlation));
    EXPECT_LE(half_sigma, 1.5 * half_scatter) << name;
    EXPECT_GE(half_sigma, half_scatter / 1.5) << name;
    EXPECT_LE(correlation, 0.3) << name;
  }
}

INSTANTIATE_TEST_SUITE_P(Controllers, ContinuousStatistics,
                         ::testing::ValuesIn(test_support::amb1dof_record_controllers()),
                         [](const auto& param_info) { return param_info.param; });

}  // namespace continuous_statistics_slow_test
}  // namespace ambid::daemons
