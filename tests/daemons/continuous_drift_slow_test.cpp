// The identifier daemon's estimator (ContinuousEstimator: rpem, one estimate per 0.5 s window
// about a held theta, see continuous_estimator.hpp) does not drift on a nominal bearing: on records it did not generate
// (tests/support/amb1dof_records.hpp: the NONLINEAR bearing, RK4 at 16 steps per sample, the
// LQR loop the stack's bearing runs) at a real bearing's sensor noise (0.1 um on x, 1 mA on each
// current), fed as the stack feeds it (10 s records one after another, the predictor restarted
// at each record's start), the mean of the published R1, R2, kw1, kw2 (v5, v7, v8, v9 against
// the true plant linearised where its loop settles) over each 30 s of plant time after the
// first kDriftSkip s is within 3 standard errors plus 0.3 % of the truth, at the stack's 1 V
// PRBS and at 0.5 V. The former default (a plain RPEM, its information relaxed by carry 0.1 after
// each window, amb1dof_recursive_pem.hpp) read +1.1..+1.5 % at 1 V and +1.6..+2.4 % at 0.5 V over
// every 30 s (about one window sigma), which the diagnostics' detectors, comparing windows with
// the learned baseline, turned into false alerts over long nominal runs. Not yet held: at 0.3 V the window estimates
// read +1.3..+2.5 % (scatter 4 % per window) in the same test.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "identifier/identify_experiment.hpp"
#include "services/daemons/continuous_estimator.hpp"
#include "support/amb1dof_records.hpp"

namespace ambid::daemons {
namespace continuous_drift_slow_test {

constexpr double kDriftSkip = 4.0;                                      // s: the start from the nominal model
constexpr double kBlock = 30.0;                                         // s of plant time per mean
constexpr double kRecord = 10.0;                                        // s per record, as the stack's plant source
constexpr int kRecords = 6;                                             // 60 s
constexpr double kAllowance = 0.003;                                    // relative, beyond 3 standard errors
const std::vector<std::string> kDriftNames = {"v5", "v7", "v8", "v9"};  // R1, R2, kw1, kw2

// Per parameter: (plant time, relative error) of every estimate after kDriftSkip.
using Errors = std::map<std::string, std::vector<std::pair<double, double>>>;

Errors published_errors(double amplitude) {
  ContinuousEstimator estimator;
  Errors out;
  std::uint64_t seq = 0;
  for (int r = 0; r < kRecords; ++r) {
    test_support::Amb1dofRecordOptions o;
    o.controller = "lqr";
    o.amplitude = amplitude;
    o.duration = kRecord;
    o.position_noise = 1e-7;
    o.current_noise = 1e-3;
    o.seed = 100 + std::uint64_t(r);
    const test_support::Amb1dofRecord record = test_support::simulate_amb1dof_record(o);
    Experiment e = record.experiment;
    const double start = double(r) * (kRecord + 1.0);  // a gap before each record: a restart
    e.t.array() += start - e.t(record.settled);
    const auto per_window = Eigen::Index(std::lround(0.5 / e.sample_time));
    for (Eigen::Index begin = record.settled; begin + per_window <= e.samples(); begin += per_window) {
      const bus::IdentifiedModel m =
          estimator.identify(ident::experiment_segment(e, begin, begin + per_window), "p", seq++);
      if (m.time < kDriftSkip) continue;
      for (const bus::Estimate& p : m.parameters)
        if (std::find(kDriftNames.begin(), kDriftNames.end(), p.name) != kDriftNames.end())
          out[p.name].emplace_back(m.time, p.value / record.truth.at(p.name) - 1.0);
    }
  }
  return out;
}

class ContinuousDrift : public ::testing::TestWithParam<double> {};

TEST_P(ContinuousDrift, EveryThirtySecondsMeanIsTheTruth) {
  const Errors errors = published_errors(GetParam());
  for (const std::string& name : kDriftNames) {
    const auto& series = errors.at(name);
    for (double from = 0.0; from + kBlock <= kRecords * (kRecord + 1.0); from += kBlock) {
      std::vector<double> x;
      for (const auto& [t, error] : series)
        if (t >= from && t < from + kBlock) x.push_back(error);
      ASSERT_GE(x.size(), 30u) << name << " from " << from << " s";
      double mean = 0.0, var = 0.0;
      for (double v : x) mean += v / double(x.size());
      for (double v : x) var += (v - mean) * (v - mean) / double(x.size() - 1);
      const double standard_error = std::sqrt(var / double(x.size()));
      RecordProperty(name + "_mean_from_" + std::to_string(int(from)), std::to_string(mean));
      EXPECT_LE(std::abs(mean), 3.0 * standard_error + kAllowance)
          << name << " over " << kBlock << " s from " << from << " s, scatter " << std::sqrt(var);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Amplitudes, ContinuousDrift, ::testing::Values(1.0, 0.5),
                         [](const auto& param_info) { return param_info.param == 1.0 ? "stack_1V" : "low_0_5V"; });

}  // namespace continuous_drift_slow_test
}  // namespace ambid::daemons
