// Samples where a controller clamp acted are not exogenous (experiment-format.md): on a loop
// whose output clamps act (the LAMSTF loop of plant_sim/lamstf_scenario.hpp with its coil
// currents clamped; the runner records the commanded u and applies the clamped one),
// identify_experiment leaves them out and stays near the truth, while the same record with the
// limits removed from its sidecar (so nothing marks the clamped samples) is biased. Measured
// (seed 21, 176 of 8000 samples clamped): closed-loop 0.38 % left out, 1.70 % kept; okid and
// projection 0.40 % and 1.59 %.
//
// Truth: the analytical model sampled by zero-order hold; error (seed 002, 4.36): mean over
// j = 0..29 of ||C A^j B - Chat Ahat^j Bhat||_2 / ||C A^j B||_2, percent.
#include <algorithm>
#include <iostream>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <numeric>

#include "amb1dof_truth.hpp"
#include "core/controller_replay.hpp"
#include "identifier/identify_experiment.hpp"
#include "identifier/time_domain/markov.hpp"
#include "plant_sim/families.hpp"
#include "plant_sim/lamstf.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::ident {
namespace clamped_samples_test {

// Mean (4.36) error of the first 30 Markov parameters C A^j B, percent.
double markov_error_percent(const DiscreteSystem& truth, const DiscreteSystem& model) {
  const std::vector<double> e =
      markov_errors_percent(markov_parameters(truth, 30), markov_parameters(model, 30), 1, 30);
  return std::accumulate(e.begin(), e.end(), 0.0) / double(e.size());
}

// The share of the samples whose command is beyond the amplifier limit in the pem test (before
// the clamp acts) and the worst v error pem must stay below.
constexpr double kPemClampedShare = 0.02;
constexpr double kPemLeftOutBound = 0.01;

Experiment clamped_loop() {
  sim::ScenarioOptions o = sim::plant_family("lamstf", "test").default_options();
  o.seed = 21;
  // A; the commanded currents have an rms near 1.5 A. Lower limits act more often and the
  // loop, whose observer reads the commanded u, loses this strongly unstable plant (4 A: at 22 s).
  o.input_limit = 4.5;
  return sim::simulate_scenario(o);
}

TEST(ClampedSamples, LeftOutOfTheArxMethodsWhichStayNearTheTruth) {
  const Experiment clamped = clamped_loop();
  const ControllerReplay mask = clamped_samples(clamped);
  const double fraction = double(mask.clamped_samples) / double(clamped.samples());
  std::cout << "clamped samples: " << mask.clamped_samples << " of " << clamped.samples() << "\n";
  ASSERT_GT(fraction, 0.01);  // the clamps act ...
  ASSERT_LT(fraction, 0.15);  // ... but leave most of the record
  Experiment unmarked = clamped;
  unmarked.controller->output_limits.clear();
  const DiscreteSystem truth = c2d_zoh(sim::lamstf().system, clamped.sample_time);
  for (const std::string method : {"closed-loop", "okid", "projection"}) {
    IdentifyOptions o;
    o.method = method;
    o.arx_order = 7;
    const Model left_out = identify_experiment(clamped, o);
    const Model kept = identify_experiment(unmarked, o);
    const double e_left_out = markov_error_percent(truth, left_out.discrete);
    const double e_kept = markov_error_percent(truth, kept.discrete);
    std::cout << method << ": Markov error " << e_left_out << " % with the clamped samples left out, " << e_kept
              << " % with them in the fit\n";
    ::testing::Test::RecordProperty(method + "_error_left_out_percent", std::to_string(e_left_out));
    ::testing::Test::RecordProperty(method + "_error_kept_percent", std::to_string(e_kept));
    // Table 4.1's 0.684 % at this noise level (0.5 %), with room for the rows the clamps cost.
    EXPECT_LT(e_left_out, 1.0) << method;
    EXPECT_GT(e_kept, 3.0 * e_left_out) << method;
    const nlohmann::json& report = left_out.extra.json().at("clamped_samples");
    EXPECT_GT(report.at("fit_window").get<int>(), 0);
    EXPECT_GT(report.at("validation").get<int>(), 0);
    EXPECT_EQ(report.at("fit_window").get<int>() + report.at("validation").get<int>(), mask.clamped_samples);
    EXPECT_EQ(kept.extra.json().at("clamped_samples").at("fit_window").get<int>(), 0);
  }
}

// deadbeat runs its regression over contiguous samples: it is fitted on the longest stretch of
// the fit window (the first 75 %) without a clamp, and says so. amb1dof_voltage with its
// amplifier commands clamped at 8.85 V (the operating point is 8.75 V).
TEST(ClampedSamples, MethodsThatCannotSkipSamplesFitTheLongestStretchWithoutOne) {
  sim::ScenarioOptions o;
  o.duration = 1.0;
  o.seed = 3;
  o.input_limit = 8.85;
  const Experiment e = sim::simulate_scenario(o);
  const Eigen::Index fit_end = e.samples() - Eigen::Index(0.25 * double(e.samples()));
  const std::vector<bool> clamped = clamped_samples(e).clamped;
  Eigen::Index longest = 0, run = 0, in_fit = 0;
  for (Eigen::Index k = 0; k < fit_end; ++k) {
    run = clamped[std::size_t(k)] ? 0 : run + 1;
    longest = std::max(longest, run);
    in_fit += clamped[std::size_t(k)] ? 1 : 0;
  }
  ASSERT_GT(in_fit, 0);
  ASSERT_LT(longest, fit_end);
  IdentifyOptions io;
  io.method = "deadbeat";
  const Model m = identify_experiment(e, io);
  EXPECT_EQ(m.extra.json().at("samples").at("fit").get<Eigen::Index>(), longest);
  EXPECT_EQ(m.extra.json().at("clamped_samples").at("fit_window").get<Eigen::Index>(), in_fit);
  const std::string handling = m.extra.json().at("clamped_samples").at("fit").get<std::string>();
  EXPECT_NE(handling.find("method 'deadbeat' cannot leave single samples out: fitted on the longest stretch"),
            std::string::npos)
      << handling;
  std::cout << "deadbeat: " << in_fit << " clamped samples in the fit window of " << fit_end << "; fitted on "
            << longest << "; v1 = " << m.parameters.at("v1") << "\n";
}

// pem leaves out of its cost the prediction error of every sample whose one-step prediction
// used a clamped input (the recorded u, the command, is not what the amplifier delivered) and
// drives its predictor with the clamped input, as replay applies it. Measured: 201 clamped
// samples of 10000, worst v error 0.49 % with them handled, 2.80 % without (limits removed
// from the sidecar); masking alone (the command driving the predictor) gave 2.49 %.
// amb1dof_voltage at 0.1 um / 0.1 mA (PRBS 0.5 V) with its amplifier commands clamped at the
// level the unclamped loop's larger command exceeds in kPemClampedShare of its samples. Against the true v1..v9
// (amb1dof_truth.hpp), with the clamped samples left out and with the limits removed from the sidecar (nothing marks
// them: every wrong u is in the cost).
TEST(ClampedSamples, PemLeavesThePredictionsFromClampedInputsOutOfItsCost) {
  sim::ScenarioOptions o;
  o.duration = 1.0;
  o.amplitude = 0.5;
  o.seed = 3;
  o.position_noise = 1e-7;
  o.current_noise = 1e-4;
  {  // the limit: the kPemClampedShare quantile of the larger command of the unclamped loop
    const Experiment free = sim::simulate_scenario(o);
    std::vector<double> larger(std::size_t(free.samples()));
    for (Eigen::Index k = 0; k < free.samples(); ++k) larger[std::size_t(k)] = free.u.row(k).maxCoeff();
    const auto at = larger.begin() + std::ptrdiff_t((1.0 - kPemClampedShare) * double(larger.size()));
    std::nth_element(larger.begin(), at, larger.end());
    o.input_limit = *at;
  }
  const Experiment e = sim::simulate_scenario(o);
  const std::map<std::string, double> truth = testing::true_structure(o);
  IdentifyOptions io;
  io.method = "pem";
  io.validation_fraction = 0.0;
  const std::vector<bool> clamped = clamped_samples(e).clamped;
  const Eigen::Index count = std::count(clamped.begin(), clamped.end() - 1, true);  // the last one predicts nothing
  ASSERT_GT(count, 0);
  Experiment unmarked = e;
  unmarked.controller->output_limits.clear();
  auto worst = [&](const Model& m) {
    double w = 0.0;
    for (const auto& [name, value] : truth) w = std::max(w, std::abs(m.parameters.at(name) / value - 1.0));
    return w;
  };
  const Model left_out = identify_experiment(e, io);
  const Model kept = identify_experiment(unmarked, io);
  const double e_left_out = worst(left_out), e_kept = worst(kept);
  std::cout << "pem: " << count << " clamped samples of " << e.samples() << "; worst v error " << 100.0 * e_left_out
            << " % with them handled, " << 100.0 * e_kept << " % with the limits removed\n";
  RecordProperty("pem_clamped_samples", std::to_string(count));
  RecordProperty("pem_worst_v_error_left_out", std::to_string(e_left_out));
  RecordProperty("pem_worst_v_error_kept", std::to_string(e_kept));
  EXPECT_EQ(left_out.extra.json().at("pem").at("scored_samples").get<Eigen::Index>(), e.samples() - count);
  EXPECT_EQ(kept.extra.json().at("pem").at("scored_samples").get<Eigen::Index>(), e.samples());
  EXPECT_EQ(left_out.extra.json().at("samples").at("fit").get<Eigen::Index>(), e.samples());  // not a stretch
  EXPECT_NE(left_out.extra.json().at("clamped_samples").at("fit").get<std::string>().find("prediction-error cost"),
            std::string::npos);
  EXPECT_LT(e_left_out, kPemLeftOutBound);
  EXPECT_GT(e_kept, 3.0 * e_left_out);
}

}  // namespace clamped_samples_test
}  // namespace ambid::ident
