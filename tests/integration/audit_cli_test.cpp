// `ambid sim --effect` and `ambid audit` as a user runs them: a hidden effect is named in
// audit.json, the extended model and the HTML report are written, the report renders in
// headless Chromium, and bad input fails clearly.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "core/experiment_io.hpp"

namespace ambid {
namespace audit_cli_test {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

using cli_test::CommandResult;
using cli_test::fresh_dir;
using cli_test::read_json;
using cli_test::run_ambid;

// The command fails with exit code 1 and a message containing `message`.
void expect_failure(const std::string& args, const std::string& message) {
  const CommandResult r = run_ambid(args);
  EXPECT_EQ(r.status, 1) << args;
  EXPECT_THAT(r.output, HasSubstr(message)) << args;
}

const std::string kNoisy = " --duration 0.5 --amplitude 0.3 --position-noise 2e-9 --current-noise 2e-5 --seed 21";

TEST(SimEffectCli, EffectsChangeTheTruthNotTheSidecar) {
  const fs::path dir = fresh_dir("sim_effect");
  CommandResult r = run_ambid(
      "sim --duration 0.1 --effect amplifier_bandwidth --set channel=2 --set amplifier_bandwidth.tau=2e-4 "
      "--effect eddy_current --set eddy_current.tau=1e-4 --set R1=18 --out " +
      (dir / "two").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const Experiment e = read_experiment(dir / "two").experiment;
  EXPECT_DOUBLE_EQ(e.plant.parameters.at("R1"), 17.5);
  const auto& effects = e.extra.json()["simulation"]["effects"];
  ASSERT_EQ(effects.size(), 2u);
  EXPECT_EQ(effects[0]["effect"], "amplifier_bandwidth");
  EXPECT_EQ(effects[0]["channel"], 2);
  EXPECT_DOUBLE_EQ(effects[1]["parameters"]["tau"].get<double>(), 1e-4);
  EXPECT_TRUE(effects[1]["channel"].is_null());
  EXPECT_DOUBLE_EQ(e.extra.json()["simulation"]["true_parameters"]["R1"].get<double>(), 18.0);
}

TEST(SimEffectCli, UnknownEffectsAndParametersListTheValidOnes) {
  const fs::path dir = fresh_dir("sim_effect_bad");
  const std::string out = " --duration 0.1 --out " + (dir / "x").string();
  expect_failure("sim --effect eddy" + out, "unknown effect 'eddy' (known: coil_resistance, amplifier_gain");
  expect_failure("sim --effect sensor_delay --set tau=1e-4" + out, "valid: m x0 i0 R1 R2 Ls1 Ls2 K1 K2 kw1 kw2 delay");
  expect_failure("sim --effect sensor_delay --set delay=-1" + out, "outside");
  expect_failure("sim --effect amplifier_bandwidth --effect eddy_current --set tau=1e-4" + out, "EFFECT.tau");
  EXPECT_FALSE(fs::exists(dir / "x.csv"));
}

TEST(AuditCli, NamesTheHiddenEffectAndWritesItsFiles) {
  const fs::path dir = fresh_dir("audit_gain");
  ASSERT_EQ(
      run_ambid("sim" + kNoisy + " --effect sensor_gain --set dgain=-0.12 --out " + (dir / "run").string()).status, 0);
  const CommandResult r = run_ambid("audit " + (dir / "run.json").string() + " --out " + (dir / "audit").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("misses sensor_gain"));
  EXPECT_THAT(r.output, ::testing::Not(HasSubstr("ambid audit: screen")));  // no progress: stderr is a pipe
  const nlohmann::json a = read_json(dir / "audit" / "audit.json");
  EXPECT_EQ(a["clamped_samples"]["count"], 0);
  EXPECT_EQ(a["format"], "ambid-audit/1");
  EXPECT_EQ(a["experiment"], "run.json");
  EXPECT_EQ(a["cause"], "sensor_gain");
  EXPECT_NEAR(a["findings"][0]["parameters"]["dgain"].get<double>(), -0.12, 0.03);
  EXPECT_LT(a["findings"][0]["nrmse_total_after"].get<double>(), 0.7 * a["baseline"]["nrmse_total"].get<double>());
  const nlohmann::json m = read_json(dir / "audit" / a["extended_model"].get<std::string>());
  EXPECT_EQ(m["effects"][0]["effect"], "sensor_gain");
  std::ifstream html(dir / "audit" / "report.html");
  const std::string page((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
  EXPECT_THAT(page, HasSubstr("<svg"));
  EXPECT_THAT(page, HasSubstr("Residual spectra"));
  EXPECT_THAT(page, HasSubstr("Closed-loop frequency response"));
  EXPECT_THAT(page, HasSubstr("Plant frequency response"));
  EXPECT_THAT(page, HasSubstr("Measured / model frequency response ratio"));
  EXPECT_THAT(page, HasSubstr("Dependence on amplitude"));
  EXPECT_TRUE(a["frf_ratio"]["nominal"].contains("x/u1"));
}

TEST(AuditCli, RefusesWhatItCannotAudit) {
  const fs::path dir = fresh_dir("audit_bad");
  expect_failure("audit " + (dir / "missing.json").string() + " --out " + (dir / "a").string(), "missing");
  ASSERT_EQ(run_ambid("sim --duration 0.1 --excitation none --out " + (dir / "quiet").string()).status, 0);
  expect_failure("audit " + (dir / "quiet.json").string() + " --out " + (dir / "a").string(), "no excitation");
  ASSERT_EQ(run_ambid("sim --duration 0.1 --amplitude 0.3 --out " + (dir / "short").string()).status, 0);
  expect_failure("audit " + (dir / "short.json").string() + " --false-acceptance 1.5 --out " + (dir / "a").string(),
                 "false-acceptance probability must be in (0, 1)");
  EXPECT_FALSE(fs::exists(dir / "a" / "audit.json"));
}

// The screenshot of the report must carry far more than that of an empty page of the same size.
TEST(AuditCli, ReportRendersInHeadlessChromium) {
  if (cli_test::run_command("command -v chromium").status != 0)
    FAIL() << "chromium is not installed (scripts/setup.sh installs it)";
  const fs::path dir = fresh_dir("audit_chromium");
  ASSERT_EQ(run_ambid("sim" + kNoisy + " --effect harmonic_disturbance --set f=90 --set Fc=0.3 --out " +
                      (dir / "run").string())
                .status,
            0);
  ASSERT_EQ(run_ambid("audit " + (dir / "run.json").string() + " --out " + (dir / "audit").string()).status, 0);
  std::ofstream(dir / "empty.html") << "<!DOCTYPE html><html><body></body></html>\n";
  auto screenshot = [&](const fs::path& page, const fs::path& png) {
    const fs::path profile = dir / ("profile-" + png.stem().string());
    const CommandResult r = cli_test::run_command(
        "timeout 120 chromium --headless --no-sandbox --disable-gpu "
        "--disable-background-networking --disable-component-update --disable-sync "
        "--no-first-run --user-data-dir=" +
        profile.string() + " --screenshot=" + png.string() + " --window-size=1200,2400 file://" + page.string());
    EXPECT_EQ(r.status, 0) << r.output;
    return fs::exists(png) ? fs::file_size(png) : 0;
  };
  const auto report = screenshot(dir / "audit" / "report.html", dir / "report.png");
  const auto empty = screenshot(dir / "empty.html", dir / "empty.png");
  EXPECT_GT(empty, 0u);
  EXPECT_GT(report, 5 * empty) << "report " << report << " bytes, empty page " << empty << " bytes";
}

}  // namespace audit_cli_test
}  // namespace ambid
