// `ambid frf` as a user runs it: `ambid sim --excitation multisine` then `ambid frf`; frf.json
// holds the open-loop plant recovered from closed-loop data, checked against the analytic
// linearisation of amb1dof_voltage (plant_sim), the fitted unstable pole, the ISO zones; the
// plots are well-formed SVG; data that cannot support an FRF give a clear error.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <fstream>
#include <iterator>
#include <map>
#include <numbers>
#include <random>
#include <set>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "core/experiment_io.hpp"
#include "core/linalg.hpp"
#include "core/state_space.hpp"
#include "plant_sim/amb1dof_voltage.hpp"
#include "plant_sim/closed_loop.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid {
namespace frf_cli_test {

using cli_test::CommandResult;
using cli_test::run_ambid;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

// The sampled linear plant's response at f: C (e^{jwT} I - A)^-1 B + D of its ZOH discretisation.
Eigen::MatrixXcd sampled_linear_plant(double f, double T) {
  const DiscreteSystem d = c2d_zoh(sim::Amb1dofVoltage().linearize(), T);
  const std::complex<double> z = std::exp(std::complex<double>(0.0, 2.0 * std::numbers::pi * f * T));
  const Eigen::MatrixXcd resolvent =
      z * Eigen::MatrixXcd::Identity(d.A.rows(), d.A.cols()) - d.A.cast<std::complex<double>>();
  return d.C.cast<std::complex<double>>() *
             linalg::lu_solve(resolvent, Eigen::MatrixXcd(d.B.cast<std::complex<double>>())).x +
         d.D.cast<std::complex<double>>();
}

double unstable_pole_of_linear_plant() {
  const Eigen::VectorXcd p = poles(sim::Amb1dofVoltage().linearize());
  return p.real().maxCoeff();
}

// One simulated experiment and its analysis serve every check (each test binary run costs a
// simulation and an analysis, so the checks are helpers of one test).
void check_plant_x_u1(const nlohmann::json& frf) {
  const auto f = frf["frequency_hz"].get<std::vector<double>>();
  ASSERT_EQ(f.size(), 1000u);
  const nlohmann::json& pair = frf["plant"]["x/u1"];
  const auto re = pair["re"].get<std::vector<double>>();
  const auto im = pair["im"].get<std::vector<double>>();
  ASSERT_EQ(re.size(), f.size());
  ASSERT_EQ(im.size(), f.size());
  ASSERT_EQ(pair["noise_std"].size(), f.size());
  double worst_magnitude = 0.0, worst_phase = 0.0;
  int checked = 0;
  for (std::size_t l = 0; l < f.size(); ++l) {
    if (f[l] >= 1000.0) continue;
    const std::complex<double> G(re[l], im[l]);
    const std::complex<double> G0 = sampled_linear_plant(f[l], 1e-4)(0, 0);
    worst_magnitude = std::max(worst_magnitude, std::abs(std::abs(G) / std::abs(G0) - 1.0));
    worst_phase = std::max(worst_phase, std::abs(std::arg(G / G0)) * 180.0 / std::numbers::pi);
    ++checked;
  }
  EXPECT_EQ(checked, 999);
  ::testing::Test::RecordProperty("x_u1_worst_magnitude_error", std::to_string(worst_magnitude));
  ::testing::Test::RecordProperty("x_u1_worst_phase_error_deg", std::to_string(worst_phase));
  EXPECT_LT(worst_magnitude, 0.01);
  EXPECT_LT(worst_phase, 1.0);
}

void check_unstable_pole(const nlohmann::json& frf) {
  const double truth = unstable_pole_of_linear_plant();
  EXPECT_NEAR(truth, 455.06, 0.01);
  const nlohmann::json& model = frf["model"]["x/u1"];
  ASSERT_FALSE(model["poles"].empty());
  double found = 0.0;
  for (const auto& p : model["unstable_poles"])
    if (p[1].get<double>() == 0.0) found = std::max(found, p[0].get<double>());
  ::testing::Test::RecordProperty("x_u1_unstable_pole", std::to_string(found));
  EXPECT_LT(std::abs(found - truth), 0.01 * truth);
}

void check_sensitivity(const nlohmann::json& frf, const std::string& summary) {
  for (const char* loop : {"u1", "u2", "sigma_max"}) {
    const nlohmann::json& s = frf["sensitivity"][loop];
    ASSERT_TRUE(s.is_object()) << loop;
    const double peak_db = s["peak_db"].get<double>();
    EXPECT_GT(s["peak_hz"].get<double>(), 0.0) << loop;
    // The zone follows from the peak by the ISO 14839-3 limits (a limit value is the worse zone).
    const std::string zone = peak_db < 9.5 ? "A" : peak_db < 12.0 ? "B" : peak_db < 14.0 ? "C" : "D";
    EXPECT_EQ(s["zone"], zone) << loop;
    EXPECT_THAT(summary, HasSubstr(std::string("sensitivity ") + loop + ": peak"));
  }
}

void check_plots(const fs::path& out) {
  for (const char* name : {"bode_x_u1.svg", "bode_x_u2.svg", "bode_i1_u1.svg", "bode_i2_u2.svg", "sensitivity_u1.svg",
                           "sensitivity_u2.svg", "sensitivity_sigma_max.svg"}) {
    const fs::path file = out / name;
    ASSERT_TRUE(fs::exists(file)) << name;
    EXPECT_GT(fs::file_size(file), 1000u) << name;
    EXPECT_TRUE(cli_test::well_formed_xml(file)) << name;
  }
}

TEST(FrfCli, MultisineExperimentGivesPlantPoleZonesAndPlots) {
  const fs::path dir = cli_test::fresh_dir("frf_cli");
  // 7 one-second periods, Hadamard blocks of 2: one period discarded, two blocks -> noise std.
  const CommandResult sim = run_ambid("sim --excitation multisine --duration 7 --seed 3 --f-min 1 --f-max 1000 --out " +
                                      (dir / "ms").string());
  ASSERT_EQ(sim.status, 0) << sim.output;
  const CommandResult frf = run_ambid("frf " + (dir / "ms.json").string() + " --out " + (dir / "frf").string());
  ASSERT_EQ(frf.status, 0) << frf.output;
  EXPECT_THAT(frf.output, HasSubstr("model x/u1"));
  const nlohmann::json json = cli_test::read_json(dir / "frf" / "frf.json");
  {
    SCOPED_TRACE("plant x/u1");
    check_plant_x_u1(json);
  }
  {
    SCOPED_TRACE("unstable pole");
    check_unstable_pole(json);
  }
  {
    SCOPED_TRACE("sensitivity");
    check_sensitivity(json, frf.output);
  }
  {
    SCOPED_TRACE("plots");
    check_plots(dir / "frf");
  }
}

// A record from another generator: plant_sim's bearing and controller driven by a zippered
// random-phase multisine written here (0.2 s period, 5 Hz grid, r1 on the odd and r2 on the
// even lines, 5 Hz to 1 kHz, 4 s), written without any excitation description.
fs::path foreign_zippered_record(const fs::path& dir) {
  const Eigen::Index N = 2000, samples = 40000;
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * std::numbers::pi);
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(samples, 2);
  for (Eigen::Index k = 1; k <= 200; ++k) {
    const double phi = phase(rng);
    for (Eigen::Index n = 0; n < samples; ++n)
      r(n, (k + 1) % 2) += 0.005 * std::cos(2.0 * std::numbers::pi * static_cast<double>(k * (n % N)) / 2000.0 + phi);
  }
  sim::ScenarioOptions s;
  s.duration = 4.0;
  sim::Scenario scenario = sim::build_scenario(s);
  scenario.options.excitation = r;
  scenario.header.extra.json().erase("excitation");
  write_experiment(sim::run_closed_loop(*scenario.truth, scenario.header, scenario.options), dir / "foreign");
  return dir / "foreign.json";
}

TEST(FrfCli, ForeignPeriodicRecordIsAnalysedAtItsExactLines) {
  const fs::path dir = cli_test::fresh_dir("frf_cli_foreign");
  const fs::path record = foreign_zippered_record(dir);
  ASSERT_FALSE(cli_test::read_json(record).contains("excitation"));
  const CommandResult frf = run_ambid("frf " + record.string() + " --out " + (dir / "frf").string());
  ASSERT_EQ(frf.status, 0) << frf.output;
  EXPECT_THAT(frf.output, HasSubstr("periodic estimate (unknown excitation"));
  EXPECT_THAT(frf.output, HasSubstr("periodic r (detected in the record): period 2000 samples (0.2 s), 20 whole "
                                    "periods, 1 discarded as transient, 19 used; local rational"));
  EXPECT_THAT(frf.output, HasSubstr("r1: 100 excited lines 5-995 Hz on a 5 Hz grid"));
  EXPECT_THAT(frf.output, HasSubstr("r2: 100 excited lines 10-1e+03 Hz on a 5 Hz grid"));
  const nlohmann::json json = cli_test::read_json(dir / "frf" / "frf.json");
  EXPECT_EQ(json["method"], "periodic");
  const nlohmann::json& p = json["periodic"];
  EXPECT_EQ(p["source"], "r");
  EXPECT_EQ(p["period_samples"], 2000);
  EXPECT_EQ(p["periods_used"], 19);
  EXPECT_EQ(p["lines_per_reference"]["r1"]["count"], 100);
  EXPECT_EQ(p["lines_per_reference"]["r2"]["dft_lines"][0], 2);
  // Exact lines: the analysis frequencies are the 200 excited lines, 5 Hz apart.
  const auto f = json["frequency_hz"].get<std::vector<double>>();
  ASSERT_EQ(f.size(), 200u);
  const auto re = json["plant"]["x/u1"]["re"].get<std::vector<double>>();
  const auto im = json["plant"]["x/u1"]["im"].get<std::vector<double>>();
  double worst_magnitude = 0.0, worst_phase = 0.0;
  for (std::size_t l = 0; l < f.size(); ++l) {
    EXPECT_NEAR(f[l], 5.0 * static_cast<double>(l + 1), 1e-9);
    if (f[l] >= 1000.0) continue;
    const std::complex<double> G(re[l], im[l]), G0 = sampled_linear_plant(f[l], 1e-4)(0, 0);
    worst_magnitude = std::max(worst_magnitude, std::abs(std::abs(G) / std::abs(G0) - 1.0));
    worst_phase = std::max(worst_phase, std::abs(std::arg(G / G0)) * 180.0 / std::numbers::pi);
  }
  RecordProperty("foreign_x_u1_worst_magnitude_error", std::to_string(worst_magnitude));
  RecordProperty("foreign_x_u1_worst_phase_error_deg", std::to_string(worst_phase));
  EXPECT_LT(worst_magnitude, 0.01);
  EXPECT_LT(worst_phase, 1.0);
  check_unstable_pole(json);
}

// A copy of the experiment with its sidecar edited.
fs::path edited_copy(const fs::path& dir, const std::string& stem, void (*edit)(nlohmann::json&)) {
  nlohmann::json sidecar = cli_test::read_json(dir / "ms.json");
  edit(sidecar);
  std::ofstream(dir / (stem + ".json")) << sidecar.dump();
  fs::copy_file(dir / "ms.csv", dir / (stem + ".csv"), fs::copy_options::overwrite_existing);
  return dir / (stem + ".json");
}

TEST(FrfCli, DataThatCannotSupportAnFrfIsRefused) {
  const fs::path dir = cli_test::fresh_dir("frf_cli_refused");
  const CommandResult ms = run_ambid("sim --excitation multisine --duration 0.3 --out " + (dir / "ms").string());
  ASSERT_EQ(ms.status, 0) << ms.output;
  const std::string out = " --out " + (dir / "bad").string();

  const fs::path no_controller = edited_copy(dir, "no_controller", [](nlohmann::json& j) { j.erase("controller"); });
  CommandResult r = run_ambid("frf " + no_controller.string() + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("no_controller.json: records no controller"));

  const fs::path no_r = edited_copy(dir, "no_r", [](nlohmann::json& j) { j["signals"].erase("r"); });
  r = run_ambid("frf " + no_r.string() + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("no_r.json: records no excitation"));

  // The sidecar promises 1 s periods; the record holds 0.3 s.
  const fs::path too_short =
      edited_copy(dir, "too_short", [](nlohmann::json& j) { j["excitation"]["period_samples"] = 10000; });
  r = run_ambid("frf " + too_short.string() + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("too_short.json: periodic FRF: 0 whole periods"));
  EXPECT_FALSE(fs::exists(dir / "bad" / "frf.json"));
}

// Issue 18 item 6: a run that fails while writing (here a directory where one of its plots
// goes) leaves the previous frf.json and plots as they were; it used to replace the plots
// written before the failure, so the folder held new plots beside the old frf.json.
TEST(FrfCli, AFailedRunLeavesThePreviousOutputs) {
  const fs::path dir = cli_test::fresh_dir("frf_cli_failed");
  const CommandResult sim = run_ambid("sim --excitation multisine --duration 3 --seed 3 --f-min 1 --f-max 1000 --out " +
                                      (dir / "ms").string());
  ASSERT_EQ(sim.status, 0) << sim.output;
  const std::string frf = "frf " + (dir / "ms.json").string() + " --out " + (dir / "frf").string();
  ASSERT_EQ(run_ambid(frf + " --no-fit").status, 0);
  const auto contents = [&] {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::directory_iterator(dir / "frf")) {
      if (!entry.is_regular_file() || entry.path().filename().string().front() == '.') continue;
      std::ifstream in(entry.path(), std::ios::binary);
      files[entry.path().filename().string()] = {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }
    return files;
  };
  std::map<std::string, std::string> before = contents();
  ASSERT_TRUE(before.count("frf.json") && before.count("bode_x_u1.svg") && before.count("sensitivity_sigma_max.svg"));
  fs::remove(dir / "frf" / "sensitivity_sigma_max.svg");
  fs::create_directories(dir / "frf" / "sensitivity_sigma_max.svg" / "blocker");
  before.erase("sensitivity_sigma_max.svg");
  const CommandResult failed = run_ambid(frf);  // with the rational fits: other plots, another frf.json
  EXPECT_EQ(failed.status, 1) << failed.output;
  EXPECT_THAT(failed.output, HasSubstr("sensitivity_sigma_max.svg"));
  const std::map<std::string, std::string> after = contents();
  std::set<std::string> names_before, names_after;  // nothing new, no temporary left
  for (const auto& [name, text] : before) names_before.insert(name);
  for (const auto& [name, text] : after) names_after.insert(name);
  EXPECT_EQ(names_after, names_before);
  for (const auto& [name, text] : before)
    EXPECT_TRUE(after.count(name) && after.at(name) == text) << name << " was replaced by the failed run";
}

}  // namespace frf_cli_test
}  // namespace ambid
