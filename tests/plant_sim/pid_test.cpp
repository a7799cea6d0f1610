#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "plant_sim/observer_controller.hpp"
#include "plant_sim/pid.hpp"
#include "plant_sim/sales_rotor.hpp"

namespace ambid::sim {
namespace pid_test {

DiscreteSystem as_system(const StateSpaceController& c) { return DiscreteSystem{c.A, c.B, c.C, c.D, c.sample_time}; }

TEST(Pid, StepResponseMatchesDifferenceEquation) {
  const double T = 1e-3;
  PidLoop loop;
  loop.measured = "x";
  loop.drives = {{"u1", 1.0}, {"u2", -1.0}};
  loop.kp = 2.0;
  loop.ki = 50.0;
  loop.kd = 0.03;
  loop.derivative_time_constant = 4e-3;
  const StateSpaceController c = pid_controller({loop}, T, {"u1", "u2", "u3"});
  EXPECT_EQ(c.inputs, std::vector<std::string>{"x"});
  EXPECT_EQ(c.states(), 2);
  EXPECT_NO_THROW(c.validate({"u1", "u2", "u3"}));

  const int steps = 50;
  const Eigen::MatrixXd y = Eigen::MatrixXd::Ones(steps, 1);  // measured step: e = -1
  const Eigen::MatrixXd uf = simulate(as_system(c), y);
  const double a = loop.derivative_time_constant / (loop.derivative_time_constant + T);
  const double b = loop.kd / (loop.derivative_time_constant + T);
  double integral = 0.0, d = 0.0, e_prev = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double e = -y(k, 0);
    d = a * d + b * (e - e_prev);
    const double expected = loop.kp * e + loop.ki * integral + d;
    EXPECT_NEAR(uf(k, 0), expected, 1e-12) << "k = " << k;
    EXPECT_NEAR(uf(k, 1), -expected, 1e-12) << "k = " << k;
    EXPECT_EQ(uf(k, 2), 0.0);
    integral += T * e;
    e_prev = e;
  }
}

TEST(Pid, ProportionalOnlyHasNoStates) {
  PidLoop loop{"x", {{"u", 1.0}}, 3.0, 0.0, 0.0, 0.0};
  const StateSpaceController c = pid_controller({loop}, 1e-4, {"u"});
  EXPECT_EQ(c.states(), 0);
  EXPECT_DOUBLE_EQ(c.D(0, 0), -3.0);
}

TEST(Pid, StabilisesTheSalesRotor) {
  // G(s) = 840 / (s^2 - 2800); with kp = 30, ki = 300, kd = 0.25 the continuous loop has
  // s^3 + 210 s^2 + 22400 s + 252000 (Routh: 210 * 22400 > 252000, stable).
  const NamedSystem rotor = sales_rotor();
  const double T = 1e-4;
  PidLoop loop{"y", {{"u", 1.0}}, 30.0, 300.0, 0.25, 2e-4};
  const StateSpaceController c = pid_controller({loop}, T, rotor.input_names);
  const DiscreteSystem plant = c2d_zoh(rotor.system, T);
  EXPECT_GT(spectral_radius(plant), 1.0);
  const DiscreteSystem cl = linear_closed_loop(plant, rotor.input_names, rotor.output_names, c);
  EXPECT_LT(spectral_radius(cl), 1.0);
  // Without the controller's sign convention (positive feedback) the loop is unstable.
  PidLoop wrong = loop;
  wrong.drives = {{"u", -1.0}};
  EXPECT_GT(spectral_radius(linear_closed_loop(plant, rotor.input_names, rotor.output_names,
                                               pid_controller({wrong}, T, rotor.input_names))),
            1.0);
}

TEST(LeadLag, SingleSectionMatchesTustinDifferenceEquation) {
  const double T = 1e-3, k = 2.5, lead = 8e-3, lag = 1e-3;
  const StateSpaceController c = lead_lag_controller({{"y", {{"u", 1.0}}, k, {{lead, lag}}}}, T, {"u"});
  ASSERT_EQ(c.states(), 1);
  const int steps = 40;
  Eigen::MatrixXd y(steps, 1);
  for (int i = 0; i < steps; ++i) y(i, 0) = std::sin(0.3 * i) + 0.2;
  const Eigen::MatrixXd uf = simulate(as_system(c), y);
  // (2 lag/T + 1) c[k] + (1 - 2 lag/T) c[k-1] = k ((2 lead/T + 1) e[k] + (1 - 2 lead/T) e[k-1])
  double c_prev = 0.0, e_prev = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double e = -y(i, 0);
    const double expected =
        (k * ((2 * lead / T + 1) * e + (1 - 2 * lead / T) * e_prev) - (1 - 2 * lag / T) * c_prev) / (2 * lag / T + 1);
    EXPECT_NEAR(uf(i, 0), expected, 1e-12) << "k = " << i;
    c_prev = expected;
    e_prev = e;
  }
}

TEST(LeadLag, IntegralAddsTheForwardEulerSumOfTheError) {
  const double T = 1e-3, k = 2.5, lead = 8e-3, lag = 1e-3, ki = 40.0;
  const StateSpaceController c = lead_lag_controller({{"y", {{"u", 1.0}}, k, {{lead, lag}}, ki}}, T, {"u"});
  ASSERT_EQ(c.states(), 2);
  const int steps = 40;
  Eigen::MatrixXd y(steps, 1);
  for (int i = 0; i < steps; ++i) y(i, 0) = std::sin(0.3 * i) + 0.2;
  const Eigen::MatrixXd uf = simulate(as_system(c), y);
  // The section's difference equation as above, plus ki T (e[0] + ... + e[k-1]).
  double c_prev = 0.0, e_prev = 0.0, sum = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double e = -y(i, 0);
    const double section =
        (k * ((2 * lead / T + 1) * e + (1 - 2 * lead / T) * e_prev) - (1 - 2 * lag / T) * c_prev) / (2 * lag / T + 1);
    EXPECT_NEAR(uf(i, 0), section + ki * T * sum, 1e-12) << "k = " << i;
    c_prev = section;
    e_prev = e;
    sum += e;
  }
}

TEST(LeadLag, CascadeFrequencyResponseIsTheWarpedContinuousOne) {
  const double T = 1e-4, gain = 3.0;
  const std::vector<LeadLagSection> sections = {{5e-3, 5e-4}, {0.0, 2e-3}, {1e-3, 1e-2}};
  const StateSpaceController c =
      lead_lag_controller({{"x", {{"u1", 1.0}, {"u2", -0.5}}, gain, sections}}, T, {"u1", "u2"});
  ASSERT_EQ(c.states(), 3);
  for (const double w : {10.0, 300.0, 5000.0}) {
    const std::complex<double> z = std::exp(std::complex<double>(0.0, w * T));
    const std::complex<double> s = 2.0 / T * (z - 1.0) / (z + 1.0);
    std::complex<double> expected = -gain;  // e = -y
    for (const auto& sec : sections) expected *= (sec.lead_time_constant * s + 1.0) / (sec.lag_time_constant * s + 1.0);
    const Eigen::MatrixXcd resolvent = z * Eigen::MatrixXcd::Identity(3, 3) - c.A.cast<std::complex<double>>();
    const Eigen::MatrixXcd input = c.B.cast<std::complex<double>>();
    const Eigen::MatrixXcd H =
        c.C.cast<std::complex<double>>() * linalg::lu_solve(resolvent, input).x + c.D.cast<std::complex<double>>();
    EXPECT_LT(std::abs(H(0, 0) - expected), 1e-10 * std::abs(expected)) << "w = " << w;
    EXPECT_LT(std::abs(H(1, 0) + 0.5 * expected), 1e-10 * std::abs(expected)) << "w = " << w;
  }
}

TEST(LeadLag, StabilisesTheSalesRotor) {
  // C(s) = 30 (8.33e-3 s + 1) / (1e-3 s + 1): 1e-3 s^3 + s^2 + 207.2 s + 22400 (stable).
  const NamedSystem rotor = sales_rotor();
  const double T = 1e-4;
  const StateSpaceController c =
      lead_lag_controller({{"y", {{"u", 1.0}}, 30.0, {{0.25 / 30.0, 1e-3}}}}, T, rotor.input_names);
  const DiscreteSystem cl = linear_closed_loop(c2d_zoh(rotor.system, T), rotor.input_names, rotor.output_names, c);
  EXPECT_LT(spectral_radius(cl), 1.0);
}

TEST(Pid, RejectsBadLoops) {
  EXPECT_THROW(pid_controller({}, 1e-4, {"u"}), Error);
  EXPECT_THROW(pid_controller({{"x", {{"v", 1.0}}, 1.0, 0.0, 0.0, 0.0}}, 1e-4, {"u"}), Error);
  EXPECT_THROW(pid_controller({{"x", {{"u", 1.0}}, 1.0, 0.0, 1.0, 0.0}}, 1e-4, {"u"}), Error);
  EXPECT_THROW(pid_controller({{"x", {{"u", 1.0}}, 1.0, 0.0, 0.0, 0.0}}, 0.0, {"u"}), Error);
  EXPECT_THROW(pid_controller({{"u", {{"u", 1.0}}, 1.0, 0.0, 0.0, 0.0}}, 1e-4, {"u"}), Error);
  EXPECT_THROW(lead_lag_controller({{"x", {{"u", 1.0}}, 1.0, {{1e-3, 0.0}}}}, 1e-4, {"u"}), Error);
}

}  // namespace pid_test
}  // namespace ambid::sim
