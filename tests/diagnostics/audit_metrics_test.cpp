// The audit's measures against analytic truth: the contract's NRMSE, the Welch spectrum of a
// sinusoid (line position and Parseval), the strongest line, the correlation of a delayed
// copy; the replay of an unchanged nominal record reproduces it; audit.json has the
// contract's keys; bad experiments are refused clearly.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "audit_cases.hpp"
#include "core/error.hpp"
#include "diagnostics/audit.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::diag {
namespace audit_metrics_test {

using ::testing::HasSubstr;
constexpr double kPi = std::numbers::pi;

TEST(AuditMetrics, NrmseIsTheContractDefinition) {
  Eigen::MatrixXd measured(4, 1), model(4, 1);
  measured << 1, 2, 3, 6;  // mean 3, ||y - mean|| = sqrt(4 + 1 + 0 + 9)
  model << 1, 2, 4, 6;     // error norm 1
  EXPECT_DOUBLE_EQ(nrmse(measured, model, {0, 4})[0], 1.0 / std::sqrt(14.0));
  EXPECT_DOUBLE_EQ(nrmse(measured, model, {2, 4})[0], 1.0 / std::sqrt(4.5));  // segment 3, 6: mean 4.5
  EXPECT_THROW(nrmse(measured, model, {0, 5}), Error);
  EXPECT_THROW(nrmse(Eigen::MatrixXd::Ones(4, 1), model, {0, 4}), InsufficientData);
}

// A sample where a controller clamp acted counts neither in the error nor in the spread.
TEST(AuditMetrics, NrmseLeavesOutTheClampedSamples) {
  Eigen::MatrixXd measured(6, 1), model(6, 1);
  measured << 1, 2, 50, 3, 6, -40;
  model << 1, 2, 0, 4, 6, 7;
  Segment segment{0, 6};
  segment.left_out = {false, false, true, false, false, true};
  EXPECT_DOUBLE_EQ(nrmse(measured, model, segment)[0], 1.0 / std::sqrt(14.0));  // the case above
  segment.left_out = {true, true, true, true, true, false};
  EXPECT_THROW(nrmse(measured, model, segment), InsufficientData);
}

TEST(AuditMetrics, WelchSpectrumOfASineHasItsLineAndPower) {
  const double dt = 1e-3, f = 125.0, amplitude = 2.0;  // f on a bin of the 512-sample window
  Eigen::VectorXd s(8192);
  for (Eigen::Index k = 0; k < s.size(); ++k) s[k] = amplitude * std::sin(2 * kPi * f * double(k) * dt);
  const Spectrum p = welch_spectrum(s, dt, 512);
  Eigen::Index peak = 0;
  p.power.col(0).maxCoeff(&peak);
  EXPECT_DOUBLE_EQ(p.frequency[peak], f);
  const double bin = p.frequency[1];
  EXPECT_NEAR(p.power.col(0).sum() * bin, amplitude * amplitude / 2, 0.01 * amplitude * amplitude / 2);  // Parseval
  const Line line = strongest_line(s, dt, 10.0, 400.0);
  EXPECT_NEAR(line.frequency, f, 0.05);
  EXPECT_NEAR(line.amplitude, amplitude, 0.02 * amplitude);
  EXPECT_THROW(welch_spectrum(s.head(100), dt, 512), Error);
}

TEST(AuditMetrics, CorrelationFindsADelayedCopy) {
  Eigen::VectorXd r = Eigen::VectorXd::Random(2000), e = Eigen::VectorXd::Zero(2000);
  e.tail(1993) = 3.0 * r.head(1993);
  EXPECT_GT(excitation_correlation(e, r, 10), 0.99);
  EXPECT_LT(excitation_correlation(e, r, 5), 0.1);  // the lag is beyond the window
}

TEST(AuditReplay, ANoiseFreeNominalRecordReplaysToItself) {
  sim::ScenarioOptions o;
  o.duration = 0.2;
  o.amplitude = 0.3;
  const Experiment e = sim::simulate_scenario(o);
  const Eigen::MatrixXd y = replay_outputs(e, {}, e.samples());
  ASSERT_EQ(y.rows(), e.samples());
  EXPECT_LT((y - e.y_deviation()).cwiseAbs().maxCoeff(), 1e-15);
  // A replay with an effect is a different record.
  EXPECT_GT(nrmse(e.y_deviation(), replay_outputs(e, {sim::make_effect("sensor_gain", {{"dgain", 0.1}})}, e.samples()),
                  {0, e.samples()})[0],
            0.01);
}

TEST(AuditJson, HasTheKeysOfTheContract) {
  const sim::Effect truth = testing::draw_effect("sensor_gain", 9);
  const AuditResult r = run_audit(testing::simulate_hidden(truth, 0.4, 9));
  const nlohmann::json j = audit_json(r, "run.json", "model-extended.json");
  EXPECT_EQ(j["format"], "ambid-audit/1");
  EXPECT_EQ(j["experiment"], "run.json");
  for (const char* y : {"x", "i1", "i2"}) EXPECT_TRUE(j["baseline"]["nrmse"].contains(y)) << y;
  EXPECT_DOUBLE_EQ(j["baseline"]["nrmse_total"].get<double>(), r.baseline_nrmse.mean());
  EXPECT_EQ(j["cause"], "sensor_gain");
  ASSERT_FALSE(j["findings"].empty());
  const auto& f = j["findings"][0];
  EXPECT_EQ(f["effect"], "sensor_gain");
  EXPECT_TRUE(f["channel"].is_null());
  EXPECT_TRUE(f["parameters"].contains("dgain"));
  EXPECT_LT(f["nrmse_total_after"].get<double>(), f["nrmse_total_before"].get<double>());
  EXPECT_FALSE(f["evidence"].get<std::string>().empty());
  EXPECT_EQ(j["extended_model"], "model-extended.json");
  // Additive keys: the acceptance rule, each finding's significance, the FRF ratio, the
  // residual-excitation correlation and the amplitude dependence.
  EXPECT_DOUBLE_EQ(j["acceptance"]["false_acceptance_probability"].get<double>(), 0.01);
  EXPECT_GT(f["significance"]["z"].get<double>(), j["acceptance"]["z_threshold"].get<double>());
  ASSERT_TRUE(j["frf_ratio"].is_object());
  const auto lines = j["frf_ratio"]["nominal"]["i1/u1"]["frequency_hz"].size();
  EXPECT_GT(lines, 5u);
  EXPECT_EQ(j["frf_ratio"]["nominal"]["i1/u1"]["magnitude"].size(), lines);
  EXPECT_EQ(j["frf_ratio"]["extended"]["i2/u2"]["phase_deg"].size(),
            j["frf_ratio"]["extended"]["i2/u2"]["frequency_hz"].size());
  EXPECT_GE(j["residual_excitation_correlation"]["x"]["r1"].get<double>(), 0.0);
  EXPECT_FALSE(j["amplitude_dependence"]["determinable"].get<bool>());  // one PRBS level
  EXPECT_FALSE(j["amplitude_dependence"]["reason"].get<std::string>().empty());
  const nlohmann::json model = extended_model_json(testing::simulate_hidden(truth, 0.4, 9), r);
  EXPECT_EQ(model["effects"][0]["effect"], "sensor_gain");
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// x_meas = (1 + dgain) x with the plant itself unchanged: the indirect estimate of the
// measured plant is the nominal one with its position row scaled by 1 + dgain, the current rows
// unchanged, at every frequency; with the true effect in the model the ratio is 1.
TEST(AuditFrf, SensorGainScalesThePositionRowOfTheRatio) {
  const double dgain = 0.1;
  const sim::Effect truth = sim::make_effect("sensor_gain", {{"dgain", dgain}});
  const Experiment e = testing::simulate_hidden(truth, 1.0, 12);
  const Segment validation{e.samples() / 2, e.samples()};
  const AuditFrfs f = audit_frfs(e, replay_loop(e, {}, e.samples()), replay_loop(e, {truth}, e.samples()), validation);
  ASSERT_GT(f.ratio_nominal.lines(), 20);
  auto stat = [&](const ident::Frf& q, Eigen::Index i, Eigen::Index j, bool phase) {
    std::vector<double> v;
    for (Eigen::Index k : determined_lines(f, i, j)) {
      const auto z = q.value[std::size_t(k)](i, j);
      v.push_back(phase ? std::arg(z) * 180.0 / kPi : std::abs(z));
    }
    EXPECT_GE(v.size(), 10u) << i << "/" << j;
    return v.empty() ? 0.0 : median(v);
  };
  for (Eigen::Index j = 0; j < 2; ++j) {
    EXPECT_NEAR(stat(f.ratio_nominal, 0, j, false), 1.0 + dgain, 0.02) << "x/u" << j + 1;
    EXPECT_NEAR(stat(f.ratio_nominal, 0, j, true), 0.0, 2.0) << "x/u" << j + 1;
    EXPECT_NEAR(stat(f.ratio_nominal, 1 + j, j, false), 1.0, 0.02) << "i/u" << j + 1;
    EXPECT_NEAR(stat(f.ratio_extended, 0, j, false), 1.0, 0.02) << "x/u" << j + 1;
  }
  EXPECT_EQ(f.loop_measured.lines(), f.loop_nominal.lines());
}

TEST(AuditInput, RefusesWhatItCannotReplay) {
  Experiment e = testing::simulate_hidden({}, 0.05, 1);
  Experiment no_r = e;
  no_r.r_names.clear();
  no_r.r.resize(0, 0);
  EXPECT_THAT([&] { run_audit(no_r); }, ::testing::ThrowsMessage<InsufficientData>(HasSubstr("no excitation")));
  Experiment no_controller = e;
  no_controller.controller.reset();
  EXPECT_THAT([&] { run_audit(no_controller); }, ::testing::ThrowsMessage<Error>(HasSubstr("no controller")));
  Experiment other = e;
  other.plant.model = "lamstf";
  EXPECT_THAT([&] { run_audit(other); }, ::testing::ThrowsMessage<Error>(HasSubstr("lamstf")));
  AuditOptions bad;
  bad.estimation_fraction = 1.5;
  EXPECT_THAT([&] { run_audit(e, bad); }, ::testing::ThrowsMessage<Error>(HasSubstr("estimation_fraction")));
}

}  // namespace audit_metrics_test
}  // namespace ambid::diag
