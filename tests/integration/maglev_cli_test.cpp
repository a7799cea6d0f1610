// The single-coil maglev from the command line: `ambid sim --plant maglev1coil_voltage` writes a
// rig-like record the reader accepts, `ambid identify --method greybox` finds the truth's
// physical parameters in it, and what the record lacks for an audit is named.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.hpp"
#include "core/experiment_io.hpp"

namespace ambid {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

using cli_test::CommandResult;
using cli_test::fresh_dir;
using cli_test::run_ambid;

TEST(MaglevCli, SimulatedRigRecordIsIdentifiedWithinOnePercent) {
  const fs::path dir = fresh_dir("maglev_cli");
  const std::string stem = (dir / "run").string();
  CommandResult r = run_ambid(
      "sim --plant maglev1coil_voltage --duration 9.75 --set R=205 --set L=0.27 --set Km=1.62e-8 --set Ke=1.62e-8 "
      "--step-period 1.5 --seed 7 --out " +
      stem);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("3000 samples"));
  const Experiment e = read_experiment(stem + ".json").experiment;
  EXPECT_EQ(e.plant.model, "maglev1coil_voltage");
  EXPECT_DOUBLE_EQ(e.sample_time, 3.25e-3);
  EXPECT_EQ(e.y_names, (std::vector<std::string>{"x", "i"}));
  EXPECT_FALSE(e.controller.has_value());  // the contract's form has no reference input
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

  r = run_ambid("audit " + stem + ".json --out " + (dir / "audit").string());
  EXPECT_EQ(r.status, 1);
  // The rig's record has no controller in the contract's form and no r (w is not logged).
  EXPECT_THAT(r.output, HasSubstr("the experiment has no controller, so the loop cannot be replayed"));
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

}  // namespace
}  // namespace ambid
