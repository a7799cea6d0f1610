// `ambid import` as a user runs it: a logger's CSV in mm/mA/ms with its own column names
// identifies like the simulated original; the vendored MagLev MAT record with a mapping file
// and --resample; refusals with the file and the problem and exit code 1; clamp counts.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <charconv>
#include <filesystem>
#include <fstream>

#include "cli_run.hpp"
#include "core/experiment_io.hpp"

namespace ambid {
namespace import_cli_test {

using cli_test::CommandResult;
using cli_test::fresh_dir;
using cli_test::read_json;
using cli_test::run_ambid;
using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

std::string shortest(double v) {
  char buffer[32];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, v).ptr);
}

TEST(ImportCli, LoggerCsvInMillimetresIdentifiesLikeTheOriginal) {
  const fs::path dir = fresh_dir("import_csv");
  CommandResult r = run_ambid("sim --duration 0.4 --seed 3 --out " + (dir / "run").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const Experiment e = read_experiment(dir / "run").experiment;
  std::ofstream csv(dir / "logger.csv");
  csv << "time_ms,coil2_mA,gap_mm,cmd2,cmd1,coil1_mA,exc1,exc2\n";
  for (Eigen::Index k = 0; k < e.samples(); ++k)
    csv << shortest(e.t(k) * 1e3) << ',' << shortest(e.y(k, 2) * 1e3) << ',' << shortest(e.y(k, 0) * 1e3) << ','
        << shortest(e.u(k, 1)) << ',' << shortest(e.u(k, 0)) << ',' << shortest(e.y(k, 1) * 1e3) << ','
        << shortest(e.r(k, 0)) << ',' << shortest(e.r(k, 1)) << '\n';
  csv.close();
  r = run_ambid("import " + (dir / "logger.csv").string() + " --template " + (dir / "run.json").string() +
                " --t time_ms:ms --y x=gap_mm:mm --y i1=coil1_mA:mA --y i2=coil2_mA:mA --u u1=cmd1 --u u2=cmd2"
                " --r r1=exc1 --r r2=exc2 --out " +
                (dir / "imported").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("(CSV, 4000 rows)"));
  EXPECT_THAT(r.output, HasSubstr("x <- column 'gap_mm' in mm (x0.001)"));
  EXPECT_THAT(r.output, HasSubstr("sample time 1e-4 s (from the template)"));
  EXPECT_THAT(r.output, HasSubstr("4000 samples"));

  for (const std::string stem : {"run", "imported"}) {
    r = run_ambid("identify " + (dir / stem).string() + " --method deadbeat --out " +
                  (dir / (stem + "-model.json")).string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_THAT(r.output, HasSubstr("clamped samples (a controller clamp acted, not exogenous): 0 of 4000"));
  }
  const auto original = read_json(dir / "run-model.json")["parameters"];
  const auto imported = read_json(dir / "imported-model.json")["parameters"];
  ASSERT_EQ(original.size(), imported.size());
  for (const auto& [name, value] : original.items())
    EXPECT_NEAR(imported[name].get<double>(), value.get<double>(), 1e-9 * std::abs(value.get<double>())) << name;
}

TEST(ImportCli, VendoredMaglevRecordWithAMappingFileIsResampledQuietlyInAPipe) {
  const fs::path dir = fresh_dir("import_maglev");
  std::ofstream(dir / "mapping.json") << R"json({"t": "Aclas(:,1)", "y": ["x=Aclas(:,2)"], "u": ["u=Aclas(:,3)"]})json";
  const std::string record = std::string(AMBID_SOURCE_DIR) + "/tests/data/labcontrol-maglev/Classic_PID.mat";
  const std::string args = "import " + record + " --plant maglev1coil_voltage --mapping " +
                           (dir / "mapping.json").string() + " --out " + (dir / "classic").string();
  CommandResult r = run_ambid(args);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("ambid: error: " + record + ": sampling is not uniform"));
  r = run_ambid(args + " --resample");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("(MAT v5, 4847 rows)"));
  EXPECT_THAT(r.output, HasSubstr("sample time 0.02 s (the median step of t)"));
  EXPECT_THAT(r.output, HasSubstr("resampled 4847 rows onto 5000 samples every 0.02 s by linear interpolation"));
  EXPECT_THAT(r.output, Not(HasSubstr("\r")));  // no progress line: stderr is a pipe
  EXPECT_EQ(read_experiment(dir / "classic").experiment.samples(), 5000);
}

TEST(ImportCli, BadRecordsAndMappingsAreRefusedWithTheFileAndExitCode1) {
  const fs::path dir = fresh_dir("import_bad");
  std::ofstream(dir / "log.csv") << "time,pos\n0,1\n0.001,oops\n";
  const std::string base = "import " + (dir / "log.csv").string() + " --plant maglev1coil_voltage --out " +
                           (dir / "out").string() + " --t time --u u=pos";
  CommandResult r = run_ambid(base + " --y x=pos");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr((dir / "log.csv").string() + ": line 3, column 'pos': expected a finite number, "
                                                               "got 'oops'"));
  r = run_ambid(base + " --y x=gap");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("no column 'gap' (the header has 'time', 'pos')"));
  r = run_ambid(base + " --y x=pos:inch");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("unknown unit 'inch'"));
  EXPECT_FALSE(fs::exists(dir / "out.json"));
}

TEST(ImportCli, IdentifyAndDiagnoseCountTheClampedSamples) {
  const fs::path dir = fresh_dir("import_clamped");
  const CommandResult sim =
      run_ambid("sim --duration 0.4 --seed 3 --amplitude 0.5 --input-limit 9.4 --out " + (dir / "run").string());
  ASSERT_EQ(sim.status, 0) << sim.output;
  const ReadResult read = read_experiment(dir / "run");
  ASSERT_GT(read.clamped_samples, 0);
  const CommandResult r =
      run_ambid("identify " + (dir / "run").string() + " --method deadbeat --out " + (dir / "model.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("not exogenous): " + std::to_string(read.clamped_samples) + " of 4000"));
}

}  // namespace import_cli_test
}  // namespace ambid
