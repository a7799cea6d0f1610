// The prediction-error method (`pem`, amb1dof_prediction_error.hpp) on the NONLINEAR
// amb1dof_voltage closed loop with realistic sensor noise: seed 000 examples I-III within the
// paper's 0.64 %, where plain least squares is biased by the noise the controller feeds back;
// its sigmas; and the data it must refuse.
//
// Truth (amb1dof_truth.hpp): seed 000 eq. (4) of the true parameters where the loop settles.
#include "identifier/families/amb1dof_prediction_error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "amb1dof_truth.hpp"
#include "core/error.hpp"
#include "identifier/identify_experiment.hpp"
#include "identifier/time_domain/loop_signals.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace {

// Position noise 1e-7 m rms, current noise 1e-4 A rms (a realistic AMB's sensors); PRBS of
// kAmplitude V on both inputs (x about 0.45 um rms in the 350 um gap; the nonlinearity alone
// moves v1 by ~0.1 % at this level). 2.5 s: 1.8 s fitted after the settling and the 25 %
// validation.
constexpr double kPositionNoise = 1e-7, kCurrentNoise = 1e-4, kAmplitude = 1.5, kDuration = 2.5;

sim::ScenarioOptions noisy_scenario(const std::string& parameter, double factor, std::uint64_t seed) {
  sim::ScenarioOptions s;
  s.duration = kDuration;
  s.amplitude = kAmplitude;
  s.position_noise = kPositionNoise;
  s.current_noise = kCurrentNoise;
  s.seed = seed;
  if (!parameter.empty())
    s.true_parameters[parameter] = factor * sim::Amb1dofParameters::nominal().to_map().at(parameter);
  return s;
}

Model identify(const Experiment& e, const std::string& method) {
  IdentifyOptions o;
  o.method = method;
  o.skip_samples = 1000;  // the settling to the true operating point
  return identify_experiment(e, o);
}

// Every v within `tolerance` of the truth except `changed`, which must move by +20 % +- 1 %
// against the nominal; and every error within 4.5 reported sigmas.
void check_example(const std::string& parameter, const std::string& changed, double tolerance) {
  SCOPED_TRACE(parameter.empty() ? "nominal" : parameter + " +20 %");
  const sim::ScenarioOptions scenario = noisy_scenario(parameter, 1.2, 11);
  sim::ScenarioOptions settle = scenario;
  settle.duration = 1.0;  // long enough to settle at the true operating point
  const auto truth = testing::true_structure(settle);
  const auto nominal = sim::amb1dof_structure_parameters(sim::Amb1dofParameters::nominal());
  const Model m = identify(sim::simulate_scenario(scenario), "pem");
  const std::string tag = parameter.empty() ? "nominal" : parameter;
  for (const auto& [name, value] : truth) {
    const double error = m.parameters.at(name) / value - 1.0;
    const double sigma = m.uncertainty.at(name) / value;
    ::testing::Test::RecordProperty(tag + "_" + name + "_error", testing::sci(error));
    ::testing::Test::RecordProperty(tag + "_" + name + "_sigma", testing::sci(sigma));
    if (name == changed)
      EXPECT_NEAR(m.parameters.at(name) / nominal.at(name) - 1.0, 0.2, 0.01) << name;
    else
      EXPECT_NEAR(error, 0.0, tolerance) << name;
    EXPECT_LT(std::abs(error), 4.5 * sigma + 1e-4) << name << ": error beyond its reported sigma";
  }
  for (const auto& [name, value] : m.physical) EXPECT_GT(m.uncertainty.at(name), 0.0) << name;
}

TEST(Amb1dofPredictionError, NominalWithinTheSeed000AccuracyUnderRealisticNoise) { check_example("", "", 0.0064); }

TEST(Amb1dofPredictionError, CoilResistanceChangeUnderRealisticNoise) { check_example("R1", "v5", 0.0064); }

TEST(Amb1dofPredictionError, AmplifierGainChangeUnderRealisticNoise) { check_example("kw1", "v8", 0.0064); }

TEST(Amb1dofPredictionError, LeastSquaresIsBiasedOnTheSameData) {
  // The bias the prediction-error method removes: deadbeat (least squares) on the same record.
  const sim::ScenarioOptions scenario = noisy_scenario("", 1.0, 11);
  const auto truth = testing::true_structure(scenario);
  const Model m = identify(sim::simulate_scenario(scenario), "deadbeat");
  double worst = 0.0;
  for (const auto& [name, value] : truth) worst = std::max(worst, std::abs(m.parameters.at(name) / value - 1.0));
  ::testing::Test::RecordProperty("deadbeat_worst_error", testing::sci(worst));
  EXPECT_GT(worst, 0.05);
}

struct Direct {
  Eigen::MatrixXd y, u, r;
  Eigen::Matrix<double, 9, 1> v;
};

Direct direct_inputs(const Experiment& e) {
  const LoopSignals s = loop_signals(e, {"x", "i1", "i2"}, {"u1", "u2"}, "test");
  Direct d{s.y, s.u, s.r, {}};
  const auto v = sim::amb1dof_structure_parameters(sim::Amb1dofParameters::nominal());
  for (int i = 0; i < 9; ++i) d.v(i) = v.at("v" + std::to_string(i + 1));
  return d;
}

TEST(Amb1dofPredictionError, UnexcitedLoopIsRefused) {
  // Noise only, no excitation: nothing drives the simulated loop but its free offsets and
  // initial state, which could fit v to noise; refused before any fit.
  sim::ScenarioOptions s = noisy_scenario("", 1.0, 3);
  s.excitation = "none";
  s.duration = 0.3;
  const Direct d = direct_inputs(sim::simulate_scenario(s));
  EXPECT_THROW(fit_amb1dof_prediction_error(d.y, d.u, d.r, 1e-4, {d.v}), InsufficientData);
}

TEST(Amb1dofPredictionError, TooShortRecordAndBadInputsAreRefused) {
  sim::ScenarioOptions s = noisy_scenario("", 1.0, 3);
  s.duration = 0.1;  // 1000 samples < 10 blocks of 200
  const Direct d = direct_inputs(sim::simulate_scenario(s));
  try {
    fit_amb1dof_prediction_error(d.y, d.u, d.r, 1e-4, {d.v});
    ADD_FAILURE() << "identified from 1000 samples";
  } catch (const InsufficientData& e) {
    EXPECT_NE(std::string(e.what()).find("1000 samples"), std::string::npos) << e.what();
  }
  Eigen::Matrix<double, 9, 1> zero = d.v;
  zero(3) = 0.0;
  EXPECT_THROW(fit_amb1dof_prediction_error(d.y, d.u, d.r, 1e-4, {zero}), Error);
  EXPECT_THROW(fit_amb1dof_prediction_error(d.y.leftCols(2), d.u, d.r, 1e-4, {d.v}), Error);
}

}  // namespace
}  // namespace ambid::ident
