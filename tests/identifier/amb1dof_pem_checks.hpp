#pragma once
// What the prediction-error tests (amb1dof_prediction_error_test.cpp and its slow twin) share:
// the record settings and the checks against the independent truth of
// tests/support/amb1dof_records.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "core/model_file.hpp"
#include "identifier/identify_experiment.hpp"
#include "support/amb1dof_records.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident::testing {

using test_support::Amb1dofRecord;
using test_support::Amb1dofRecordOptions;
using test_support::simulate_amb1dof_record;
inline const std::vector<std::string>& amb1dof_record_controllers() {
  return test_support::amb1dof_record_controllers();
}

// PRBS levels (V on each 8.75 V input). Noise-free, the error left is the force and inductance
// nonlinearity of the true plant, proportional to the level (LQR loop, v1 of the nominal
// bearing: 2.1e-4, 4.1e-4, 8.0e-4, 1.6e-3 at 0.25, 0.5, 1, 2 V; the same at 4 and 64 RK4 steps
// per sample, so not the integrator); the softer "observer" loop lets x move more per volt
// (1.2e-3 at 1 V). Lower is not better without noise: the free predictor gain is then set by
// that small nonlinearity alone and tends to a deadbeat one, and at 0.5 V on the LQR loop the
// Jacobian's condition reaches 1.2e10 (v2, v3 against K) and the fit is refused.
inline double noise_free_amplitude(const std::string& controller) { return controller == "observer" ? 0.5 : 1.0; }
inline constexpr double kWindowAmplitude = 2.0;
// 10 s at realistic noise: 2 V where the loop lets the currents move; the PID's stiff current
// loops (1000 V/A) leave v4, v6, v7 with ~1 % sigma at 2 V, so it gets 6 V, and so does the
// lead-lag (the same current loops).
inline double noisy_amplitude(const std::string& controller) {
  return controller == "pid" || controller == "leadlag" ? 6.0 : 2.0;
}
// A realistic bearing's sensors: 0.1 um on x, 1 mA on each current.
inline constexpr double kPositionNoise = 1e-7, kCurrentNoise = 1e-3;

inline Amb1dofRecordOptions noisy_record(const std::string& controller, double duration, std::uint64_t seed) {
  Amb1dofRecordOptions o;
  o.controller = controller;
  o.amplitude = kWindowAmplitude;
  o.duration = duration;
  o.position_noise = kPositionNoise;
  o.current_noise = kCurrentNoise;
  o.clock_divider = test_support::prbs_clock_divider(controller);
  o.seed = seed;
  return o;
}

// pem on the whole record after the settling (no validation part).
inline Model identify_pem(const Amb1dofRecord& record) {
  IdentifyOptions o;
  o.method = "pem";
  o.skip_samples = record.settled;
  o.validation_fraction = 0.0;
  return identify_experiment(record.experiment, o);
}

inline double worst_v_error(const Model& m, const std::map<std::string, double>& truth) {
  double worst = 0.0;
  for (const auto& [name, value] : truth) worst = std::max(worst, std::abs(m.parameters.at(name) / value - 1.0));
  return worst;
}

// The largest scatter per 1 s window at kWindowAmplitude: 1 %, except under the PID loop,
// whose stiff current loops leave R1 and R2 with ~2.3 % sigma per window at 2 V (measured:
// the information is not in such data, whatever the estimator), and the lead-lag's (the same
// current loops; not measured yet on its own).
inline double max_window_scatter(const std::string& controller) {
  return controller == "pid" || controller == "leadlag" ? 0.04 : 0.01;
}

// 1 s windows of one noisy record, each identified cold: the scatter of R1, R2, kw1, kw2 about
// their mean at most max_window_scatter (one sigma), the mean reported sigma within a factor
// 1.5 of it, and the mean within 3 standard errors of the mean plus 0.2 % of the truth.
inline void check_window_scatter(const std::string& controller, int windows, std::uint64_t seed) {
  SCOPED_TRACE(controller);
  const Amb1dofRecord record = simulate_amb1dof_record(noisy_record(controller, double(windows), seed));
  const Eigen::Index length = Eigen::Index(std::llround(1.0 / record.experiment.sample_time));
  const std::vector<std::string> names = {"R1", "R2", "kw1", "kw2"};
  std::map<std::string, std::vector<double>> errors, sigmas;
  IdentifyOptions o;
  o.method = "pem";
  o.validation_fraction = 0.0;
  for (int w = 0; w < windows; ++w) {
    const Eigen::Index begin = record.settled + w * length;
    const Model m = identify_experiment(experiment_segment(record.experiment, begin, begin + length), o);
    for (const std::string& name : names) {
      const double truth = record.true_parameters.get(name);
      errors[name].push_back(m.physical.at(name) / truth - 1.0);
      sigmas[name].push_back(m.uncertainty.at(name) / truth);
    }
  }
  for (const std::string& name : names) {
    const Eigen::Map<const Eigen::VectorXd> e(errors[name].data(), windows), s(sigmas[name].data(), windows);
    const double mean = e.mean(), scatter = std::sqrt((e.array() - mean).square().sum() / double(windows - 1));
    const double sigma = s.mean();
    ::testing::Test::RecordProperty(controller + "_" + name + "_mean_error", sci(mean));
    ::testing::Test::RecordProperty(controller + "_" + name + "_scatter", sci(scatter));
    ::testing::Test::RecordProperty(controller + "_" + name + "_sigma", sci(sigma));
    EXPECT_LT(scatter, max_window_scatter(controller)) << name;
    EXPECT_LT(sigma, 1.5 * scatter) << name;
    EXPECT_GT(sigma, scatter / 1.5) << name;
    EXPECT_LT(std::abs(mean), 3.0 * scatter / std::sqrt(double(windows)) + 0.002) << name;
  }
}

}  // namespace ambid::ident::testing
