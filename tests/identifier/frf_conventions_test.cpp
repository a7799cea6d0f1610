// Sign conventions of the frequency-domain identifier against analytic first- and second-order
// systems: a lag is a negative phase, the DFT phasor of a cos(wt + phi) is a e^{j phi}, and
// the periodic and Welch estimators reproduce the analytic response of simulated first- and
// second-order systems, and the rational fit gives their poles with the right sign.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "core/error.hpp"
#include "frf_test_helpers.hpp"
#include "identifier/frequency_domain/freq_response.hpp"
#include "identifier/frequency_domain/frf_dft.hpp"
#include "identifier/frequency_domain/frf_periodic.hpp"
#include "identifier/frequency_domain/rational_fit.hpp"
#include "identifier/frf_types.hpp"
#include "identifier/frf_welch.hpp"

namespace ambid::ident {
namespace frf_conventions_test {

using test::kPi;

ContinuousSystem first_order(double tau) {  // 1 / (tau s + 1)
  ContinuousSystem s;
  s.A = Eigen::MatrixXd::Constant(1, 1, -1.0 / tau);
  s.B = Eigen::MatrixXd::Constant(1, 1, 1.0 / tau);
  s.C = Eigen::MatrixXd::Constant(1, 1, 1.0);
  s.D = Eigen::MatrixXd::Zero(1, 1);
  return s;
}

ContinuousSystem second_order(double wn, double zeta) {  // wn^2 / (s^2 + 2 zeta wn s + wn^2)
  ContinuousSystem s;
  s.A = (Eigen::MatrixXd(2, 2) << 0.0, 1.0, -wn * wn, -2.0 * zeta * wn).finished();
  s.B = (Eigen::MatrixXd(2, 1) << 0.0, wn * wn).finished();
  s.C = (Eigen::MatrixXd(1, 2) << 1.0, 0.0).finished();
  s.D = Eigen::MatrixXd::Zero(1, 1);
  return s;
}

TEST(FrfConventions, FirstOrderLagHasNegativePhase) {
  const double tau = 0.01;
  const auto sys = first_order(tau);
  // At the corner: |G| = 1/sqrt(2), phase -45 deg.
  const std::complex<double> g = freq_response(sys, 1.0 / tau)(0, 0);
  EXPECT_NEAR(std::abs(g), 1.0 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(test::phase_deg(g), -45.0, 1e-10);
  // Anywhere: 1 / (1 + j w tau).
  for (double w : {1.0, 37.0, 450.0, 1e4}) {
    const std::complex<double> expected = 1.0 / std::complex<double>(1.0, w * tau);
    EXPECT_LT(std::abs(freq_response(sys, w)(0, 0) - expected), 1e-12) << w;
  }
}

TEST(FrfConventions, SecondOrderAtNaturalFrequency) {
  const double wn = 300.0, zeta = 0.05;
  const std::complex<double> g = freq_response(second_order(wn, zeta), wn)(0, 0);
  EXPECT_NEAR(std::abs(g), 1.0 / (2.0 * zeta), 1e-9);
  EXPECT_NEAR(test::phase_deg(g), -90.0, 1e-9);
  // Well above resonance the phase approaches -180 deg (never +180 wrapped the other way
  // before the resonance).
  EXPECT_LT(test::phase_deg(freq_response(second_order(wn, zeta), 0.5 * wn)(0, 0)), 0.0);
  EXPECT_LT(test::phase_deg(freq_response(second_order(wn, zeta), 10.0 * wn)(0, 0)), -170.0);
}

TEST(FrfConventions, DiscreteOneSampleDelayIsLinearPhaseLag) {
  DiscreteSystem d;  // y[k] = u[k-1]: z^-1
  d.A = Eigen::MatrixXd::Zero(1, 1);
  d.B = Eigen::MatrixXd::Constant(1, 1, 1.0);
  d.C = Eigen::MatrixXd::Constant(1, 1, 1.0);
  d.D = Eigen::MatrixXd::Zero(1, 1);
  d.sample_time = 1e-3;
  for (double f : {10.0, 100.0, 333.0}) {
    const std::complex<double> g = freq_response(d, 2.0 * kPi * f)(0, 0);
    EXPECT_NEAR(std::abs(g), 1.0, 1e-14);
    EXPECT_NEAR(test::phase_deg(g), -360.0 * f * d.sample_time, 1e-9) << f;
  }
  // The same as a contract controller.
  StateSpaceController c;
  c.sample_time = 1e-3;
  c.inputs = {"y"};
  c.outputs = {"u"};
  c.A = d.A;
  c.B = d.B;
  c.C = d.C;
  c.D = d.D;
  EXPECT_NEAR(test::phase_deg(freq_response(c, 2.0 * kPi * 100.0)(0, 0)), -36.0, 1e-9);
}

TEST(FrfConventions, ZohDiscreteFirstOrderMatchesClosedForm) {
  // ZOH of 1/(tau s + 1): (1 - a) z^-1 / (1 - a z^-1), a = e^{-T/tau}.
  const double tau = 0.02, T = 1e-3, a = std::exp(-T / tau);
  const DiscreteSystem d = c2d_zoh(first_order(tau), T);
  for (double f : {1.0, 20.0, 250.0}) {
    const std::complex<double> z = std::polar(1.0, 2.0 * kPi * f * T);
    const std::complex<double> expected = (1.0 - a) / (z - a);
    EXPECT_LT(std::abs(freq_response(d, 2.0 * kPi * f)(0, 0) - expected), 1e-12) << f;
  }
}

TEST(FrfConventions, DftPhasorOfCosine) {
  const Eigen::Index N = 64;
  const double amplitude = 2.5, phi = 0.7;
  Eigen::MatrixXd x(2 * N, 1);
  for (Eigen::Index n = 0; n < 2 * N; ++n)
    x(n, 0) = amplitude * std::cos(2.0 * kPi * 5.0 * static_cast<double>(n) / static_cast<double>(N) + phi) + 0.3;
  const auto X = period_phasors(x, 0, N, 2, {3, 5});
  ASSERT_EQ(X.size(), 2u);
  for (const auto& p : X) {
    EXPECT_LT(std::abs(p(1, 0) - std::polar(amplitude, phi)), 1e-12);
    EXPECT_LT(std::abs(p(0, 0)), 1e-12);  // no leakage into another line
  }
  EXPECT_THROW(period_phasors(x, 0, N, 3, {5}), Error);   // does not fit
  EXPECT_THROW(period_phasors(x, 0, N, 1, {33}), Error);  // above N/2
}

TEST(FrfConventions, PeriodicEstimateOfSimulatedSecondOrder) {
  // Open loop (no controller): r drives u directly, y = G u. The estimate must equal the
  // analytic ZOH response, lags negative.
  const double T = 1e-3;
  const DiscreteSystem d = c2d_zoh(second_order(2.0 * kPi * 40.0, 0.2), T);
  const Eigen::Index N = 1000;
  std::vector<Eigen::Index> lines;
  for (Eigen::Index k = 1; k < 400; k += 3) lines.push_back(k);
  const Eigen::MatrixXd r = test::multisine(N, lines, 4, 1.0);
  const Eigen::MatrixXd y = simulate(d, r);
  PeriodicFrfOptions o;
  o.sample_time = T;
  o.period_samples = N;
  o.lines = lines;
  o.transient_periods = 1;
  const PeriodicFrf e = estimate_periodic_frf(r, r, y, o);
  ASSERT_EQ(e.plant.lines(), static_cast<Eigen::Index>(lines.size()));
  double worst = 0.0;
  for (Eigen::Index l = 0; l < e.plant.lines(); ++l) {
    const double f = e.plant.frequency_hz(l);
    EXPECT_NEAR(f, static_cast<double>(lines[static_cast<std::size_t>(l)]) / (N * T), 1e-12);
    const std::complex<double> expected = freq_response(d, 2.0 * kPi * f)(0, 0);
    worst = std::max(worst, std::abs(e.plant.value[static_cast<std::size_t>(l)](0, 0) / expected - 1.0));
  }
  // Transient of the 0.2-damped 40 Hz mode after one 1 s period: e^{-0.2*251*1} ~ 1e-22.
  EXPECT_LT(worst, 1e-9);
  // Below the resonance the phase is small and negative; above it passes -90 deg.
  EXPECT_LT(test::phase_deg(e.plant.value[1](0, 0)), 0.0);  // 4 Hz
  EXPECT_NEAR(test::phase_deg(freq_response(d, 2.0 * kPi * 40.0)(0, 0)), -90.0 - 360.0 * 40.0 * T / 2.0, 0.5);
}

TEST(FrfConventions, PeriodicEstimateOfSimulatedFirstOrderLag) {
  // 1/(tau s + 1), tau = 2 ms, sampled at 1 kHz: the estimate equals the closed-form ZOH
  // response (1 - a) z^-1 / (1 - a z^-1), a = e^{-T/tau}, and every phase is a lag.
  const double T = 1e-3, tau = 2e-3, a = std::exp(-T / tau);
  const DiscreteSystem d = c2d_zoh(first_order(tau), T);
  const Eigen::Index N = 500;
  std::vector<Eigen::Index> lines;
  for (Eigen::Index k = 1; k < 250; k += 2) lines.push_back(k);
  const Eigen::MatrixXd r = test::multisine(N, lines, 3, 1.0);
  PeriodicFrfOptions o;
  o.sample_time = T;
  o.period_samples = N;
  o.lines = lines;
  o.transient_periods = 1;
  const PeriodicFrf e = estimate_periodic_frf(r, r, simulate(d, r), o);
  for (Eigen::Index l = 0; l < e.plant.lines(); ++l) {
    const double w = 2.0 * kPi * e.plant.frequency_hz(l);
    const std::complex<double> zinv = std::exp(std::complex<double>(0.0, -w * T));
    const std::complex<double> expected = (1.0 - a) * zinv / (1.0 - a * zinv);
    const std::complex<double> g = e.plant.value[static_cast<std::size_t>(l)](0, 0);
    EXPECT_LT(std::abs(g / expected - 1.0), 1e-9) << w;
    EXPECT_LT(test::phase_deg(g), 0.0) << w;
    EXPECT_GT(test::phase_deg(g), -180.0) << w;
  }
}

TEST(FrfConventions, WelchEstimateOfSimulatedSecondOrderHasTheAnalyticPhase) {
  // Random input, y = G u through the ZOH model of a 0.3-damped 50 Hz mode: Welch's estimate
  // follows the analytic response (checked against closed forms above) within 1 deg, a lag.
  const double T = 1e-3;
  const DiscreteSystem d = c2d_zoh(second_order(2.0 * kPi * 50.0, 0.3), T);
  const Eigen::MatrixXd r = test::gaussian(1 << 15, 1.0, 17);
  WelchFrfOptions o;
  o.sample_time = T;
  o.segment_samples = 512;
  o.f_max = 200.0;
  const WelchFrf e = estimate_welch_frf(r, r, simulate(d, r), o);
  double worst = 0.0;
  for (Eigen::Index l = 0; l < e.plant.lines(); ++l) {
    const double f = e.plant.frequency_hz(l);
    const std::complex<double> expected = freq_response(d, 2.0 * kPi * f)(0, 0);
    const std::complex<double> g = e.plant.value[static_cast<std::size_t>(l)](0, 0);
    worst = std::max(worst, std::abs(test::phase_deg(g / expected)));
    // A lag up to 100 Hz (analytic -176 deg there with the hold's half sample); beyond, the
    // phase passes -180 deg and wraps.
    if (f <= 100.0) {
      EXPECT_LT(test::phase_deg(g), 0.0) << f;
    }
  }
  RecordProperty("welch_second_order_worst_phase_error_deg", std::to_string(worst));
  EXPECT_LT(worst, 1.0);
}

TEST(FrfConventions, RationalFitGivesPolesWithTheirSign) {
  // Exact continuous data of 1/(tau s + 1), of the unstable 1/(tau s - 1) and of a 0.1-damped
  // 80 Hz mode: the poles are -1/tau, +1/tau and -zeta wn +- j wn sqrt(1 - zeta^2).
  const double tau = 2e-3, wn = 2.0 * kPi * 80.0, zeta = 0.1;
  Eigen::VectorXd f(60);
  for (Eigen::Index i = 0; i < f.size(); ++i) f(i) = 1.0 + 5.0 * static_cast<double>(i);
  const auto fit = [&](auto G, int n) {
    Eigen::VectorXcd g(f.size());
    for (Eigen::Index i = 0; i < f.size(); ++i) g(i) = G(std::complex<double>(0.0, 2.0 * kPi * f(i)));
    RationalFitOptions o;
    o.numerator_degree = 0;
    o.denominator_degree = n;
    return fit_rational(f, g, Eigen::VectorXd(), o).model;
  };
  const RationalModel lag = fit([&](std::complex<double> s) { return 1.0 / (tau * s + 1.0); }, 1);
  EXPECT_NEAR(lag.poles()(0).real(), -1.0 / tau, 1e-6 / tau);
  EXPECT_NEAR(lag.gain(), 1.0 / tau, 1e-6 / tau);
  EXPECT_LT(test::phase_deg(lag.response(1.0 / tau)), -44.99);
  const RationalModel unstable = fit([&](std::complex<double> s) { return 1.0 / (tau * s - 1.0); }, 1);
  EXPECT_NEAR(unstable.poles()(0).real(), 1.0 / tau, 1e-6 / tau);
  const RationalModel mode =
      fit([&](std::complex<double> s) { return wn * wn / (s * s + 2.0 * zeta * wn * s + wn * wn); }, 2);
  const Eigen::VectorXcd p = mode.poles();
  ASSERT_EQ(p.size(), 2);
  for (Eigen::Index i = 0; i < 2; ++i) {
    EXPECT_NEAR(p(i).real(), -zeta * wn, 1e-6 * wn);
    EXPECT_NEAR(std::abs(p(i).imag()), wn * std::sqrt(1.0 - zeta * zeta), 1e-6 * wn);
  }
  EXPECT_NEAR(test::phase_deg(mode.response(wn)), -90.0, 1e-6);
}

TEST(FrfConventions, ConfidenceRadiusFactor) {
  EXPECT_NEAR(confidence_radius_factor(0.95, 0.0), 2.995732273554, 1e-10);  // -ln 0.05
  EXPECT_NEAR(confidence_radius_factor(0.95, 2.0), 19.0, 1e-10);            // F(2,2) 95 % = 19
  EXPECT_NEAR(confidence_radius_factor(0.95, 10.0), 4.102821015130, 1e-8);  // F(2,10) 95 %
  EXPECT_NEAR(confidence_radius_factor(0.95, 1e7), 2.9957, 1e-4);
  EXPECT_THROW(confidence_radius_factor(1.0, 2.0), Error);
  EXPECT_THROW(confidence_radius_factor(0.9, -1.0), Error);
}

}  // namespace frf_conventions_test
}  // namespace ambid::ident
