// maglev1coil_voltage: the plant, its linearisation and the rig loop against analytic truths.
#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "plant_sim/families.hpp"
#include "plant_sim/integrator.hpp"
#include "plant_sim/linearize.hpp"
#include "plant_sim/maglev1coil_voltage.hpp"
#include "plant_sim/maglev_linearize.hpp"
#include "plant_sim/maglev_loop.hpp"

namespace ambid::sim {
namespace maglev_test {

constexpr double kG = 9.81;

TEST(Maglev, EquilibriumCurrentBalancesGravity) {
  const MaglevParameters dipole = MaglevParameters::nominal();  // n_i = 1, n_x = 4
  EXPECT_NEAR(dipole.equilibrium_current(0.014), 7.4e-4 * kG * std::pow(0.014, 4) / 1.5e-8, 1e-15);
  MaglevParameters reluctance = dipole;  // i = x sqrt(m g / Km)
  reluctance.n_i = 2.0;
  reluctance.n_x = 2.0;
  reluctance.Km = 3.333e-6;
  EXPECT_NEAR(reluctance.equilibrium_current(0.015), 0.015 * std::sqrt(7.4e-4 * kG / 3.333e-6), 1e-14);
  // The body held there does not move, and the coil current holds.
  const Maglev1coilVoltage plant(reluctance, 0.015);
  const Eigen::VectorXd d =
      plant.derivative(plant.equilibrium_state(), plant.equilibrium_input(), Eigen::VectorXd::Zero(1));
  EXPECT_NEAR(d.norm(), 0.0, 1e-12);
}

TEST(Maglev, LinearisationMatchesCentralDifferencesAndTheAnalyticPole) {
  const MaglevParameters p = MaglevParameters::nominal();
  const Maglev1coilVoltage plant(p, 0.0145);
  const MaglevLinearization lin = maglev_linearize(p, 0.0145);
  LinearizeOptions o;
  o.state_scale = Eigen::Vector3d(0.0145, 0.1, 0.02);
  o.input_scale = Eigen::VectorXd::Constant(1, 4.0);
  const ContinuousSystem numeric = linearize(plant, o);
  EXPECT_LT((lin.system.A - numeric.A).norm(), 1e-6 * numeric.A.norm());
  EXPECT_LT((lin.system.B - numeric.B).norm(), 1e-6 * numeric.B.norm());
  EXPECT_LT((lin.system.C - numeric.C).norm(), 1e-9);
  EXPECT_NEAR(lin.unstable_pole, std::sqrt(4.0 * kG / 0.0145), 1e-12);  // sqrt(n_x g / x0) = 52.0 rad/s
  // With the current held, the mechanical rows alone have the poles +-sqrt(n_x g / x0).
  const Eigen::VectorXcd mech = linalg::eigenvalues(Eigen::MatrixXd(lin.system.A.topLeftCorner(2, 2)));
  EXPECT_NEAR(std::max(mech(0).real(), mech(1).real()), std::sqrt(4.0 * kG / 0.0145), 1e-9);
  // With the voltage driven coil, the open loop still has one real unstable pole.
  const Eigen::VectorXcd full = linalg::eigenvalues(lin.system.A);
  int unstable = 0;
  for (const auto& z : full) unstable += z.real() > 0.0;
  EXPECT_EQ(unstable, 1);
}

TEST(Maglev, MeasuredPointClosesTheForceConstantByGravityBalance) {
  const MaglevParameters p = MaglevParameters::nominal();
  const MaglevLinearization lin = maglev_linearize_measured(p, {0.014, 0.019, 4.0});
  EXPECT_NEAR(lin.Km, 7.4e-4 * kG * std::pow(0.014, 4) / 0.019, 1e-20);
  // The mechanical row needs neither Km nor m: n_x g / x0 and n_i g / i0.
  EXPECT_NEAR(lin.system.A(1, 0), 4.0 * kG / 0.014, 1e-9);
  EXPECT_NEAR(lin.system.A(1, 2), -kG / 0.019, 1e-9);
  // The nominal model holds 14 mm with 18.6 mA: the measured 19 mA is 2 % above it.
  EXPECT_NEAR(lin.nominal_current, p.equilibrium_current(0.014), 1e-15);
  EXPECT_NEAR(lin.current_ratio, 0.019 / p.equilibrium_current(0.014), 1e-12);
  EXPECT_THROW(maglev_linearize_measured(p, {0.011, 0.019, 4.0}), Error);  // above the top stop
  EXPECT_THROW(maglev_linearize_measured(p, {0.014, -0.019, 4.0}), Error);
}

TEST(Maglev, RigRecordHasTheLoggersResolutionAndAMeasuredOperatingPoint) {
  MaglevRunOptions o;
  o.samples = 1500;
  const MaglevRun run = run_maglev_rig(MaglevParameters::nominal(), MaglevParameters::nominal(), MaglevRig{}, o);
  ASSERT_TRUE(run.ended.empty()) << run.ended;
  const Experiment& e = run.experiment;
  e.validate();
  EXPECT_EQ(e.samples(), 1500);
  for (Eigen::Index k = 0; k < e.samples(); ++k) {
    EXPECT_NEAR(e.y(k, 0) * 1e5, std::round(e.y(k, 0) * 1e5), 1e-6);  // 0.01 mm
    EXPECT_NEAR(e.u(k, 0) * 1e2, std::round(e.u(k, 0) * 1e2), 1e-6);  // 0.01 V
  }
  EXPECT_EQ(e.extra.json().at("operating_point_source"), "measured");
  // The first level is 14 mm: the PID's integral action holds it, at the true equilibrium current.
  EXPECT_NEAR(e.operating_point.at("x"), 0.014, 2e-5);
  EXPECT_NEAR(e.operating_point.at("i"), MaglevParameters::nominal().equilibrium_current(0.014), 3e-4);
}

TEST(Maglev, ATouchEndsTheRecordWithItsMessage) {
  MaglevRig weak;  // too little gain for the step to 16 mm: the body lands on the ground
  weak.Kp = 2.0;
  MaglevRunOptions o;
  o.samples = 4000;
  const MaglevRun fall = run_maglev_rig(MaglevParameters::nominal(), MaglevParameters::nominal(), weak, o);
  EXPECT_NE(fall.ended.find("touched the ground"), std::string::npos) << fall.ended;
  EXPECT_LT(fall.experiment.samples(), 4000);
  EXPECT_LT(fall.experiment.y.col(0).maxCoeff(), 0.017);

  MaglevRig offset;  // the sensor reads 3 mm too far: the loop pulls the body against the top
  offset.sensor_offset = 0.003;
  const MaglevRun lift = run_maglev_rig(MaglevParameters::nominal(), MaglevParameters::nominal(), offset, o);
  EXPECT_NE(lift.ended.find("touched the top stop"), std::string::npos) << lift.ended;

  ScenarioOptions s = plant_family("maglev1coil_voltage", "test").default_options();
  s.rig["Kp"] = 2.0;
  try {
    simulate_scenario(s);
    FAIL() << "a touch must end the simulation";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("touched the ground at t = "), std::string::npos) << error.what();
  }
}

TEST(Maglev, TheDacQuantisesTheCoilVoltage) {
  MaglevRig rig;
  rig.dac_step = 0.35;
  EXPECT_DOUBLE_EQ(rig.dac(4.1), 4.2);  // 12 steps
  EXPECT_DOUBLE_EQ(rig.dac(3.85), 3.85);
  // In the loop the coil sees the quantised command: the current follows the exact
  // zero-order-hold response to dac(u) (the back-EMF of a slowly moving body aside), not to u.
  rig.log_x = rig.log_u = rig.log_i = 0.0;
  MaglevRunOptions o;
  o.samples = 600;
  const MaglevParameters p = MaglevParameters::nominal();
  const Experiment e = run_maglev_rig(p, p, rig, o).experiment;
  const double a = std::exp(-p.R / p.L * o.sample_time);
  double quantised = 0.0, raw = 0.0;
  for (Eigen::Index k = 0; k + 1 < e.samples(); ++k) {
    const double base = a * e.y(k, 1);
    quantised += std::pow(e.y(k + 1, 1) - base - (1 - a) * p.kw / p.R * rig.dac(e.u(k, 0)), 2);
    raw += std::pow(e.y(k + 1, 1) - base - (1 - a) * p.kw / p.R * e.u(k, 0), 2);
  }
  const double rms_quantised = std::sqrt(quantised / double(e.samples() - 1));
  EXPECT_LT(rms_quantised, 2e-5);  // A; the back-EMF is ~1e-3 of the voltage
  EXPECT_GT(std::sqrt(raw / double(e.samples() - 1)), 10 * rms_quantised);
}

TEST(Maglev, RecordDoesNotDependOnTheIntegrationStep) {
  MaglevRunOptions coarse;
  coarse.samples = 1000;
  MaglevRunOptions fine = coarse;
  fine.substeps = 4 * coarse.substeps;
  MaglevRig rig;
  rig.log_x = rig.log_u = rig.log_i = 0.0;
  const MaglevParameters p = MaglevParameters::nominal();
  const Experiment a = run_maglev_rig(p, p, rig, coarse).experiment, b = run_maglev_rig(p, p, rig, fine).experiment;
  // 20 RK4 steps per sample: both within 1 % of the logger's resolution (0.01 mm, 0.01 mA).
  EXPECT_LT((a.y.col(0) - b.y.col(0)).cwiseAbs().maxCoeff(), 1e-7);  // m
  EXPECT_LT((a.y.col(1) - b.y.col(1)).cwiseAbs().maxCoeff(), 1e-7);  // A
}

TEST(PlantFamilies, UnknownFamilyIsRefusedWithTheKnownOnes) {
  try {
    plant_family("maglev2coil", "sim");
    FAIL();
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(),
                 "sim: unknown plant 'maglev2coil' (known: amb1dof_voltage, maglev1coil_voltage, lamstf)");
  }
  ScenarioOptions o;
  o.plant = "maglev1coil_voltage";
  try {
    build_scenario(o);
    FAIL();
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("plant model 'maglev1coil_voltage' has no scenario"), std::string::npos)
        << error.what();
  }
  o.controller = "pid";
  o.excitation = "uniform";
  o.effects.push_back(make_effect("sensor_gain"));
  EXPECT_THROW(simulate_scenario(o), Error);  // the rig's errors are rig settings
}

}  // namespace maglev_test
}  // namespace ambid::sim
