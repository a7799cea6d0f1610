// `ambid sim` as a user runs it: the files it writes are read back by the reader, and bad
// options give a clear message and a non-zero exit.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "cli_run.hpp"
#include "core/experiment_io.hpp"
#include "stack_support.hpp"

namespace ambid {
namespace sim_cli_test {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

using cli_test::CommandResult;
using cli_test::fresh_dir;
using cli_test::run_ambid;

TEST(SimCli, WritesAnExperimentTheReaderAccepts) {
  const fs::path dir = fresh_dir("sim_nominal");
  const CommandResult r =
      run_ambid("sim --plant amb1dof_voltage --duration 0.2 --seed 7 --out " + (dir / "nominal").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("2000 samples"));
  const ReadResult read = read_experiment(dir / "nominal.json");
  const Experiment& e = read.experiment;
  EXPECT_EQ(e.samples(), 2000);
  EXPECT_EQ(e.plant.model, "amb1dof_voltage");
  EXPECT_DOUBLE_EQ(e.sample_time, 1e-4);
  ASSERT_TRUE(e.controller.has_value());
  EXPECT_EQ(e.r_names, (std::vector<std::string>{"r1", "r2"}));
  EXPECT_TRUE(read.warnings.empty());
  // Levitating: the rotor stays within 5 % of the 0.35 mm gap.
  EXPECT_LT(e.y_deviation().col(0).cwiseAbs().maxCoeff(), 0.05 * 3.5e-4);
}

TEST(SimCli, SetChangesTheTruthNotTheSidecar) {
  const fs::path dir = fresh_dir("sim_fault");
  const CommandResult r = run_ambid("sim --duration 0.2 --set R1=21 --out " + (dir / "hot").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const Experiment e = read_experiment(dir / "hot").experiment;
  EXPECT_DOUBLE_EQ(e.plant.parameters.at("R1"), 17.5);
  EXPECT_DOUBLE_EQ(e.extra.json()["simulation"]["true_parameters"]["R1"].get<double>(), 21.0);
  // With the hotter coil the controller must command more voltage on coil 1 in steady state.
  EXPECT_GT(e.u.col(0).tail(500).mean(), 8.75 * 1.1);
}

TEST(SimCli, BadOptionsFailClearly) {
  const fs::path dir = fresh_dir("sim_bad");
  const std::string out = " --out " + (dir / "x").string();
  CommandResult r = run_ambid("sim --set R3=1" + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("R3"));
  r = run_ambid("sim --set R1=abc" + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("'abc' is not a finite number"));
  r = run_ambid("sim --plant lamstf9" + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("unknown plant 'lamstf9'"));
  r = run_ambid("sim --duration -2" + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("duration"));
  r = run_ambid("sim");
  EXPECT_NE(r.status, 0);
  EXPECT_THAT(r.output, HasSubstr("--out is required"));
  EXPECT_FALSE(fs::exists(dir / "x.csv"));
}

}  // namespace sim_cli_test
}  // namespace ambid
