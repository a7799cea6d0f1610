// `ambid sim` then `ambid identify` as a user runs them: the written model.json against the
// true linearised parameters of the simulated bearing (experiment-format.md, seed 000 eq. 4 at
// the contract's nominal values), and bad input -> a clear message and exit code 1.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "cli_run.hpp"
#include "core/experiment_file.hpp"
#include "core/model_file.hpp"
#include "plant_sim/amb1dof_parameters.hpp"
#include "plant_sim/amb1dof_physical.hpp"

namespace ambid {
namespace identify_cli_test {

using cli_test::CommandResult;
using cli_test::fresh_dir;
using cli_test::run_ambid;
using nlohmann::json;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

// experiment-format.md, "Plant model amb1dof_voltage" (exact to the digits printed there).
const std::map<std::string, double> kTrueV = {{"v1", 777777.8}, {"v2", 272.222}, {"v3", 272.222},
                                              {"v4", 1142.191}, {"v5", 40.7925}, {"v6", 1142.191},
                                              {"v7", 40.7925},  {"v8", 2.33100}, {"v9", 2.33100}};

// A 0.4 s nominal run (PRBS 0.05 V), shared by the tests of one directory.
fs::path simulate(const fs::path& dir, const std::string& extra = "") {
  const fs::path stem = dir / "run";
  const CommandResult r = run_ambid("sim --duration 0.4 --seed 3 " + extra + " --out " + stem.string());
  EXPECT_EQ(r.status, 0) << r.output;
  return stem;
}

void check_parameters(const Model& m, double tolerance) {
  for (const auto& [name, truth] : kTrueV) {
    ASSERT_TRUE(m.parameters.count(name)) << name;
    EXPECT_NEAR(m.parameters.at(name) / truth - 1.0, 0.0, tolerance) << name;
  }
}

TEST(IdentifyCli, DeadbeatModelFileHasTheTrueParameters) {
  const fs::path dir = fresh_dir("identify_deadbeat");
  const fs::path stem = simulate(dir);
  const fs::path out = dir / "model.json";
  const CommandResult r = run_ambid("identify " + stem.string() + ".json --method deadbeat --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("wrote " + out.string()));
  const Model m = read_model(out);
  EXPECT_EQ(m.method, "deadbeat");
  EXPECT_EQ(m.plant_model, "amb1dof_voltage");
  EXPECT_EQ(m.sample_time, 1e-4);
  ASSERT_TRUE(m.continuous.has_value());
  check_parameters(m, 1e-3);  // the nonlinear plant: measured errors below 3e-4
  EXPECT_NEAR(m.physical.at("R1"), 17.5, 17.5 * 1e-3);
  EXPECT_NEAR(m.physical.at("kw2"), 1.0, 1e-3);
  EXPECT_GT(m.uncertainty.at("v5"), 0.0);
  EXPECT_LT(m.uncertainty.at("v5"), 0.01 * 40.79);
  // Validated on the last 25 %: the model reproduces the closed loop.
  for (const char* y : {"x", "i1", "i2"}) {
    ASSERT_TRUE(m.fit_nrmse.count(y)) << y;
    EXPECT_LT(m.fit_nrmse.at(y), 0.01) << y;
  }
  // The open-loop unstable plant stays unstable, its pole where the true linear model has it.
  const ContinuousSystem truth =
      sim::amb1dof_structure_system(sim::amb1dof_structure_parameters(sim::Amb1dofParameters::nominal()));
  const double unstable = poles(truth).real().maxCoeff();
  EXPECT_GT(unstable, 400.0);
  EXPECT_NEAR(poles(*m.continuous).real().maxCoeff() / unstable, 1.0, 1e-3);
}

TEST(IdentifyCli, EraAndPredictionErrorMethodsGiveThePhysicalParametersWithSigmas) {
  const fs::path dir = fresh_dir("identify_era");
  const fs::path stem = simulate(dir);
  for (const std::string method : {"okid", "closed-loop", "projection", "pem"}) {
    SCOPED_TRACE(method);
    const fs::path out = dir / (method + ".json");
    const CommandResult r = run_ambid("identify " + stem.string() + " --method " + method + " --out " + out.string());
    ASSERT_EQ(r.status, 0) << r.output;
    const Model m = read_model(out);
    check_parameters(m, 2e-3);
    EXPECT_LT(m.fit_nrmse.at("x"), 0.01);
    // model.json has a one-sigma uncertainty for every parameter and physical quantity.
    for (const auto* group : {&m.parameters, &m.physical})
      for (const auto& [name, value] : *group) {
        ASSERT_TRUE(m.uncertainty.count(name)) << name;
        EXPECT_GT(m.uncertainty.at(name), 0.0) << name;
      }
  }
}

// Rewrites the sidecar of `stem` with `edit` applied.
void edit_sidecar(const fs::path& stem, void (*edit)(json&)) {
  json j = json::parse(read_text_file(stem.string() + ".json"));
  edit(j);
  std::ofstream(stem.string() + ".json") << j.dump(2);
}

TEST(IdentifyCli, BadInputFailsClearly) {
  const fs::path dir = fresh_dir("identify_bad");
  const fs::path stem = simulate(dir);
  const std::string out = " --out " + (dir / "model.json").string();
  CommandResult r = run_ambid("identify " + stem.string() + " --method n4sid" + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("unknown method 'n4sid'"));
  r = run_ambid("identify " + (dir / "absent").string() + " --method deadbeat" + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("absent.json"));
  r = run_ambid("identify " + stem.string() + " --method deadbeat --order 6" + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("--order 6"));
  r = run_ambid("identify " + stem.string() + out);
  EXPECT_NE(r.status, 0);
  EXPECT_THAT(r.output, HasSubstr("--method is required"));

  const fs::path shortrun = dir / "short";
  ASSERT_EQ(run_ambid("sim --duration 0.002 --out " + shortrun.string()).status, 0);
  r = run_ambid("identify " + shortrun.string() + " --method closed-loop" + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("needs more than"));

  edit_sidecar(stem, [](json& j) { j["controller"]["D"][0][0] = 0.5; });  // inputs start with u1
  r = run_ambid("identify " + stem.string() + " --method closed-loop" + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("algebraic loop"));  // refused by the reader already

  edit_sidecar(stem, [](json& j) { j.erase("controller"); });
  for (const char* method : {"deadbeat", "closed-loop"}) {
    r = run_ambid("identify " + stem.string() + " --method " + method + out);
    EXPECT_EQ(r.status, 1) << method;
    EXPECT_THAT(r.output, HasSubstr("no controller")) << method;
  }
  EXPECT_FALSE(fs::exists(dir / "model.json"));
}

}  // namespace identify_cli_test
}  // namespace ambid
