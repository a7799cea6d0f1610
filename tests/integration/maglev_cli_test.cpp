// The single-coil maglev from the command line: `ambid sim --plant maglev1coil_voltage` writes a
// rig-like record the reader accepts, `ambid identify --method greybox` finds the truth's
// physical parameters in it, and what the record lacks for an audit is named.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.hpp"
#include "core/experiment_io.hpp"
#include "core/linalg.hpp"

namespace ambid {
namespace maglev_cli_test {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

using cli_test::CommandResult;
using cli_test::fresh_dir;
using cli_test::run_ambid;

// The positive eigenvalue of the true plant (the note's force law with the sidecar's true
// parameters) linearised analytically at the point (x0, i0), the force and back-EMF constants
// closed by gravity balance there (maglev_identification.hpp).
double true_unstable_pole(const Experiment& e, double x0, double i0) {
  const auto& p = e.extra.json().at("simulation").at("true_parameters");
  const double g = p.at("g"), n_i = p.at("n_i"), n_x = p.at("n_x"), L = p.at("L"), R = p.at("R");
  const double rho = p.at("Km").get<double>() * std::pow(i0, n_i) / (p.at("m").get<double>() * g * std::pow(x0, n_x));
  const double emf = n_i * p.at("Ke").get<double>() / rho * std::pow(i0, n_i - 1) / (std::pow(x0, n_x) * L);
  Eigen::Matrix3d A;
  A << 0, 1, 0, n_x * g / x0, 0, -n_i * g / i0, 0, emf, -R / L;
  return linalg::eigenvalues(A).real().maxCoeff();
}

// The rig-like record both tests below simulate (3.25 ms, reference steps every 1.5 s); add the
// output stem.
constexpr const char* kRigRecord =
    "sim --plant maglev1coil_voltage --duration 9.75 --set R=205 --set L=0.27 --set Km=1.62e-8 --set Ke=1.62e-8 "
    "--step-period 1.5 --seed 7 --out ";

TEST(MaglevCli, SimulatedRigRecordIsIdentifiedWithinOnePercent) {
  const fs::path dir = fresh_dir("maglev_cli");
  const std::string stem = (dir / "run").string();
  CommandResult r = run_ambid(std::string(kRigRecord) + stem);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("3000 samples"));
  const Experiment e = read_experiment(stem + ".json").experiment;
  EXPECT_EQ(e.plant.model, "maglev1coil_voltage");
  EXPECT_DOUBLE_EQ(e.sample_time, 3.25e-3);
  EXPECT_EQ(e.y_names, (std::vector<std::string>{"x", "i"}));
  ASSERT_TRUE(e.controller.has_value());                // the board's PID in the contract's form
  EXPECT_EQ(e.r_names, std::vector<std::string>{"r"});  // reconstructed from the logged u
  EXPECT_TRUE(e.extra.json().at("rig").contains("not_in_controller"));
  EXPECT_EQ(e.extra.json().at("operating_point_source"), "measured");

  r = run_ambid("identify " + stem + ".json --method greybox --out " + (dir / "model.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(dir / "model.json");
  const nlohmann::json model = nlohmann::json::parse(in);
  const auto& physical = model.at("physical");
  EXPECT_NEAR(physical.at("R").get<double>() / 205.0, 1.0, 0.01);
  EXPECT_NEAR(physical.at("L").get<double>() / 0.27, 1.0, 0.01);
  EXPECT_NEAR(physical.at("n_i").get<double>(), 1.0, 0.01);
  EXPECT_NEAR(physical.at("n_x").get<double>() / 4.0, 1.0, 0.01);
  EXPECT_NEAR(physical.at("Km").get<double>() / 1.62e-8, 1.0, 0.01);
}

// The structure per settled level (identifier/frequency_domain/frf_levels.hpp). One structure
// fitted to the whole record's Welch FRF read 55.9 +- 0.66 rad/s, 6.6 % above the truth at the
// first level (52.40): it averaged the plant over 13 to 16 mm, where b = n_i g / i0 changes
// 2.3x. Per level, each at its own means, the unstable pole against the truth's linearisation
// at those means; at the operating point (the first level's means) the level there, and all
// levels pooled there.
TEST(MaglevCli, FrfUnstablePolePerLevelOfASimulatedRigRecord) {
  const fs::path dir = fresh_dir("maglev_cli_frf");
  const std::string stem = (dir / "run").string();
  CommandResult r = run_ambid(std::string(kRigRecord) + stem);
  ASSERT_EQ(r.status, 0) << r.output;
  const Experiment e = read_experiment(stem + ".json").experiment;

  r = run_ambid("frf " + stem + ".json --out " + (dir / "frf").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("structure: unstable_pole "));
  EXPECT_THAT(r.output, HasSubstr("structure at x = 0.014 ("));
  std::ifstream frf_in(dir / "frf" / "frf.json");
  const nlohmann::json frf = nlohmann::json::parse(frf_in);
  const auto& structure = frf.at("structure");
  EXPECT_EQ(structure.at("level_signal"), "x");
  // Six levels; at 13 mm a controller clamp acts in all but one of its Welch segments.
  const auto& levels = structure.at("levels");
  ASSERT_EQ(levels.size(), 6u);
  int fitted = 0;
  for (const auto& level : levels) {
    const double x = level.at("operating_point").at("x"), i = level.at("operating_point").at("i");
    SCOPED_TRACE(x);
    if (!level.contains("derived")) continue;
    ++fitted;
    const auto& pole = level.at("derived").at("unstable_pole");
    const double truth = true_unstable_pole(e, x, i), value = pole.at("value"), sigma = pole.at("sigma");
    EXPECT_GT(sigma, 0.0);
    EXPECT_LT(sigma / truth, 0.05);
    EXPECT_NEAR(value / truth, 1.0, std::min(0.06, 3 * sigma / truth));
  }
  EXPECT_GE(fitted, 5);
  // At the measured operating point: the first level.
  EXPECT_EQ(structure.at("level_at_operating_point"), 0);
  const auto& pole = structure.at("derived").at("unstable_pole");
  const double truth = true_unstable_pole(e, e.operating_point.at("x"), e.operating_point.at("i"));
  EXPECT_NEAR(truth, 52.40, 0.01);
  EXPECT_NEAR(pole.at("value").get<double>() / truth, 1.0, std::min(0.05, 3 * pole.at("sigma").get<double>() / truth));
  // Every level carried to the operating point by gravity balance and pooled: half the sigma.
  const auto& pooled = structure.at("pooled_at_operating_point");
  EXPECT_EQ(pooled.at("levels"), fitted);
  const auto& pooled_pole = pooled.at("derived").at("unstable_pole");
  const double pooled_sigma = pooled_pole.at("sigma");
  EXPECT_LT(pooled_sigma, 0.7 * pole.at("sigma").get<double>());
  EXPECT_NEAR(pooled_pole.at("value").get<double>() / truth, 1.0, std::min(0.03, 3 * pooled_sigma / truth));
  EXPECT_LT(pooled_pole.at("birge_ratio").get<double>(), 2.0);  // the levels agree within their sigmas
}

TEST(MaglevCli, TouchAndUnknownPlantAreClearErrors) {
  const fs::path dir = fresh_dir("maglev_cli_errors");
  CommandResult r =
      run_ambid("sim --plant maglev1coil_voltage --duration 10 --rig Kp=2 --out " + (dir / "fall").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("the body touched the ground at t = "));
  r = run_ambid("sim --plant maglev2coil --out " + (dir / "x").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("unknown plant 'maglev2coil' (known: amb1dof_voltage, maglev1coil_voltage, lamstf)"));
  r = run_ambid("sim --plant amb1dof_voltage --rig Kp=2 --duration 0.01 --out " + (dir / "y").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("--rig and --levels are settings of a rig's own loop"));
}

}  // namespace maglev_cli_test
}  // namespace ambid
