// The effect catalogue: neutral effects leave the nominal bearing exactly as it is, tiny ones
// barely change it, and each effect leaves its documented signature (plant_sim/EFFECTS.md),
// checked against formulas written out here independently of the library.
#include <cmath>
#include <complex>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/Core>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "plant_sim/amb1dof_extended.hpp"
#include "plant_sim/effects.hpp"
#include "plant_sim/linearize.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::sim {
namespace effects_test {

using ::testing::HasSubstr;
constexpr double kPi = std::numbers::pi;

Experiment simulate(const std::vector<Effect>& effects, double duration = 0.05) {
  ScenarioOptions o;
  o.duration = duration;
  o.seed = 3;
  o.amplitude = 0.3;
  o.position_noise = 1e-8;
  o.current_noise = 1e-4;
  o.effects = effects;
  return simulate_scenario(o);
}

// The acceleration x'' of `plant` at its equilibrium state with entries replaced.
double acceleration(const Plant& plant, const std::map<int, double>& state) {
  Eigen::VectorXd x = plant.equilibrium_state();
  for (const auto& [i, v] : state) x[i] = v;
  return plant.derivative(x, plant.equilibrium_input(), Eigen::VectorXd::Zero(1))[1];
}

TEST(EffectCatalogue, VocabularyOfTheContract) {
  EXPECT_EQ(effect_names(),
            (std::vector<std::string>{"coil_resistance", "amplifier_gain", "amplifier_bandwidth", "eddy_current",
                                      "sensor_delay", "sensor_gain", "flexible_mode", "magnetic_saturation", "air_gap",
                                      "rotor_mass", "harmonic_disturbance", "force_factor"}));
  for (const auto& spec : effect_catalogue()) {
    EXPECT_TRUE(make_effect(spec.name).neutral()) << spec.name;
    EXPECT_EQ(make_effect(spec.name).channel, spec.has_channel ? 1 : 0);
    for (const auto& p : spec.parameters) EXPECT_FALSE(p.unit.empty()) << spec.name << "." << p.name;
  }
}

TEST(EffectCatalogue, BadNamesAndValuesAreClearErrors) {
  EXPECT_THAT([] { make_effect("eddy"); }, ::testing::ThrowsMessage<Error>(HasSubstr("known: coil_resistance")));
  EXPECT_THAT(
      [] {
        make_effect("eddy_current", {{"delay", 1e-4}});
      },
      ::testing::ThrowsMessage<Error>(HasSubstr("no parameter 'delay' (valid: tau)")));
  EXPECT_THAT(
      [] {
        make_effect("coil_resistance", {{"channel", 3}});
      },
      ::testing::ThrowsMessage<Error>(HasSubstr("channel must be 1 or 2")));
  EXPECT_THAT(
      [] {
        make_effect("sensor_delay", {{"delay", -1e-4}});
      },
      ::testing::ThrowsMessage<Error>(HasSubstr("outside")));
  EXPECT_THAT(
      [] {
        make_effect("sensor_gain", {{"dgain", NAN}});
      },
      ::testing::ThrowsMessage<Error>(HasSubstr("dgain")));
  EXPECT_THAT(
      [] {
        Amb1dofExtended(Amb1dofParameters::nominal(), {Effect{"coil_resistance", 1, {{"dR", -17.5}}}});
      },
      ::testing::ThrowsMessage<Error>(HasSubstr("R1")));
  EXPECT_THAT(
      [] {
        Amb1dofExtended(Amb1dofParameters::nominal(), {make_effect("sensor_delay", {{"delay", 1e-4}})});
      },
      ::testing::ThrowsMessage<Error>(HasSubstr("positive sample time")));
}

TEST(Effects, NeutralEffectsGiveTheNominalBearingExactly) {
  const Experiment nominal = simulate({});
  for (const auto& name : effect_names()) {
    const Experiment e = simulate({make_effect(name)});
    EXPECT_EQ(e.y, nominal.y) << name;
    EXPECT_EQ(e.u, nominal.u) << name;
  }
}

// Small effects change the outputs in proportion to their size: the extension is continuous
// and reduces to the nominal bearing as its parameters go to their neutral values.
TEST(Effects, SmallEffectsChangeTheBearingInProportion) {
  const Experiment nominal = simulate({});
  for (const auto& spec : effect_catalogue()) {
    auto change = [&](double size) {
      std::map<std::string, double> values;
      for (const auto& p : spec.parameters)
        if (p.switches) values[p.name] = size * p.scale;
      const Experiment e = simulate({make_effect(spec.name, values)});
      return (e.y - nominal.y)
          .cwiseQuotient(nominal.y_deviation().cwiseAbs().colwise().maxCoeff().replicate(e.y.rows(), 1))
          .cwiseAbs()
          .maxCoeff();
    };
    const double small = change(1e-3), twice = change(2e-3);
    EXPECT_GT(small, 0.0) << spec.name;
    // One coil's K alone unbalances the bias forces: 1e-4 of K1 is 12 mN at the operating
    // point, which moves the rotor until the integral action takes it over (measured 0.10).
    EXPECT_LT(small, spec.name == "force_factor" ? 0.15 : 0.05) << spec.name;
    EXPECT_NEAR(twice / small, 2.0, 0.2) << spec.name;
  }
}

// Open loop from a displaced rotor with a fixed input sequence held over each dt: the sensor
// effects act on the measured position only. `split` > 1 samples every dt / split.
Eigen::MatrixXd open_loop_outputs(const Plant& plant, double dt, int split = 1) {
  Eigen::VectorXd x = plant.equilibrium_state();
  x[0] = 1e-7;
  Eigen::MatrixXd y(40 * split, 3);
  for (int n = 0; n < 40 * split; ++n) {
    y.row(n) = plant.output(x).transpose();
    Eigen::VectorXd u = plant.equilibrium_input();
    u[0] += 0.5 * std::sin(0.3 * (n / split));
    plant.advance(x, u, Eigen::VectorXd::Zero(1), dt / split, 4);
  }
  return y;
}

TEST(Effects, SensorDelayShiftsThePositionByItsSamples) {
  const double dt = 1e-4;
  const auto p = Amb1dofParameters::nominal();
  const Eigen::MatrixXd nominal = open_loop_outputs(Amb1dofVoltage(p), dt);
  const Eigen::MatrixXd three =
      open_loop_outputs(Amb1dofExtended(p, {make_effect("sensor_delay", {{"delay", 3 * dt}})}, dt), dt);
  const Eigen::MatrixXd half =
      open_loop_outputs(Amb1dofExtended(p, {make_effect("sensor_delay", {{"delay", 2.5 * dt}})}, dt), dt);
  // The truth between the samples: the nominal plant sampled twice as fast (same input, held).
  const Eigen::MatrixXd fine = open_loop_outputs(Amb1dofVoltage(p), dt, 2);
  EXPECT_EQ(three.rightCols(2), nominal.rightCols(2));
  for (int k = 3; k < 20; ++k) {
    EXPECT_DOUBLE_EQ(three(k, 0), nominal(k - 3, 0)) << k;
    // x(t_k - 2.5 dt) by cubic Hermite: within 1e-3 of the swing, where the linear mean of the
    // neighbours is off by the curvature (a low-pass of the delayed signal).
    const double swing = std::abs(nominal(k - 2, 0) - nominal(k - 3, 0)) + 1e-30;
    EXPECT_NEAR(half(k, 0), fine(2 * k - 5, 0), 1e-3 * swing) << k;
  }
  EXPECT_EQ(three(0, 0), 0.0);  // before the first sample arrives, the line holds the equilibrium
}

TEST(Effects, SensorGainScalesThePosition) {
  const auto p = Amb1dofParameters::nominal();
  const Eigen::MatrixXd nominal = open_loop_outputs(Amb1dofVoltage(p), 1e-4);
  const Eigen::MatrixXd scaled =
      open_loop_outputs(Amb1dofExtended(p, {make_effect("sensor_gain", {{"dgain", -0.15}})}), 1e-4);
  for (int k = 0; k < 40; ++k) EXPECT_DOUBLE_EQ(scaled(k, 0), 0.85 * nominal(k, 0));
  EXPECT_EQ(scaled.rightCols(2), nominal.rightCols(2));
}

TEST(Effects, HarmonicDisturbanceIsALineAtItsFrequency) {
  ScenarioOptions o;
  o.duration = 0.5;
  o.excitation = "none";
  o.effects = {make_effect("harmonic_disturbance", {{"f", 120.0}, {"Fc", 0.3}, {"Fs", 0.4}})};
  const Eigen::VectorXd x = simulate_scenario(o).y_deviation().col(0);
  // DFT magnitude at 2 Hz resolution from 50 to 500 Hz: the 120 Hz line stands out.
  auto line = [&](double f) {
    std::complex<double> sum = 0;
    for (Eigen::Index k = 0; k < x.size(); ++k) sum += x[k] * std::polar(1.0, -2 * kPi * f * double(k) * 1e-4);
    return std::abs(sum);
  };
  const double peak = line(120.0);
  for (double f = 50; f <= 500; f += 2)
    if (std::abs(f - 120.0) > 4) {
      EXPECT_LT(line(f), 0.05 * peak) << f;
    }
  // The force itself: (Fc cos + Fs sin) / m at any phase of the oscillator.
  const auto p = Amb1dofParameters::nominal();
  const Amb1dofExtended plant(p, o.effects);
  EXPECT_NEAR(acceleration(plant, {{4, 0.6}, {5, 0.8}}), (0.3 * 0.6 + 0.4 * 0.8) / p.m, 1e-12);
}

TEST(Effects, CoilAndAmplifierEffectsChangeTheirChannelOnly) {
  const auto p = Amb1dofParameters::nominal();
  const Amb1dofVoltage nominal(p);
  const Eigen::VectorXd x = nominal.equilibrium_state(), u = nominal.equilibrium_input();
  const Eigen::VectorXd w = Eigen::VectorXd::Zero(1);
  const double L = p.Ls1 + p.K1 / (2 * p.x0);
  const Eigen::VectorXd d0 = nominal.derivative(x, u, w);
  const Eigen::VectorXd dr =
      Amb1dofExtended(p, {make_effect("coil_resistance", {{"channel", 2}, {"dR", 3.0}})}).derivative(x, u, w);
  EXPECT_NEAR(dr[3] - d0[3], -3.0 * p.i0 / L, 1e-9);
  EXPECT_EQ(dr[2], d0[2]);
  const Eigen::VectorXd dk = Amb1dofExtended(p, {make_effect("amplifier_gain", {{"dkw", 0.2}})}).derivative(x, u, w);
  EXPECT_NEAR(dk[2] - d0[2], 0.2 * u[0] / L, 1e-9);
  EXPECT_EQ(dk[3], d0[3]);
}

TEST(Effects, AmplifierBandwidthIsAFirstOrderLag) {
  const auto p = Amb1dofParameters::nominal();
  const double tau = 3e-4;
  const Amb1dofExtended plant(p, {make_effect("amplifier_bandwidth", {{"channel", 2}, {"tau", tau}})});
  ASSERT_EQ(plant.state_names()[4], "v2");
  Eigen::VectorXd x = plant.equilibrium_state();
  const double v0 = x[4];
  EXPECT_DOUBLE_EQ(v0, p.R2 * p.i0);
  Eigen::VectorXd u = plant.equilibrium_input();
  u[1] += 1.0;  // one volt more command, held for one time constant
  plant.advance(x, u, Eigen::VectorXd::Zero(1), tau, 200);
  EXPECT_NEAR(x[4] - v0, p.kw2 * 1.0 * (1 - std::exp(-1.0)), 1e-9);
}

TEST(Effects, EddyCurrentsLagTheForceBehindTheCurrent) {
  const auto p = Amb1dofParameters::nominal();
  const double tau = 2e-4;
  const Amb1dofExtended plant(p, {make_effect("eddy_current", {{"tau", tau}})});
  // Coil 1 current raised, force current still at i0: no force yet, and the force current
  // moves toward the coil current at 1/tau.
  Eigen::VectorXd x = plant.equilibrium_state();
  x[2] = p.i0 + 0.1;
  const Eigen::VectorXd d = plant.derivative(x, plant.equilibrium_input(), Eigen::VectorXd::Zero(1));
  EXPECT_NEAR(d[1], 0.0, 1e-9);
  EXPECT_NEAR(d[4], 0.1 / tau, 1e-9);
  EXPECT_EQ(d[5], 0.0);
  // Once the force current has caught up, the force is the nominal one.
  x[4] = p.i0 + 0.1;
  EXPECT_NEAR(plant.derivative(x, plant.equilibrium_input(), Eigen::VectorXd::Zero(1))[1],
              p.K1 / 4 * (std::pow((p.i0 + 0.1) / p.x0, 2) - std::pow(p.i0 / p.x0, 2)) / p.m, 1e-9);
}

TEST(Effects, FlexibleModeAddsItsPolePair) {
  const auto p = Amb1dofParameters::nominal();
  const double f = 900.0, zeta = 0.02, w = 2 * kPi * f;
  const Amb1dofExtended plant(p, {make_effect("flexible_mode", {{"coupling", 0.05}, {"f", f}, {"zeta", zeta}})});
  LinearizeOptions lo;
  lo.state_scale = (Eigen::VectorXd(6) << p.x0, p.x0 * 1e3, p.i0, p.i0, 1e-6, 1e-3).finished();
  lo.input_scale = plant.equilibrium_input();
  const Eigen::VectorXcd poles = linalg::eigenvalues(linearize(plant, lo).A);
  const std::complex<double> expected(-zeta * w, w * std::sqrt(1 - zeta * zeta));
  double closest = INFINITY;
  for (const auto& s : poles) closest = std::min(closest, std::abs(s - expected));
  EXPECT_LT(closest, 1e-6 * w);
  // The sensor sees rotor plus mode.
  Eigen::VectorXd x = plant.equilibrium_state();
  x[0] = 1e-6;
  x[4] = 2e-7;
  EXPECT_DOUBLE_EQ(plant.output(x)[0], 1.2e-6);
}

TEST(Effects, SaturationFlattensTheForceLaw) {
  const auto p = Amb1dofParameters::nominal();
  const double beta = 0.4, a0 = p.i0 / p.x0;
  const Amb1dofExtended plant(p, {make_effect("magnetic_saturation", {{"beta", beta}})});
  auto force = [&](double a) { return p.K1 / 4 * a * a / (1 + beta * (a / a0) * (a / a0)); };
  for (double k : {0.5, 1.5, 3.0})
    EXPECT_NEAR(acceleration(plant, {{2, k * p.i0}}) * p.m, force(k * a0) - force(a0), 1e-9) << k;
  // The coil sees the incremental air-gap inductance K/2 phi'(a) / gap, phi'(a) = (1 + beta (a/a0)^2)^(-3/2).
  Eigen::VectorXd x = plant.equilibrium_state();
  x[2] = 1.5 * p.i0;
  const Eigen::VectorXd u = plant.equilibrium_input();
  const double slope = std::pow(1 + beta * 2.25, -1.5);
  EXPECT_NEAR(plant.derivative(x, u, Eigen::VectorXd::Zero(1))[2],
              (p.kw1 * u[0] - p.R1 * x[2]) / (p.Ls1 + 0.5 * p.K1 * slope / p.x0), 1e-9);
  // Far above the operating flux the force of a coil approaches K a0^2 / (4 beta).
  EXPECT_LT(acceleration(plant, {{2, 50 * p.i0}}) * p.m + force(a0), p.K1 * a0 * a0 / (4 * beta));
  EXPECT_GT(acceleration(plant, {{2, 50 * p.i0}}) * p.m + force(a0), 0.99 * p.K1 * a0 * a0 / (4 * beta));
}

TEST(Effects, AirGapAndRotorMassChangeTheMechanics) {
  const auto p = Amb1dofParameters::nominal();
  const double x = 2e-5, dx0 = 3e-5, dm = 0.25;
  auto force = [&](double gap) { return p.K1 / 4 * (std::pow(p.i0 / (gap - x), 2) - std::pow(p.i0 / (gap + x), 2)); };
  EXPECT_NEAR(acceleration(Amb1dofExtended(p, {make_effect("air_gap", {{"dx0", dx0}})}), {{0, x}}),
              force(p.x0 + dx0) / p.m, 1e-9);
  EXPECT_NEAR(acceleration(Amb1dofExtended(p, {make_effect("rotor_mass", {{"dm", dm}})}), {{0, x}}),
              force(p.x0) / (p.m + dm), 1e-9);
}

}  // namespace effects_test
}  // namespace ambid::sim
