// The open-loop FRF of an unstable plant recovered from noise-free closed-loop data with a
// periodic multisine: the Sales rotor (seed 003 eq. 8) stabilised by a filtered PD controller,
// and a coupled two-axis version identified with an orthogonal (Hadamard) reference pattern.
// Truth: the zero-order-hold model of the plant evaluated at e^{jwT} (what sampled data can
// show; the continuous G(jw) differs by the hold).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include "core/error.hpp"
#include "frf_test_helpers.hpp"
#include "identifier/frequency_domain/freq_response.hpp"
#include "identifier/frequency_domain/frf_open_loop.hpp"
#include "identifier/frequency_domain/frf_periodic.hpp"
#include "identifier/frequency_domain/sensitivity_function.hpp"

namespace ambid::ident {
namespace frf_closed_loop_test {

using test::kPi;

constexpr double kT = 1e-4;        // 10 kHz, as the bearing rigs
constexpr Eigen::Index kN = 2000;  // 0.2 s period: lines every 5 Hz

std::vector<Eigen::Index> lines_up_to(Eigen::Index last, Eigen::Index step = 1) {
  std::vector<Eigen::Index> lines;
  for (Eigen::Index k = 1; k <= last; k += step) lines.push_back(k);
  return lines;
}

class SalesRotorLoop : public ::testing::Test {
 protected:
  void SetUp() override {
    plant = c2d_zoh(test::sales_rotor_system(), kT);
    controller = test::sales_pd_controller(kT);
    ASSERT_LT(test::closed_loop_radius(plant, controller), 0.999);
    lines = lines_up_to(300);  // 5 Hz .. 1.5 kHz
    r = test::multisine(kN, lines, 6, 0.5);
    data = test::simulate_loop(plant, controller, test::sales_signals(), r);
    PeriodicFrfOptions o;
    o.sample_time = kT;
    o.period_samples = kN;
    o.lines = lines;
    o.transient_periods = 2;
    estimate = estimate_periodic_frf(r, data.u, data.y, o);
  }
  std::complex<double> truth(double f) const { return freq_response(plant, 2.0 * kPi * f)(0, 0); }

  DiscreteSystem plant;
  StateSpaceController controller;
  std::vector<Eigen::Index> lines;
  Eigen::MatrixXd r;
  test::LoopData data;
  PeriodicFrf estimate;
};

TEST_F(SalesRotorLoop, OpenLoopFrfFromClosedLoopData) {
  ASSERT_EQ(estimate.blocks, 4);
  ASSERT_EQ(estimate.plant.lines(), 300);
  double worst_mag = 0.0, worst_phase = 0.0, worst_rel = 0.0;
  int checked = 0;
  for (Eigen::Index l = 0; l < estimate.plant.lines(); ++l) {
    const double f = estimate.plant.frequency_hz(l);
    const std::complex<double> g = estimate.plant.value[static_cast<std::size_t>(l)](0, 0), g0 = truth(f);
    // The truth from c2d_zoh agrees with the closed form of the ZOH plant.
    EXPECT_LT(std::abs(g0 / test::sales_rotor_zoh(std::polar(1.0, 2.0 * kPi * f * kT), kT) - 1.0), 1e-9);
    worst_rel = std::max(worst_rel, std::abs(g / g0 - 1.0));
    if (f < 1000.0) {
      ++checked;
      worst_mag = std::max(worst_mag, std::abs(std::abs(g) / std::abs(g0) - 1.0));
      worst_phase = std::max(worst_phase, std::abs(test::phase_error_deg(g, g0)));
    }
  }
  EXPECT_EQ(checked, 199);
  EXPECT_LT(worst_mag, 0.01);   // the brief: 1 % magnitude
  EXPECT_LT(worst_phase, 1.0);  // and 1 degree below 1 kHz
  EXPECT_LT(worst_rel, 1e-7);   // in fact exact up to the transient left after two periods
  // The plant is unstable: at 5 Hz (31 rad/s < 52.9 rad/s) the response is negative real,
  // G ~ 840 / (-(2800 + w^2)) — not what a stable plant at low frequency would show.
  EXPECT_LT(estimate.plant.value[0](0, 0).real(), 0.0);
  EXPECT_NEAR(estimate.plant.value[0](0, 0).real(), 840.0 / (-(2800.0 + std::pow(2.0 * kPi * 5.0, 2))), 2e-3);
}

TEST_F(SalesRotorLoop, DirectEstimateIsUnbiasedWithoutNoise) {
  for (Eigen::Index l = 0; l < estimate.plant.lines(); l += 7) {
    const double f = estimate.plant.frequency_hz(l);
    EXPECT_LT(std::abs(estimate.plant_direct.value[static_cast<std::size_t>(l)](0, 0) / truth(f) - 1.0), 1e-7) << f;
  }
}

TEST_F(SalesRotorLoop, Eq11OpenLoopFromClosedLoopWithKnownController) {
  const Frf G = open_loop_from_closed_loop(estimate.output_from_reference, controller, test::sales_signals());
  for (Eigen::Index l = 0; l < G.lines(); ++l) {
    const double f = G.frequency_hz(l);
    EXPECT_LT(std::abs(G.value[static_cast<std::size_t>(l)](0, 0) / truth(f) - 1.0), 1e-7) << f;
  }
}

TEST_F(SalesRotorLoop, Eq5RecoversTheKnownController) {
  const ControllerCheck check =
      check_controller(estimate.plant, estimate.output_from_reference, controller, test::sales_signals());
  ASSERT_EQ(check.measured.size(), 300u);
  EXPECT_LT(check.relative_error.maxCoeff(), 1e-7);
  // Independent truth: the closed-form ZOH equivalent of the filtered PD,
  // K(z) = -(kp + kd/tau) + (kd/tau) (1 - e^{-T/tau}) / (z - e^{-T/tau}). (Against the continuous
  // K(jw) the difference is 3-9 % already at 5-50 Hz: the proportional part is the small
  // difference of two large terms, -530 + 500/(1 + j w tau), and the hold shifts the second.)
  for (std::size_t l = 0; l < check.measured.size(); ++l) {
    const std::complex<double> z = std::polar(1.0, 2.0 * kPi * check.frequency_hz(static_cast<Eigen::Index>(l)) * kT);
    EXPECT_LT(std::abs(check.measured[l](0, 0) / test::sales_pd_zoh(z, kT) - 1.0), 1e-7) << l;
    EXPECT_LT(std::abs(check.measured[l](0, 0) / check.known[l](0, 0) - 1.0), 1e-7);
  }
  // The paper's negative-feedback form (G - T)/(T G) is -K in the contract's sign.
  const std::complex<double> G = estimate.plant.value[10](0, 0), T = estimate.output_from_reference.value[10](0, 0);
  EXPECT_LT(std::abs((G - T) / (T * G) + check.known[10](0, 0)), 1e-7 * std::abs(check.known[10](0, 0)));
}

TEST_F(SalesRotorLoop, MeasuredSensitivityMatchesModel) {
  const Frf S_meas = input_sensitivity_from_reference(estimate.input_from_reference, controller, test::sales_signals());
  const Frf S_model = input_sensitivity(plant, controller, test::sales_signals(), S_meas.frequency_hz);
  for (Eigen::Index l = 0; l < S_meas.lines(); ++l)
    EXPECT_LT(
        std::abs(S_meas.value[static_cast<std::size_t>(l)](0, 0) / S_model.value[static_cast<std::size_t>(l)](0, 0) -
                 1.0),
        1e-7);
  // Independent: S = 1 / (1 - K G) with the closed-form ZOH plant and controller.
  for (Eigen::Index l = 0; l < S_meas.lines(); ++l) {
    const std::complex<double> z = std::polar(1.0, 2.0 * kPi * S_meas.frequency_hz(l) * kT);
    const std::complex<double> S0 = 1.0 / (1.0 - test::sales_pd_zoh(z, kT) * test::sales_rotor_zoh(z, kT));
    EXPECT_LT(std::abs(S_meas.value[static_cast<std::size_t>(l)](0, 0) / S0 - 1.0), 1e-7) << l;
  }
  const auto peaks = sensitivity_peaks(S_meas, {"u"});
  ASSERT_EQ(peaks.size(), 1u);
  // Fine-grid peak of the model: the 5 Hz line grid is within 0.2 dB of it.
  Eigen::VectorXd fine(3000);
  for (Eigen::Index i = 0; i < fine.size(); ++i) fine(i) = 0.5 * static_cast<double>(i + 1);
  const auto fine_peak = sensitivity_peaks(input_sensitivity(plant, controller, test::sales_signals(), fine), {"u"});
  EXPECT_NEAR(peaks[0].magnitude_db, fine_peak[0].magnitude_db, 0.2);
  EXPECT_GT(peaks[0].magnitude_db, 0.0);
}

TEST_F(SalesRotorLoop, RefusesTooShortRecordsAndBadLines) {
  PeriodicFrfOptions o;
  o.sample_time = kT;
  o.period_samples = kN;
  o.lines = lines;
  o.transient_periods = 6;  // nothing left
  EXPECT_THROW(estimate_periodic_frf(r, data.u, data.y, o), InsufficientData);
  o.transient_periods = 1;
  o.lines = {3, 3};
  EXPECT_THROW(estimate_periodic_frf(r, data.u, data.y, o), Error);
  o.lines = {1000};
  EXPECT_THROW(estimate_periodic_frf(r, data.u, data.y, o), Error);
  o.lines = {301};  // not excited
  EXPECT_THROW(estimate_periodic_frf(r, data.u, data.y, o), InsufficientData);
}

// Two coupled unstable axes, decentralised PD, two references in the Hadamard pattern.
struct TwoAxis {
  DiscreteSystem plant;
  StateSpaceController controller;
  LoopSignalNames signals{{"y1", "y2"}, {"u1", "u2"}, {"r1", "r2"}};
};

TwoAxis two_axis() {
  ContinuousSystem c;
  c.A = (Eigen::MatrixXd(4, 4) << 0, 1, 0, 0, 2800, 0, -300, 0, 0, 0, 0, 1, -300, 0, 2500, 0).finished();
  c.B = (Eigen::MatrixXd(4, 2) << 0, 0, 4.2, 0.5, 0, 0, 0.3, 4.0).finished();
  c.C = (Eigen::MatrixXd(2, 4) << 200, 0, 0, 0, 0, 0, 180, 0).finished();
  c.D = Eigen::MatrixXd::Zero(2, 2);
  TwoAxis t;
  t.plant = c2d_zoh(c, kT);
  const StateSpaceController pd = test::sales_pd_controller(kT);
  StateSpaceController& k = t.controller;
  k.sample_time = kT;
  k.inputs = {"y1", "y2"};
  k.outputs = {"u1", "u2"};
  k.A = Eigen::MatrixXd::Zero(2, 2);
  k.A.diagonal().setConstant(pd.A(0, 0));
  k.B = Eigen::MatrixXd::Identity(2, 2) * pd.B(0, 0);
  k.C = Eigen::MatrixXd::Identity(2, 2) * pd.C(0, 0);
  k.D = Eigen::MatrixXd::Identity(2, 2) * pd.D(0, 0);
  return t;
}

TEST(FrfClosedLoopMimo, HadamardPatternSeparatesTheInputs) {
  // As the simulator's multisine: 1 s periods (1 Hz lines, all excited up to 300 Hz), the
  // channel signs flipped by the Hadamard rows from period to period.
  const TwoAxis t = two_axis();
  ASSERT_LT(test::closed_loop_radius(t.plant, t.controller), 0.999);
  const Eigen::Index N = 10000;
  const auto lines = lines_up_to(300);
  const Eigen::MatrixXd r = test::multisine(N, lines, 3 + 2 * 2, 0.5, 2);
  const test::LoopData data = test::simulate_loop(t.plant, t.controller, t.signals, r);
  PeriodicFrfOptions o;
  o.sample_time = kT;
  o.period_samples = N;
  o.lines = lines;
  o.transient_periods = 3;  // odd: the blocks start on the second Hadamard column; any P consecutive periods do
  o.periods_per_block = 2;
  auto relative_errors = [&](const Frf& G) {
    std::vector<double> err;
    for (Eigen::Index l = 0; l < G.lines(); ++l) {
      const Eigen::MatrixXcd G0 = freq_response(t.plant, 2.0 * kPi * G.frequency_hz(l));
      err.push_back((G.value[static_cast<std::size_t>(l)] - G0).norm() / G0.norm());
    }
    std::sort(err.begin(), err.end());
    return err;
  };
  // Without a transient model every period's switching transient leaks into the lines.
  o.transient_model = PeriodicFrfOptions::TransientModel::none;
  const auto leaky = relative_errors(estimate_periodic_frf(r, data.u, data.y, o).plant);
  EXPECT_GT(leaky[leaky.size() / 2], 0.05);
  // The local polynomial model removes it (automatic for P > 1).
  o.transient_model = PeriodicFrfOptions::TransientModel::automatic;
  const PeriodicFrf e = estimate_periodic_frf(r, data.u, data.y, o);
  EXPECT_EQ(e.blocks, 2);
  const auto err = relative_errors(e.plant);
  RecordProperty("hadamard_lpm_median_error", std::to_string(err[err.size() / 2]));
  RecordProperty("hadamard_lpm_worst_error", std::to_string(err.back()));
  EXPECT_LT(err[err.size() / 2], 1e-6);
  EXPECT_LT(err.back(), 0.005);  // worst at the lowest lines, where G turns around the unstable pole
  // Magnitude and phase of every element within 1 % and 1 degree below 1 kHz (all lines here).
  for (Eigen::Index l = 0; l < e.plant.lines(); ++l) {
    const Eigen::MatrixXcd G0 = freq_response(t.plant, 2.0 * kPi * e.plant.frequency_hz(l));
    for (Eigen::Index i = 0; i < 2; ++i)
      for (Eigen::Index j = 0; j < 2; ++j) {
        const std::complex<double> g = e.plant.value[static_cast<std::size_t>(l)](i, j);
        EXPECT_LT(std::abs(std::abs(g) / std::abs(G0(i, j)) - 1.0), 0.01) << l << " " << i << j;
        EXPECT_LT(std::abs(test::phase_error_deg(g, G0(i, j))), 1.0) << l << " " << i << j;
      }
  }
  // Eq. 11 in MIMO form and the controller check (square plant: K itself).
  const Frf G11 = open_loop_from_closed_loop(e.output_from_reference, t.controller, t.signals);
  const auto err11 = relative_errors(G11);
  EXPECT_LT(err11[err11.size() / 2], 1e-6);
  const ControllerCheck check = check_controller(e.plant, e.output_from_reference, t.controller, t.signals);
  std::vector<double> kerr(check.relative_error.data(), check.relative_error.data() + check.relative_error.size());
  std::sort(kerr.begin(), kerr.end());
  EXPECT_LT(kerr[kerr.size() / 2], 1e-6);
  EXPECT_LT(kerr.back(), 0.01);
  // Both references carrying the same signal cannot separate the inputs.
  Eigen::MatrixXd same = r;
  same.col(1) = same.col(0);
  const test::LoopData d2 = test::simulate_loop(t.plant, t.controller, t.signals, same);
  EXPECT_THROW(estimate_periodic_frf(same, d2.u, d2.y, o), InsufficientData);
}

}  // namespace frf_closed_loop_test
}  // namespace ambid::ident
