// `ambid frf`'s entry point on simulated bearing experiments (plant_sim's scenario: the
// nonlinear amb1dof_voltage plant under the LQR observer controller): the estimator is chosen
// from the sidecar's excitation description, the plant FRF matches the linearised plant, the
// sensitivity peaks and zones, the controller check and the fitted unstable pole are reported.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include "core/error.hpp"
#include "frf_test_helpers.hpp"
#include "identifier/frequency_domain/freq_response.hpp"
#include "identifier/frequency_domain/frf_grey_box.hpp"
#include "identifier/frequency_domain/sensitivity_function.hpp"
#include "identifier/frf_analysis.hpp"
#include "plant_sim/amb1dof_physical.hpp"
#include "plant_sim/amb1dof_voltage.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::ident {
namespace frf_analysis_test {

using test::kPi;

DiscreteSystem linear_bearing(double T) { return c2d_zoh(sim::Amb1dofVoltage().linearize(), T); }

double unstable_pole_of_linear_bearing() {
  const Eigen::VectorXcd p = poles(sim::Amb1dofVoltage().linearize());
  double best = 0.0;
  for (Eigen::Index i = 0; i < p.size(); ++i) best = std::max(best, p(i).real());
  return best;
}

class BearingMultisine : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    sim::ScenarioOptions s;
    s.excitation = "multisine";
    s.duration = 7.0;  // 1 s periods, Hadamard blocks of 2: 6 periods, 1 discarded, 2 blocks
    s.f_min = 1.0;
    s.f_max = 1000.0;
    s.amplitude = 0.05;
    s.seed = 3;
    experiment = new Experiment(sim::simulate_scenario(s));
    report = new FrfReport(analyse_frf(*experiment));
  }
  static void TearDownTestSuite() {
    delete report;
    delete experiment;
  }
  static Experiment* experiment;
  static FrfReport* report;
};
Experiment* BearingMultisine::experiment = nullptr;
FrfReport* BearingMultisine::report = nullptr;

TEST_F(BearingMultisine, ChoosesThePeriodicEstimatorAndNamesThePairs) {
  EXPECT_EQ(report->method, "periodic");
  EXPECT_EQ(report->excitation, "multisine");
  EXPECT_EQ(report->blocks, 2);
  ASSERT_EQ(report->pairs.size(), 6u);
  EXPECT_EQ(report->pairs[0].name, "x/u1");
  EXPECT_EQ(report->pairs[5].name, "i2/u2");
  EXPECT_EQ(report->frequency_hz.size(), 1000);
  EXPECT_NEAR(report->frequency_hz(0), 1.0, 1e-12);
  EXPECT_EQ(report->pairs[0].bound.size(), 1000);  // two blocks: bounds exist
}

TEST_F(BearingMultisine, PlantMatchesTheLinearisedBearing) {
  const DiscreteSystem truth = linear_bearing(experiment->sample_time);
  std::vector<double> err;
  double worst_mag = 0.0, worst_phase = 0.0;
  for (Eigen::Index l = 0; l < report->frequency_hz.size(); ++l) {
    const double f = report->frequency_hz(l);
    const Eigen::MatrixXcd G0 = freq_response(truth, 2.0 * kPi * f);
    const Eigen::MatrixXcd& G = report->plant.value[static_cast<std::size_t>(l)];
    err.push_back((G - G0).norm() / G0.norm());
    // x/u1 magnitude and phase
    worst_mag = std::max(worst_mag, std::abs(std::abs(G(0, 0)) / std::abs(G0(0, 0)) - 1.0));
    worst_phase = std::max(worst_phase, std::abs(test::phase_error_deg(G(0, 0), G0(0, 0))));
  }
  std::sort(err.begin(), err.end());
  RecordProperty("bearing_median_error", std::to_string(err[err.size() / 2]));
  RecordProperty("bearing_worst_error", std::to_string(err.back()));
  RecordProperty("bearing_x_u1_worst_magnitude", std::to_string(worst_mag));
  RecordProperty("bearing_x_u1_worst_phase_deg", std::to_string(worst_phase));
  EXPECT_LT(err[err.size() / 2], 1e-3);
  EXPECT_LT(worst_mag, 0.01);
  EXPECT_LT(worst_phase, 1.0);
}

TEST_F(BearingMultisine, SensitivityPeaksAndControllerCheck) {
  ASSERT_TRUE(report->sensitivity.has_value());
  ASSERT_EQ(report->sensitivity_peaks.size(), 3u);
  EXPECT_EQ(report->sensitivity_peaks[0].loop, "u1");
  EXPECT_EQ(report->sensitivity_peaks[2].loop, "sigma_max");
  // The model's sensitivity on the same lines.
  const LoopSignalNames signals{experiment->y_names, experiment->u_names, experiment->r_names};
  const Frf S0 = input_sensitivity(linear_bearing(experiment->sample_time), *experiment->controller, signals,
                                   report->frequency_hz);
  const auto model_peaks = sensitivity_peaks(S0, experiment->u_names);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(report->sensitivity_peaks[i].magnitude_db, model_peaks[i].magnitude_db, 0.1) << i;
    EXPECT_EQ(report->sensitivity_peaks[i].zone, iso14839_zone(model_peaks[i].magnitude_db));
    RecordProperty("peak_db_" + report->sensitivity_peaks[i].loop,
                   std::to_string(report->sensitivity_peaks[i].magnitude_db));
  }
  ASSERT_TRUE(report->controller_check.has_value());
  std::vector<double> e(
      report->controller_check->relative_error.data(),
      report->controller_check->relative_error.data() + report->controller_check->relative_error.size());
  std::sort(e.begin(), e.end());
  EXPECT_LT(e[e.size() / 2], 1e-3);
}

TEST_F(BearingMultisine, FitFindsTheUnstablePole) {
  const auto it =
      std::find_if(report->fits.begin(), report->fits.end(), [](const FittedPair& p) { return p.name == "x/u1"; });
  ASSERT_NE(it, report->fits.end());
  const double truth = unstable_pole_of_linear_bearing();
  const Eigen::VectorXcd p = it->fit.model.poles();
  double found = -1e300;
  for (Eigen::Index i = 0; i < p.size(); ++i)
    if (std::abs(p(i).imag()) < 1e-6 * std::abs(p(i)) && p(i).real() > 0.0) found = std::max(found, p(i).real());
  RecordProperty("bearing_unstable_pole_true", std::to_string(truth));
  RecordProperty("bearing_unstable_pole_fit", std::to_string(found));
  EXPECT_LT(std::abs(found - truth), 0.01 * truth);
}

// v1..v9 of seed 000 eq. 4 by a grey-box fit of the structure to the measured 3x2 FRF.
Eigen::VectorXd structure_vector(const std::map<std::string, double>& v) {
  Eigen::VectorXd out(9);
  for (int k = 0; k < 9; ++k) out(k) = v.at("v" + std::to_string(k + 1));
  return out;
}
ContinuousSystem structure_model(const Eigen::VectorXd& theta) {
  std::map<std::string, double> v;
  for (int k = 0; k < 9; ++k) v["v" + std::to_string(k + 1)] = theta(k);
  return sim::amb1dof_structure_system(v);
}
GreyBoxFit fit_structure(const FrfReport& report, double T) {
  // Start 10-30 % away from the nominal values.
  Eigen::VectorXd start = structure_vector(sim::Amb1dofVoltage().structure_parameters());
  for (int k = 0; k < 9; ++k) start(k) *= 1.0 + 0.1 * (1 + k % 3) * (k % 2 ? -1.0 : 1.0);
  GreyBoxOptions o;
  o.sample_time = T;
  return fit_grey_box(report.plant, structure_model, start, o);
}

TEST_F(BearingMultisine, GreyBoxFitRecoversTheStructureParameters) {
  const GreyBoxFit fit = fit_structure(*report, experiment->sample_time);
  const Eigen::VectorXd truth = structure_vector(sim::Amb1dofVoltage().structure_parameters());
  EXPECT_TRUE(fit.converged);
  const double worst = ((fit.parameters - truth).array() / truth.array()).abs().maxCoeff();
  RecordProperty("grey_box_worst_relative_error", std::to_string(worst));
  EXPECT_LT(worst, 1e-3);
  ASSERT_EQ(fit.standard_deviation.size(), 9);
}

TEST(FrfAnalysis, GreyBoxSeesACoilResistanceFault) {
  // Seed 000 example II: R1 20 % high in the true plant; the sidecar keeps the nominal values.
  sim::ScenarioOptions s;
  s.excitation = "multisine";
  s.duration = 5.0;
  s.f_min = 1.0;
  s.f_max = 500.0;
  s.seed = 9;
  s.true_parameters = {{"R1", 1.2 * sim::Amb1dofParameters::nominal().R1}};
  const Experiment e = sim::simulate_scenario(s);
  FrfAnalysisOptions o;
  o.fit = false;
  const FrfReport rep = analyse_frf(e, o);
  const GreyBoxFit fit = fit_structure(rep, e.sample_time);
  std::map<std::string, double> v;
  for (int k = 0; k < 9; ++k) v["v" + std::to_string(k + 1)] = fit.parameters(k);
  const sim::Amb1dofPhysical phys = sim::amb1dof_physical_from_structure(v, sim::Amb1dofParameters::nominal());
  RecordProperty("R1_identified", std::to_string(phys.R1));
  EXPECT_NEAR(phys.R1 / sim::Amb1dofParameters::nominal().R1, 1.2, 0.005);
  EXPECT_NEAR(phys.R2 / sim::Amb1dofParameters::nominal().R2, 1.0, 0.005);
  EXPECT_NEAR(phys.kw1, 1.0, 0.005);
}

TEST(FrfAnalysis, PrbsScenarioUsesWelch) {
  sim::ScenarioOptions s;
  s.excitation = "prbs";
  s.duration = 4.0;
  s.amplitude = 0.05;
  s.seed = 5;
  const Experiment e = sim::simulate_scenario(s);
  FrfAnalysisOptions o;
  o.fit = false;
  o.f_max = 1000.0;
  const FrfReport rep = analyse_frf(e, o);
  EXPECT_EQ(rep.method, "welch");
  EXPECT_EQ(rep.excitation, "prbs");
  ASSERT_EQ(rep.pairs.size(), 6u);
  EXPECT_EQ(rep.pairs[0].coherence.size(), rep.frequency_hz.size());
  const DiscreteSystem truth = linear_bearing(e.sample_time);
  std::vector<double> err;
  for (Eigen::Index l = 0; l < rep.frequency_hz.size(); ++l) {
    if (rep.frequency_hz(l) < 20.0) continue;
    const Eigen::MatrixXcd G0 = freq_response(truth, 2.0 * kPi * rep.frequency_hz(l));
    err.push_back(std::abs(rep.plant.value[static_cast<std::size_t>(l)](0, 0) / G0(0, 0) - 1.0));
  }
  std::sort(err.begin(), err.end());
  RecordProperty("prbs_x_u1_median_error", std::to_string(err[err.size() / 2]));
  EXPECT_LT(err[err.size() / 2], 0.02);
}

TEST(FrfAnalysis, RefusesAnExperimentWithoutExcitation) {
  sim::ScenarioOptions s;
  s.excitation = "none";
  s.duration = 0.2;
  const Experiment e = sim::simulate_scenario(s);
  EXPECT_THROW(analyse_frf(e), InsufficientData);
}

}  // namespace frf_analysis_test
}  // namespace ambid::ident
