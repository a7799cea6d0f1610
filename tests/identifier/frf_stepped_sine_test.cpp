// The stepped-sine estimator on the unstable Sales rotor (seed 003 eq. 8) under its filtered
// PD controller: plant_sim's stepped sine as the reference, each step's window analysed by an
// exact DFT; truth is the ZOH model of the plant. Also through analyse_frf from an experiment
// whose sidecar describes the steps, and the refusals.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <complex>

#include "core/error.hpp"
#include "frf_test_helpers.hpp"
#include "identifier/frequency_domain/freq_response.hpp"
#include "identifier/frequency_domain/frf_stepped_sine.hpp"
#include "identifier/frf_analysis.hpp"
#include "plant_sim/excitation.hpp"

namespace ambid::ident {
namespace frf_stepped_sine_test {

using test::kPi;

constexpr double kT = 1e-4;

sim::Excitation sales_stepped_sine() {
  sim::SteppedSineOptions s;
  for (double f = 5.0; f <= 1000.0; f *= std::pow(10.0, 0.2)) s.frequencies.push_back(f);
  s.amplitude = 0.5;
  s.settle_time = 0.2;  // with 0.05 s the previous step's transient leaves 0.14 % errors
  s.measure_periods = 10;
  return sim::stepped_sine(s, kT);
}

SteppedSineFrfOptions options_from(const nlohmann::json& description) {
  SteppedSineFrfOptions o;
  o.sample_time = kT;
  for (const auto& step : description["steps"])
    o.steps.push_back({step["measure_start_sample"].get<Eigen::Index>(), step["measure_samples"].get<Eigen::Index>(),
                       description["measure_periods"].get<Eigen::Index>()});
  return o;
}

class SalesSteppedSine : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_LT(test::closed_loop_radius(plant, controller), 0.999);
    data = test::simulate_loop(plant, controller, test::sales_signals(), excitation.samples);
  }
  DiscreteSystem plant = c2d_zoh(test::sales_rotor_system(), kT);
  StateSpaceController controller = test::sales_pd_controller(kT);
  sim::Excitation excitation = sales_stepped_sine();
  test::LoopData data;
};

TEST_F(SalesSteppedSine, EachStepGivesTheOpenLoopPlant) {
  const SteppedSineFrf e =
      estimate_stepped_sine_frf(excitation.samples, data.u, data.y, options_from(excitation.description.json()));
  ASSERT_EQ(e.plant.lines(), static_cast<Eigen::Index>(excitation.description.json()["steps"].size()));
  double worst = 0.0;
  for (Eigen::Index l = 0; l < e.plant.lines(); ++l) {
    const double f = e.plant.frequency_hz(l);
    const std::complex<double> G0 = freq_response(plant, 2.0 * kPi * f)(0, 0);
    worst = std::max(worst, std::abs(e.plant.value[static_cast<std::size_t>(l)](0, 0) / G0 - 1.0));
  }
  RecordProperty("stepped_sine_worst_relative_error", test::scientific(worst));
  EXPECT_LT(worst, 1e-6);
  // Noise-free, the open-loop formula agrees with the indirect estimate.
  EXPECT_LT(std::abs(e.plant_direct.value[3](0, 0) / e.plant.value[3](0, 0) - 1.0), 1e-9);
  EXPECT_NEAR(e.plant.frequency_hz(0), 5.0, 0.01);
}

TEST_F(SalesSteppedSine, AnalyseFrfUsesTheStepsOfTheDescription) {
  Experiment x;
  x.name = "sales stepped sine";
  x.plant.model = "sales_rotor";
  x.sample_time = kT;
  x.y_names = {"y"};
  x.u_names = {"u"};
  x.r_names = {"r"};
  x.operating_point = {{"y", 0.0}, {"u", 0.0}};
  x.controller = controller;
  const Eigen::Index n = excitation.samples.rows();
  x.t = Eigen::VectorXd::LinSpaced(n, 0.0, static_cast<double>(n - 1) * kT);
  x.y = data.y;
  x.u = data.u;
  x.r = excitation.samples;
  x.extra.json() = {{"excitation", excitation.description.json()}};
  FrfAnalysisOptions o;
  o.fit = false;
  const FrfReport report = analyse_frf(x, o);
  EXPECT_EQ(report.method, "stepped_sine");
  ASSERT_EQ(report.pairs.size(), 1u);
  EXPECT_EQ(report.pairs[0].name, "y/u");
  const std::complex<double> G0 = freq_response(plant, 2.0 * kPi * report.frequency_hz(5))(0, 0);
  EXPECT_LT(std::abs(report.pairs[0].value(5) / G0 - 1.0), 1e-3);
  ASSERT_EQ(report.sensitivity_peaks.size(), 2u);  // "u" and sigma_max
}

TEST_F(SalesSteppedSine, Refusals) {
  SteppedSineFrfOptions o = options_from(excitation.description.json());
  const Eigen::MatrixXd two(excitation.samples.rows(), 2);
  EXPECT_THROW(estimate_stepped_sine_frf(two, data.u, data.y, o), InsufficientData);
  o.steps.back().measure_start = excitation.samples.rows();
  EXPECT_THROW(estimate_stepped_sine_frf(excitation.samples, data.u, data.y, o), Error);
  o = options_from(excitation.description.json());
  o.steps[1].cycles = o.steps[1].measure_samples;  // above Nyquist
  EXPECT_THROW(estimate_stepped_sine_frf(excitation.samples, data.u, data.y, o), Error);
  o = options_from(excitation.description.json());
  o.f_min = 2000.0;
  EXPECT_THROW(estimate_stepped_sine_frf(excitation.samples, data.u, data.y, o), InsufficientData);
  const Eigen::MatrixXd silent = Eigen::MatrixXd::Zero(excitation.samples.rows(), 1);
  EXPECT_THROW(estimate_stepped_sine_frf(silent, data.u, data.y, options_from(excitation.description.json())),
               InsufficientData);
}

}  // namespace frf_stepped_sine_test
}  // namespace ambid::ident
