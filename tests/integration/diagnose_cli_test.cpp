// `ambid diagnose` as a user runs it: experiments made by `ambid sim` (three nominal, then a
// hot coil 1, R1 = 21 ohm = +20 %, all with sensor noise), model files, and bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "core/experiment_io.hpp"

namespace ambid {
namespace diagnose_cli_test {

using cli_test::fresh_dir;
using cli_test::read_json;
using cli_test::run_ambid;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

const std::string kNoise = " --duration 0.5 --amplitude 1 --position-noise 1e-9 --current-noise 1e-6";

void write_json(const fs::path& path, const nlohmann::json& j) { std::ofstream(path) << j.dump(2); }

// Three nominal experiments and three with `fault` (R1 = 21 ohm by default), 0.5 s each (two
// 0.25 s windows).
std::vector<std::string> make_experiments(const fs::path& dir, const std::string& fault = "R1=21") {
  std::vector<std::string> files;
  for (int i = 1; i <= 6; ++i) {
    const std::string stem = (dir / ((i <= 3 ? "nominal" : "hot") + std::to_string(i))).string();
    const auto r = run_ambid("sim" + kNoise + " --seed " + std::to_string(i) + (i > 3 ? " --set " + fault : "") +
                             " --out " + stem);
    EXPECT_EQ(r.status, 0) << r.output;
    files.push_back(stem + ".json");
  }
  return files;
}

std::string joined(const std::vector<std::string>& files) {
  std::string s;
  for (const std::string& f : files) s += " " + f;
  return s;
}

// Runs diagnose on make_experiments() in DIR/out and returns diagnosis.json.
nlohmann::json diagnose_hot_coil(const fs::path& dir, const std::string& fault = "R1=21") {
  const auto files = make_experiments(dir, fault);
  const auto r = run_ambid("diagnose" + joined(files) + " --out " + (dir / "out").string());
  EXPECT_EQ(r.status, 0) << r.output;
  return read_json(dir / "out" / "diagnosis.json");
}

// The first alert of R1 (the first alert of the run) names coil 1 resistance.
TEST(DiagnoseCli, HotCoilOneIsNamedCoilResistanceChannelOne) {
  const fs::path dir = fresh_dir("diagnose_hot_coil");
  const nlohmann::json d = diagnose_hot_coil(dir);
  EXPECT_EQ(d["baseline_windows"], 6);  // 3 experiments x two 0.25 s windows
  ASSERT_FALSE(d["alerts"].empty());
  for (const auto& a : d["alerts"])
    for (const char* key :
         {"time", "plant_id", "level", "fault", "channel", "parameter", "value", "baseline", "message"})
      EXPECT_TRUE(a.contains(key)) << key << " missing in " << a.dump();
  const auto& a = d["alerts"][0];
  EXPECT_EQ(a["parameter"], "R1") << d["alerts"].dump(2);
  EXPECT_EQ(a["fault"], "coil_resistance");
  EXPECT_EQ(a["channel"], 1);
  EXPECT_NE(a["level"], "OK");
  // Raised within the first two faulty experiments (1.5 s to 2.5 s). With closed-loop (no
  // sigmas, the baseline scatter of 0.25 s noisy windows is ~5 % of R1) the CUSUM needs
  // more than the first faulty experiment, whose first window also skips the settling.
  EXPECT_GT(a["time"].get<double>(), 1.5);
  EXPECT_LE(a["time"].get<double>(), 2.5);
  // 6 baseline windows scattering ~1 ohm (closed-loop, noisy 0.25 s): standard error ~0.4 ohm.
  EXPECT_NEAR(a["baseline"].get<double>(), 17.5, 1.0) << a.dump();
  // The closed-loop identification reads the +20 % of the truth (noisy 0.25 s windows).
  EXPECT_GT(a["value"].get<double>() / a["baseline"].get<double>(), 1.10) << a.dump();
  // The readable summary and a trend plot per parameter.
  EXPECT_TRUE(fs::exists(dir / "out" / "summary.txt"));
  for (const char* p : {"R1", "R2", "kw1", "kw2", "kr1", "kr2", "ks"}) {
    std::ifstream svg(dir / "out" / (std::string("trend_") + p + ".svg"));
    std::string text((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
    EXPECT_THAT(text, HasSubstr("<svg")) << p;
  }
}

// With the default closed-loop method (unbiased off nominal) R1 +20 % is an ERROR of coil 1
// and nothing else is named (deadbeat read it as +9.9 %, a WARN, and named coil 2 / air gap).
// An alert on ks or kr (the bias currents fall with the hot coil) names coil 1 as well.
TEST(DiagnoseCli, HotCoilOneIsAnErrorAndNothingElse) {
  const nlohmann::json d = diagnose_hot_coil(fresh_dir("diagnose_hot_coil_error"));
  ASSERT_FALSE(d["alerts"].empty());
  EXPECT_EQ(d["levels"]["R1"], "ERROR");
  for (const auto& a : d["alerts"]) {
    EXPECT_EQ(a["fault"], "coil_resistance") << a.dump();
    EXPECT_EQ(a["channel"], 1) << a.dump();
    if (a["level"] == "ERROR") {
      EXPECT_EQ(a["parameter"], "R1") << a.dump();
    }
  }
}

// kw2 +20 % (amplifier 2): an ERROR of amplifier 2 gain, and every alert names amplifier 2.
// The stronger amplifier moves the loop's bias currents, so ks (and kr1, kr2) truly move too;
// pem reads ks +14 % and kr +4 %, attributed to amplifier 2, never to a coil or the rotor.
TEST(DiagnoseCli, StrongAmplifierTwoIsAnErrorAndNothingElse) {
  const nlohmann::json d = diagnose_hot_coil(fresh_dir("diagnose_amplifier_two"), "kw2=1.2");
  ASSERT_FALSE(d["alerts"].empty());
  EXPECT_EQ(d["levels"]["kw2"], "ERROR");
  EXPECT_EQ(d["levels"]["R1"], "OK");
  EXPECT_EQ(d["levels"]["R2"], "OK");
  EXPECT_EQ(d["levels"]["kw1"], "OK");
  for (const auto& a : d["alerts"]) {
    EXPECT_EQ(a["fault"], "amplifier_gain") << a.dump();
    EXPECT_EQ(a["channel"], 2) << a.dump();
  }
}

// Model files (ambid-model/1): five nominal ones (0.3 % scatter) form the baseline; then R1
// +20 % is an ERROR of coil 1 resistance.
// Seven model files of a bearing whose R1 reads +20 % from the sixth on (5 baseline windows).
std::vector<std::string> write_model_files(const fs::path& dir) {
  const std::vector<double> wobble = {1.0, 1.003, 0.997, 1.002, 0.998, 1.001, 0.999};
  std::vector<std::string> files;
  for (std::size_t i = 0; i < wobble.size(); ++i) {
    const double f = wobble[i];
    nlohmann::json m;
    m["format"] = "ambid-model/1";
    m["plant_model"] = "amb1dof_voltage";
    m["method"] = "deadbeat";
    m["sample_time"] = 1e-4;
    m["discrete"] = {{"A", {{1.0}}}, {"B", {{0.0}}}, {"C", {{1.0}}}, {"D", {{0.0}}}};
    m["physical"] = {{"R1", 17.5 * f * (i >= 5 ? 1.2 : 1.0)},
                     {"R2", 17.5 / f},
                     {"kw1", f},
                     {"kw2", 1.0 / f},
                     {"kr1", 490.0 * f},
                     {"kr2", 490.0 / f},
                     {"ks", 1.4e6 * f}};
    m["uncertainty"] = {{"R1", 0.05}, {"R2", 0.05}, {"kw1", 0.003}, {"kw2", 0.003},
                        {"kr1", 1.5}, {"kr2", 1.5}, {"ks", 4000.0}};
    files.push_back((dir / ("model" + std::to_string(i) + ".json")).string());
    write_json(files.back(), m);
  }
  return files;
}

TEST(DiagnoseCli, AcceptsModelFiles) {
  const fs::path dir = fresh_dir("diagnose_models");
  std::vector<std::string> files = write_model_files(dir);
  // A discrete-only model (no continuous-time equivalent, `ambid identify` on such data) among
  // them: a window without physical parameters, skipped with its reason.
  nlohmann::json discrete_only = read_json(files[6]);
  for (const char* key : {"physical", "uncertainty"}) discrete_only.erase(key);
  discrete_only["no_continuous"] = "d2c: discrete eigenvalue -0.6 lies on the closed negative real axis";
  files.push_back((dir / "discrete_only.json").string());
  write_json(files.back(), discrete_only);
  const auto r = run_ambid("diagnose" + joined(files) + " --baseline 5 --out " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("discrete_only.json: window 1 of 1 (to t = 8 s) skipped, not identified "
                                  "(no_continuous_model): the model has no continuous part"));
  const nlohmann::json d = read_json(dir / "out" / "diagnosis.json");
  EXPECT_EQ(d["skipped_windows"]["reasons"]["no_continuous_model"], 1);
  EXPECT_EQ(d["inputs"][7]["skipped"][0]["reason"], "no_continuous_model");
  ASSERT_FALSE(d["alerts"].empty()) << r.output;
  const auto& a = d["alerts"][0];
  EXPECT_EQ(a["level"], "ERROR") << a.dump();
  EXPECT_EQ(a["fault"], "coil_resistance");
  EXPECT_EQ(a["channel"], 1);
  EXPECT_EQ(a["parameter"], "R1");
  EXPECT_DOUBLE_EQ(a["time"].get<double>(), 6.0);  // model files are 1 s apart
  for (const auto& other : d["alerts"]) EXPECT_EQ(other["parameter"], "R1") << other.dump();

  // A model without the uncertainty of a monitored parameter, or of another plant: refused.
  files.pop_back();
  nlohmann::json m = read_json(files[6]);
  m["uncertainty"].erase("kw2");
  write_json(files[6], m);
  auto bad = run_ambid("diagnose" + joined(files) + " --baseline 5 --out " + (dir / "out").string());
  EXPECT_NE(bad.status, 0);
  EXPECT_THAT(bad.output, HasSubstr("model6.json: estimate window: no uncertainty of kw2"));
  m["plant_model"] = "lamstf";
  write_json(files[6], m);
  bad = run_ambid("diagnose" + joined(files) + " --baseline 5 --out " + (dir / "out").string());
  EXPECT_NE(bad.status, 0);
  EXPECT_THAT(bad.output, HasSubstr("model6.json: plant model is 'lamstf'"));
}

std::string file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Issue 18: a run that fails leaves the previous outputs and trend store as they were (the
// store used to be deleted first), and a second run into a folder being written is refused.
TEST(DiagnoseCli, AFailedOrConcurrentRunLeavesThePreviousOutputs) {
  const fs::path dir = fresh_dir("diagnose_atomic");
  const std::string run = "diagnose" + joined(write_model_files(dir)) + " --baseline 5 --out " + (dir / "out").string();
  ASSERT_EQ(run_ambid(run).status, 0);
  const std::string store = file_text(dir / "out" / "trends.sqlite"), summary = file_text(dir / "out" / "summary.txt");
  ASSERT_GT(store.size(), 0u);

  // Another run holds the folder: refused, nothing touched.
  {
    const int fd = ::open((dir / "out" / ".ambid-lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
    const auto r = run_ambid(run);
    ::close(fd);
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_THAT(r.output, HasSubstr("out is being written by another ambid run"));
  }
  // The outputs cannot be replaced (diagnosis.json is a directory now): the run fails after
  // the diagnosis, the previous store and summary stay, no new store is left behind.
  fs::remove(dir / "out" / "diagnosis.json");
  fs::create_directories(dir / "out" / "diagnosis.json" / "blocker");
  const auto failed = run_ambid(run);
  EXPECT_EQ(failed.status, 1) << failed.output;
  EXPECT_EQ(file_text(dir / "out" / "trends.sqlite"), store);
  EXPECT_EQ(file_text(dir / "out" / "summary.txt"), summary);
  EXPECT_FALSE(fs::exists(dir / "out" / ".trends.sqlite.new"));
  fs::remove_all(dir / "out" / "diagnosis.json");
  EXPECT_EQ(run_ambid(run).status, 0);
  EXPECT_TRUE(fs::is_regular_file(dir / "out" / "diagnosis.json"));
}

// A record in the middle of the run whose recorded excitation is zero (switched off for 0.5 s):
// neither of its windows can be identified. The run completes, diagnosis.json counts both with
// their reason, stderr names them, and the other windows are diagnosed: R1 +20 % is still the
// ERROR of coil 1.
TEST(DiagnoseCli, WindowsThatCannotBeIdentifiedAreSkippedAndCounted) {
  const fs::path dir = fresh_dir("diagnose_skipped");
  std::vector<std::string> files = make_experiments(dir);
  const std::string quiet = (dir / "quiet").string();
  const auto q = run_ambid("sim" + kNoise + " --excitation none --seed 9 --set R1=21 --out " + quiet);
  ASSERT_EQ(q.status, 0) << q.output;
  Experiment e = read_experiment(quiet + ".json").experiment;  // without excitation: no r recorded
  e.r_names = {"r1", "r2"};
  e.r = Eigen::MatrixXd::Zero(e.samples(), 2);
  write_experiment(e, quiet);
  files.insert(files.begin() + 4, quiet + ".json");  // between the first and second hot record
  const auto r = run_ambid("diagnose" + joined(files) + " --out " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output,
              HasSubstr("quiet.json: window 1 of 2 (to t = 2.25 s) skipped, not identified (insufficient_data)"));
  EXPECT_THAT(r.output, HasSubstr("quiet.json: window 2 of 2 (to t = 2.5 s) skipped"));
  const nlohmann::json d = read_json(dir / "out" / "diagnosis.json");
  EXPECT_EQ(d["skipped_windows"]["count"], 2);
  EXPECT_EQ(d["skipped_windows"]["reasons"]["insufficient_data"], 2);
  EXPECT_EQ(d["skipped_windows"]["reasons"]["no_continuous_model"], 0);
  EXPECT_EQ(d["skipped_windows"]["reasons"]["error"], 0);
  const nlohmann::json& in = d["inputs"][4];
  EXPECT_EQ(in["file"], quiet + ".json");
  EXPECT_EQ(in["windows"], 0);
  ASSERT_EQ(in["skipped"].size(), 2u);
  EXPECT_EQ(in["skipped"][0]["window"], 1);
  EXPECT_DOUBLE_EQ(in["skipped"][1]["time"].get<double>(), 2.5);
  EXPECT_EQ(in["skipped"][1]["reason"], "insufficient_data");
  EXPECT_FALSE(in["skipped"][1]["message"].get<std::string>().empty());
  EXPECT_DOUBLE_EQ(in["time_to"].get<double>(), 2.5);
  // The records after it keep their place on the time axis and are diagnosed.
  EXPECT_EQ(d["inputs"][5]["windows"], 2);
  EXPECT_DOUBLE_EQ(d["inputs"][6]["time_to"].get<double>(), 3.5);
  EXPECT_EQ(d["levels"]["R1"], "ERROR");
  for (const auto& a : d["alerts"]) EXPECT_EQ(a["fault"], "coil_resistance") << a.dump();
  std::ifstream summary(dir / "out" / "summary.txt");
  const std::string text((std::istreambuf_iterator<char>(summary)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, HasSubstr("2 window(s) skipped, not identified: insufficient_data 2"));
}

TEST(DiagnoseCli, BadInputIsAClearErrorAndANonZeroExit) {
  const fs::path dir = fresh_dir("diagnose_bad");
  const auto files = make_experiments(dir);
  const std::string out = " --out " + (dir / "out").string();
  {
    const auto r = run_ambid("diagnose" + joined(files) + " " + (dir / "missing.json").string() + out);
    EXPECT_NE(r.status, 0);
    EXPECT_THAT(r.output, HasSubstr("missing.json: no such file"));
  }
  {
    // A directory named like an experiment (issue 18: it was an internal error, exit 2); a
    // directory stands for the experiments in it, and this one has none.
    fs::create_directories(dir / "folder.json");
    const auto r = run_ambid("diagnose" + joined(files) + " " + (dir / "folder.json").string() + out);
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_THAT(r.output, HasSubstr("folder.json: a directory without experiments or model files (*.json)"));
  }
  {
    const auto r = run_ambid("diagnose" + joined(files) + " --baseline 6" + out);
    EXPECT_NE(r.status, 0);
    EXPECT_THAT(r.output, HasSubstr("--baseline 6 leaves nothing to diagnose"));
  }
  {
    // 0.5 s experiments as one window each: 3 baseline windows are too few to learn from.
    const auto r = run_ambid("diagnose" + joined(files) + " --window 0" + out);
    EXPECT_NE(r.status, 0);
    EXPECT_THAT(r.output, HasSubstr("the baseline needs at least 5"));
  }
  {
    const auto r = run_ambid("diagnose" + joined(files) + " --method bogus" + out);
    EXPECT_NE(r.status, 0);
    EXPECT_THAT(r.output, HasSubstr("unknown method 'bogus'"));
  }
  {
    nlohmann::json sidecar = read_json(files[4]);
    sidecar["plant"]["model"] = "lamstf";
    write_json(files[4], sidecar);
    const auto r = run_ambid("diagnose" + joined(files) + out);
    EXPECT_NE(r.status, 0);
    EXPECT_THAT(r.output, HasSubstr("hot5.json"));
    // Refused before any window is identified: diagnostics knows no fault signatures of it.
    EXPECT_THAT(r.output,
                HasSubstr("diagnose: plant model 'lamstf' has no fault signatures (nor monitored parameters) yet"));
  }
  {
    nlohmann::json sidecar = read_json(files[3]);
    sidecar.erase("controller");
    write_json(files[3], sidecar);
    const auto r = run_ambid("diagnose" + joined(files) + out);
    EXPECT_NE(r.status, 0);
    EXPECT_THAT(r.output, HasSubstr("hot4.json"));
    EXPECT_THAT(r.output, HasSubstr("no controller"));
  }
}

}  // namespace diagnose_cli_test
}  // namespace ambid
