// `ambid diagnose` on records of the single-coil maglev from the command line: a directory of
// rig-like records (`ambid sim --plant maglev1coil_voltage` with the rig's sensor noise),
// cut into the family's 3 s windows and identified by its grey-box fit; the coil resistance
// +20 % is an ERROR about R named coil_resistance in the first window of the faulty record,
// nothing else is raised; inputs of two families, and a method the family lacks, are refused
// naming them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "cli_run.hpp"

namespace ambid {
namespace maglev_diagnose_cli_test {

using cli_test::fresh_dir;
using cli_test::read_json;
using cli_test::run_ambid;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

// 12 s at 3.25 ms (four 3 s windows), levels 13-15.5 mm held 1.5 s (with R +20 % the loop
// loses the body at 16 mm), 5 um / 10 uA of sensor noise.
const std::string kRecord =
    "sim --plant maglev1coil_voltage --duration 12 --step-period 1.5 --levels 14,13,15,14.5,15.5,13.5 "
    "--position-noise 5e-6 --current-noise 1e-5";

TEST(MaglevDiagnoseCli, ADirectoryOfRecordsNamesTheHotCoil) {
  const fs::path dir = fresh_dir("maglev_diagnose_cli");
  fs::create_directories(dir / "records");
  for (int seed = 1; seed <= 4; ++seed) {  // a_ ... sorts before b_: the nominal records first
    const auto r = run_ambid(kRecord + " --seed " + std::to_string(seed) + " --out " +
                             (dir / "records" / ("a_nominal" + std::to_string(seed))).string());
    ASSERT_EQ(r.status, 0) << r.output;
  }
  auto r = run_ambid(kRecord + " --seed 5 --set R=252 --out " + (dir / "records" / "b_hot").string());
  ASSERT_EQ(r.status, 0) << r.output;

  r = run_ambid("diagnose " + (dir / "records").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("(maglev1coil_voltage, windows of 3 s by greybox)"));
  const nlohmann::json d = read_json(dir / "out" / "diagnosis.json");
  EXPECT_EQ(d["plant_model"], "maglev1coil_voltage");
  EXPECT_EQ(d["baseline_windows"], 12);  // 3 records x four 3 s windows
  EXPECT_EQ(d["skipped_windows"]["count"], 0);
  ASSERT_EQ(d["alerts"].size(), 1u) << d["alerts"].dump(2);
  const nlohmann::json& a = d["alerts"][0];
  EXPECT_EQ(a["level"], "ERROR");
  EXPECT_EQ(a["fault"], "coil_resistance");
  EXPECT_EQ(a["parameter"], "R");
  // The end of the hot record's first window: 4 nominal records of four 923-sample windows, then one.
  EXPECT_NEAR(a["time"].get<double>(), 17 * 923 * 3.25e-3, 1e-6);
  EXPECT_NEAR(a["value"].get<double>() / a["baseline"].get<double>(), 1.2, 0.005);
  EXPECT_NEAR(a["baseline"].get<double>(), 210.0, 0.5);
  for (const char* p : {"R", "L", "Km", "n_i", "n_x"}) EXPECT_TRUE(d["levels"].contains(p)) << p;

  // One diagnosis watches one family; greybox is the maglev's window method, pem the bearing's.
  r = run_ambid("sim --duration 0.5 --out " + (dir / "bearing").string());
  ASSERT_EQ(r.status, 0) << r.output;
  r = run_ambid("diagnose " + (dir / "records").string() + " " + (dir / "bearing.json").string() + " --out " +
                (dir / "mixed").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_THAT(r.output,
              HasSubstr("bearing.json: plant model is 'amb1dof_voltage', the first input's is 'maglev1coil_voltage'"));
  r = run_ambid("diagnose " + (dir / "records").string() + " --method pem --out " + (dir / "pem").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("method 'pem' is defined for plant model 'amb1dof_voltage' only"));
}

}  // namespace maglev_diagnose_cli_test
}  // namespace ambid
