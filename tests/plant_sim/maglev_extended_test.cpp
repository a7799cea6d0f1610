// maglev1coil_voltage with effects (plant_sim/maglev_extended.hpp) against analytic truths and
// the nominal plant of maglev1coil_voltage.hpp.
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "plant_sim/maglev1coil_voltage.hpp"
#include "plant_sim/maglev_effects.hpp"
#include "plant_sim/maglev_extended.hpp"

namespace ambid::sim {
namespace maglev_extended_test {

using ::testing::HasSubstr;

Effect effect(const std::string& name, const std::map<std::string, double>& values) {
  return make_effect(maglev_effect_catalogue(), name, values);
}

const Eigen::VectorXd kNoForce = Eigen::VectorXd::Zero(1);

TEST(MaglevExtended, WithoutEffectsItIsTheNominalPlantAtItsOwnOrAMeasuredPoint) {
  const MaglevParameters p = MaglevParameters::nominal();
  const double gap = 0.0145, current = p.equilibrium_current(gap);
  const Maglev1coilVoltage nominal(p, gap);
  // At the nominal equilibrium, measured or not, the anchored force constant is Km itself.
  for (const bool measured : {false, true}) {
    const MaglevExtended plant(p, {gap, current, p.R * current}, measured, {}, 3.25e-3);
    EXPECT_NEAR(plant.parameters().Km / p.Km, 1.0, 1e-12);
    const Eigen::Vector3d x(0.0151, -0.02, 0.017);
    const Eigen::VectorXd u = Eigen::VectorXd::Constant(1, 3.7);
    EXPECT_LT((plant.derivative(x, u, kNoForce) - nominal.derivative(x, u, kNoForce)).norm(),
              1e-12 * nominal.derivative(x, u, kNoForce).norm());
    EXPECT_LT((plant.output(x) - nominal.output(x)).norm(), 1e-15);
  }
}

TEST(MaglevExtended, AtAMeasuredPointGravityBalanceHoldsWhateverTheForceLawAndMass) {
  const MaglevParameters p = MaglevParameters::nominal();
  const MaglevOperatingPoint measured{0.014, 0.019, 4.0};  // far from the nominal's own 14.8 mA
  for (const auto& e : {effect("force_law", {{"dn_i", 0.7}, {"dn_x", -1.5}}), effect("rotor_mass", {{"dm", 2e-4}})}) {
    const MaglevExtended plant(p, measured, true, {e}, 3.25e-3);
    const Eigen::VectorXd x = plant.equilibrium_state();
    EXPECT_NEAR(x[2], 0.019, 1e-15) << e.name;
    EXPECT_NEAR(plant.derivative(x, plant.equilibrium_input(), kNoForce).norm(), 0.0, 1e-9) << e.name;
    // The stiffness is n_x g / x0 (m cancels), as maglev_linearize.hpp has it.
    const double h = 1e-7;
    Eigen::VectorXd up = x, down = x;
    up[0] += h;
    down[0] -= h;
    const double stiffness = (plant.derivative(up, plant.equilibrium_input(), kNoForce)[1] -
                              plant.derivative(down, plant.equilibrium_input(), kNoForce)[1]) /
                             (2 * h);
    EXPECT_NEAR(stiffness / (plant.parameters().n_x * p.g / 0.014), 1.0, 1e-6) << e.name;
  }
}

TEST(MaglevExtended, SensorEffectsMapTheTrueGapAndTheOperatingPointIsWhereTheSensorReadsX0) {
  const MaglevParameters p = MaglevParameters::nominal();
  const MaglevOperatingPoint op{0.014, 0.019, 4.0};
  const MaglevExtended plant(p, op, true,
                             {effect("sensor_gain", {{"dgain", 0.04}}), effect("sensor_offset", {{"dy", 3e-4}}),
                              effect("sensor_nonlinearity", {{"dp", 0.2}})},
                             3.25e-3);
  const double gap = 0.0157;
  EXPECT_NEAR(plant.output(Eigen::Vector3d(gap, 0.0, 0.02))[0], 1.04 * 0.014 * std::pow(gap / 0.014, 1.2) + 3e-4,
              1e-15);
  EXPECT_NEAR(plant.output(plant.equilibrium_state())[0], 0.014, 1e-15);
  EXPECT_NEAR(plant.operating_gap(), 0.014 * std::pow((0.014 - 3e-4) / (1.04 * 0.014), 1 / 1.2), 1e-15);
}

TEST(MaglevExtended, TheDacRoundsTheCommandAndResistanceAndGainMoveTheCoil) {
  const MaglevParameters p = MaglevParameters::nominal();
  const MaglevOperatingPoint op{0.014, 0.019, 4.0};
  const Eigen::Vector3d x(0.014, 0.0, 0.019);
  const MaglevExtended dac(p, op, true, {effect("actuator_quantisation", {{"step", 0.35}})}, 3.25e-3);
  const MaglevExtended ideal(p, op, true, {}, 3.25e-3);
  EXPECT_NEAR(dac.derivative(x, Eigen::VectorXd::Constant(1, 4.1), kNoForce)[2],
              ideal.derivative(x, Eigen::VectorXd::Constant(1, 4.2), kNoForce)[2], 1e-12);  // 12 x 0.35
  const MaglevExtended coil(
      p, op, true, {effect("coil_resistance", {{"dR", 25.0}}), effect("amplifier_gain", {{"dkw", 0.1}})}, 3.25e-3);
  EXPECT_NEAR(coil.derivative(x, Eigen::VectorXd::Constant(1, 4.0), kNoForce)[2], (1.1 * 4.0 - 235.0 * 0.019) / p.L,
              1e-12);
}

// With the command logged at 0.01 V the DAC rounds the command as logged: a step of 0.3503 V has
// its edge between levels 11 and 12 at 11.5 x 0.3503 = 4.02845 V, so 4.026 (logged 4.03) goes
// up to 12 x 0.3503 where the exact command would stay at 11 x 0.3503.
TEST(MaglevExtended, TheDacRoundsTheCommandAsLogged) {
  const MaglevParameters p = MaglevParameters::nominal();
  const MaglevOperatingPoint op{0.014, 0.019, 4.0};
  const Eigen::Vector3d x(0.014, 0.0, 0.019);
  const std::vector<Effect> dac = {effect("actuator_quantisation", {{"step", 0.3503}})};
  const MaglevExtended logged(p, op, true, dac, 3.25e-3, 0.01), exact(p, op, true, dac, 3.25e-3);
  const MaglevExtended ideal(p, op, true, {}, 3.25e-3);
  const Eigen::VectorXd u = Eigen::VectorXd::Constant(1, 4.026);
  EXPECT_NEAR(logged.derivative(x, u, kNoForce)[2],
              ideal.derivative(x, Eigen::VectorXd::Constant(1, 12 * 0.3503), kNoForce)[2], 1e-12);
  EXPECT_NEAR(exact.derivative(x, u, kNoForce)[2],
              ideal.derivative(x, Eigen::VectorXd::Constant(1, 11 * 0.3503), kNoForce)[2], 1e-12);
  EXPECT_THAT([&] { MaglevExtended(p, op, true, dac, 3.25e-3, -0.01); },
              ::testing::ThrowsMessage<Error>(HasSubstr("the command's logging resolution must be finite and >= 0")));
}

TEST(MaglevExtended, TheDelayedReadingLagsByWholeAndFractionalSamples) {
  const MaglevParameters p = MaglevParameters::nominal();
  const MaglevOperatingPoint op{0.014, p.equilibrium_current(0.014), 0.0};
  const double dt = 3.25e-3;
  auto readings = [&](const std::vector<Effect>& effects) {
    const MaglevExtended plant(p, op, false, effects, dt);
    Eigen::VectorXd x = plant.equilibrium_state();
    const Eigen::VectorXd u = Eigen::VectorXd::Constant(1, 0.9 * plant.equilibrium_input()[0]);  // it falls
    std::vector<double> y;
    for (int k = 0; k < 12; ++k) {
      y.push_back(plant.output(x)[0]);
      plant.advance(x, u, kNoForce, dt, 1);
    }
    return y;
  };
  const auto now = readings({}), late = readings({effect("sensor_delay", {{"delay", 2 * dt}})}),
             between = readings({effect("sensor_delay", {{"delay", 1.5 * dt}})});
  for (std::size_t k = 2; k < now.size(); ++k) {
    EXPECT_NEAR(late[k], now[k - 2], 1e-15);
    EXPECT_NEAR(between[k], 0.5 * (now[k - 1] + now[k - 2]), 1e-15);
  }
}

TEST(MaglevExtended, BadEffectsAreClearErrors) {
  const MaglevParameters p = MaglevParameters::nominal();
  const MaglevOperatingPoint op{0.014, 0.019, 4.0};
  EXPECT_THAT(
      [&] {
        MaglevExtended(p, op, true, {make_effect("eddy_current", {{"tau", 1e-4}})}, 1e-3);
      },
      ::testing::ThrowsMessage<Error>(HasSubstr("unknown effect 'eddy_current' (known: force_law")));
  EXPECT_THAT(
      [&] {
        MaglevExtended(p, op, true, {Effect{"coil_resistance", 0, {{"dR", -210.0}}}}, 1e-3);
      },
      ::testing::ThrowsMessage<Error>(HasSubstr("the effects make the plant invalid")));
  EXPECT_THAT(
      [&] {
        MaglevExtended(p, op, true, {effect("sensor_offset", {{"dy", 4e-3}})}, 1e-3);
      },
      ::testing::ThrowsMessage<Error>(HasSubstr("true operating gap outside the stops")));
}

// The stops are inelastic: with no voltage the body falls onto the ground and lies there at
// rest; 12 V pull it off, up against the top stop, where it rests again.
TEST(MaglevExtended, TheBodyRestsOnAStopUntilTheForcesPullItOff) {
  const MaglevParameters p = MaglevParameters::nominal();
  const MaglevExtended plant(p, {0.014, 0.019, 4.0}, true, {}, 1e-3);
  Eigen::VectorXd x = plant.equilibrium_state();
  for (int k = 0; k < 1000; ++k) plant.advance(x, Eigen::VectorXd::Zero(1), kNoForce, 1e-3, 1);
  EXPECT_EQ(x[0], p.x_max);
  EXPECT_EQ(x[1], 0.0);
  EXPECT_NEAR(x[2], 0.0, 1e-12);
  for (int k = 0; k < 1000; ++k) plant.advance(x, Eigen::VectorXd::Constant(1, 12.0), kNoForce, 1e-3, 1);
  EXPECT_EQ(x[0], p.x_min);
  EXPECT_EQ(x[1], 0.0);
  EXPECT_NEAR(x[2], 12.0 / p.R, 1e-6);  // the coil at its steady current, the body held still
}

}  // namespace maglev_extended_test
}  // namespace ambid::sim
