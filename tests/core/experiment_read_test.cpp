// read_experiment against hand-written files: one test per rule of experiment-format.md, each
// checking that the message names the file, the line or key, and what was expected.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <random>

#include "core/error.hpp"
#include "core/experiment_io.hpp"
#include "core/json_text.hpp"

namespace ambid {
namespace experiment_read_test {

using nlohmann::json;
using ::testing::AllOf;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

json good_sidecar() {
  return json::parse(R"({
    "format": "ambid-experiment/1",
    "name": "hand written",
    "sample_time": 1e-3,
    "plant": { "model": "amb1dof_voltage", "parameters": { "m": 1.8, "R1": 17.5 } },
    "signals": { "y": ["x", "i1", "i2"], "u": ["u1", "u2"], "r": ["r1", "r2"] },
    "operating_point": { "x": 0.0, "i1": 0.5, "i2": 0.5, "u1": 8.75, "u2": 8.75 },
    "controller": {
      "kind": "state_space", "sample_time": 1e-3,
      "inputs": ["x", "i1"], "outputs": ["u1", "u2"],
      "A": [[0.5]], "B": [[1, 0]], "C": [[1], [2]], "D": [[-700, 0], [700, 0]]
    }
  })");
}

// Line 1 is the header; data row k (from 0) is on line k + 2.
std::string good_csv(int rows = 5) {
  std::string csv = "t,x,i1,i2,u1,u2,r1,r2\n";
  for (int k = 0; k < rows; ++k) {
    const std::string v = std::to_string(k);
    csv += std::to_string(k * 1e-3) + ",1e-6," + v + ",0.5,8.75,8.75,0.1,-0.1\n";
  }
  return csv;
}

// `csv` with the cell of `column` on `line` replaced by `cell`.
std::string with_cell(std::string csv, int line, int column, const std::string& cell) {
  std::size_t begin = 0;
  for (int l = 1; l < line; ++l) begin = csv.find('\n', begin) + 1;
  for (int c = 0; c < column; ++c) begin = csv.find(',', begin) + 1;
  const std::size_t end = csv.find_first_of(",\n", begin);
  return csv.replace(begin, end - begin, cell);
}

class ReadExperiment : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "-" + info->name();
    for (char& c : name)
      if (c == '/') c = '_';
    dir_ = fs::temp_directory_path() / ("ambid-read-test-" + name + "-" + std::to_string(std::random_device{}()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  void write(const std::string& file, const std::string& text) const { std::ofstream(dir_ / file) << text; }
  void write_pair(const json& sidecar, const std::string& csv) const {
    write("run.json", sidecar.dump(2));
    write("run.csv", csv);
  }
  ReadResult read(const ReadOptions& options = {}) const { return read_experiment(dir_ / "run", options); }
  // The message of the Error that reading throws.
  std::string refusal(const ReadOptions& options = {}) const {
    try {
      read(options);
    } catch (const Error& e) {
      return e.what();
    }
    ADD_FAILURE() << "the files were accepted";
    return {};
  }
  std::string csv_file() const { return (dir_ / "run.csv").string() + ": "; }
  std::string json_file() const { return (dir_ / "run.json").string() + ": "; }

  fs::path dir_;
};

// ---------------------------------------------------------------- accepted files

TEST_F(ReadExperiment, GoodFilesGiveAValidExperiment) {
  write_pair(good_sidecar(), good_csv());
  const ReadResult result = read();
  EXPECT_TRUE(result.warnings.empty());
  const Experiment& e = result.experiment;
  EXPECT_NO_THROW(e.validate());
  EXPECT_EQ(e.samples(), 5);
  EXPECT_EQ(e.y(3, 1), 3.0);
  EXPECT_EQ(e.u(0, 1), 8.75);
  EXPECT_EQ(e.r(4, 1), -0.1);
  EXPECT_EQ(e.plant.parameters.at("R1"), 17.5);
  ASSERT_TRUE(e.controller);
  EXPECT_EQ(e.controller->D(1, 0), 700.0);
  EXPECT_EQ(e.controller->initial_state.size(), 0);
}

TEST_F(ReadExperiment, AcceptsTheJsonTheCsvOrTheStem) {
  write_pair(good_sidecar(), good_csv());
  for (const char* path : {"run.json", "run.csv", "run"})
    EXPECT_EQ(read_experiment(dir_ / path).experiment.samples(), 5) << path;
}

TEST_F(ReadExperiment, OperatingValueOfAnExcitationDefaultsToZero) {
  write_pair(good_sidecar(), good_csv());
  const Experiment e = read().experiment;
  EXPECT_FALSE(e.operating_point.count("r1"));
  EXPECT_EQ(e.r_deviation()(0, 0), 0.1);
}

TEST_F(ReadExperiment, ExcitationAndControllerMayBeAbsent) {
  json sidecar = good_sidecar();
  sidecar["signals"].erase("r");
  sidecar.erase("controller");
  write_pair(sidecar, good_csv());
  const ReadResult result = read();
  EXPECT_FALSE(result.experiment.has_excitation());
  EXPECT_FALSE(result.experiment.controller);
  // r1 and r2 are now columns nobody named.
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_THAT(result.warnings[0], AllOf(HasSubstr(csv_file()), HasSubstr("columns 'r1', 'r2' are not named")));
}

TEST_F(ReadExperiment, ExtraColumnsAreIgnoredWithAWarningNamingThem) {
  std::string csv = good_csv();
  csv.replace(0, csv.find('\n'), "t,x,temp,i1,i2,u1,u2,r1,r2,status");
  std::string rows;
  for (int k = 0; k < 5; ++k)
    rows += std::to_string(k * 1e-3) + ",1e-6,21.5," + std::to_string(k) + ",0.5,8.75,8.75,0.1,-0.1,OK\n";
  write_pair(good_sidecar(), csv.substr(0, csv.find('\n') + 1) + rows);
  const ReadResult result = read();
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_THAT(result.warnings[0], AllOf(HasSubstr(csv_file()),
                                        HasSubstr("columns 'temp', 'status' are not named in the sidecar; ignored")));
  EXPECT_EQ(result.experiment.y(2, 1), 2.0);
}

TEST_F(ReadExperiment, ToleratesCrLfWhitespaceByteOrderMarkPlusSignAndFinalBlankLines) {
  std::string csv =
      "\xEF\xBB\xBF"
      "t, x ,i1,i2,u1,u2,r1,r2\r\n";
  for (int k = 0; k < 3; ++k) csv += std::to_string(k * 1e-3) + ", +1e-6 ,\t2,0.5,8.75,8.75,0.1,-0.1\r\n";
  write_pair(good_sidecar(), csv + "\r\n\n");
  const Experiment e = read().experiment;
  EXPECT_EQ(e.samples(), 3);
  EXPECT_EQ(e.y(2, 0), 1e-6);
}

TEST_F(ReadExperiment, SamplingWithinOnePercentIsAccepted) {
  write_pair(good_sidecar(), with_cell(good_csv(), 4, 0, "0.0020099"));  // steps 1.0099 and 0.9901 ms
  EXPECT_EQ(read().experiment.t(2), 0.0020099);
}

// ---------------------------------------------------------------- CSV rules

TEST_F(ReadExperiment, MissingCsvFileIsNamed) {
  write("run.json", good_sidecar().dump());
  EXPECT_THAT(refusal(), AllOf(HasSubstr("cannot open " + (dir_ / "run.csv").string()), HasSubstr("No such file")));
}

TEST_F(ReadExperiment, EmptyCsvIsRefused) {
  write_pair(good_sidecar(), "");
  EXPECT_THAT(refusal(), AllOf(HasSubstr(csv_file() + "line 1"), HasSubstr("expected a header line")));
}

TEST_F(ReadExperiment, FirstColumnMustBeT) {
  std::string csv = good_csv();
  csv.replace(0, 1, "time");
  write_pair(good_sidecar(), csv);
  EXPECT_THAT(refusal(), HasSubstr(csv_file() + "line 1: the first column must be 't' (time in seconds), got 'time'"));
}

TEST_F(ReadExperiment, EverySidecarSignalMustBeAColumn) {
  std::string csv = "t,x,i1,u1,u2,r1,r2\n0,0,0,0,0,0,0\n0.001,0,0,0,0,0,0\n";
  write_pair(good_sidecar(), csv);
  EXPECT_THAT(refusal(), HasSubstr(csv_file() + "line 1: column 'i2' named in signals.y is missing from the header"));
}

TEST_F(ReadExperiment, ColumnNamedTwiceIsRefused) {
  std::string csv = good_csv();
  csv.replace(0, csv.find('\n'), "t,x,i1,i2,u1,u2,r1,x");
  write_pair(good_sidecar(), csv);
  EXPECT_THAT(refusal(), HasSubstr(csv_file() + "line 1: column 'x' appears twice (columns 2 and 8)"));
}

TEST_F(ReadExperiment, EmptyCellIsRefusedWithLineAndColumn) {
  write_pair(good_sidecar(), with_cell(good_csv(), 3, 4, ""));
  EXPECT_THAT(refusal(), HasSubstr(csv_file() + "line 3, column 'u1': empty cell; expected a finite number"));
}

TEST_F(ReadExperiment, NanIsRefusedWithLineAndColumn) {
  for (const char* nan : {"nan", "NaN", "-nan"}) {
    write_pair(good_sidecar(), with_cell(good_csv(), 4, 2, nan));
    EXPECT_THAT(refusal(), HasSubstr(csv_file() + "line 4, column 'i1': expected a finite number, got '" + nan + "'"));
  }
}

TEST_F(ReadExperiment, InfinityIsRefusedInAnyCaseAndSign) {
  for (const char* inf : {"inf", "+inf", "-Inf", "INF", "infinity"}) {
    write_pair(good_sidecar(), with_cell(good_csv(), 2, 7, inf));
    EXPECT_THAT(refusal(), HasSubstr(csv_file() + "line 2, column 'r2': expected a finite number, got '" + inf + "'"));
  }
}

TEST_F(ReadExperiment, UnparsableTextIsRefusedWithLineAndColumn) {
  for (const char* text : {"abc", "1 000", "1.5V", "0x10", "1e400"}) {
    write_pair(good_sidecar(), with_cell(good_csv(), 5, 1, text));
    EXPECT_THAT(refusal(), HasSubstr(csv_file() +
                                     "line 5, column 'x': expected a finite number ('.' decimal point, "
                                     "no thousands separators), got '" +
                                     text + "'"));
  }
}

TEST_F(ReadExperiment, UnparsableTimeIsRefused) {
  write_pair(good_sidecar(), with_cell(good_csv(), 3, 0, "0:01"));
  EXPECT_THAT(refusal(), HasSubstr(csv_file() + "line 3, column 't': expected a finite number"));
}

TEST_F(ReadExperiment, DecimalCommaIsRefusedAsAWrongCellCount) {
  write_pair(good_sidecar(), with_cell(good_csv(), 3, 3, "0,5"));
  EXPECT_THAT(refusal(), HasSubstr(csv_file() + "line 3 has 9 cells, the header has 8 (a ',' decimal point"));
}

TEST_F(ReadExperiment, RowWithTooFewCellsIsRefused) {
  write_pair(good_sidecar(), good_csv() + "0.005,1,2\n");
  EXPECT_THAT(refusal(), HasSubstr(csv_file() + "line 7 has 3 cells, the header has 8"));
}

TEST_F(ReadExperiment, BlankLineInsideTheDataIsRefused) {
  std::string csv = good_csv();
  csv.insert(csv.find('\n', csv.find('\n') + 1) + 1, "\n");
  write_pair(good_sidecar(), csv);
  EXPECT_THAT(refusal(), HasSubstr(csv_file() + "line 3 is empty; expected 8 cells"));
}

TEST_F(ReadExperiment, TimeMustBeStrictlyIncreasing) {
  write_pair(good_sidecar(), with_cell(good_csv(), 4, 0, "0.001"));
  EXPECT_THAT(refusal(), HasSubstr(csv_file() + "line 4: t = '0.001' is not greater than t = 0.001 on line 3; "
                                                "t must be strictly increasing"));
}

TEST_F(ReadExperiment, NonUniformSamplingIsRefusedNamingTheGap) {
  std::string csv = good_csv();
  for (int line = 4; line <= 6; ++line) csv = with_cell(csv, line, 0, std::to_string((line - 1) * 1e-3));
  write_pair(good_sidecar(), csv);  // t = 0, 1, 3, 4, 5 ms: a 2 ms step into line 4
  EXPECT_THAT(refusal(), AllOf(HasSubstr(csv_file() + "line 4: sampling is not uniform: t jumps by 0.002 s from "
                                                      "0.001 (line 3) to 0.003 (line 4)"),
                               HasSubstr("every step must be sample_time 0.001 s within 1 %")));
}

TEST_F(ReadExperiment, FewerThanTwoRowsIsRefused) {
  write_pair(good_sidecar(), good_csv(1));
  EXPECT_THAT(refusal(), HasSubstr(csv_file() + "has 1 data rows; at least 2 are needed"));
}

// ---------------------------------------------------------------- resampling

TEST_F(ReadExperiment, ResampleInterpolatesLinearlyOntoTheUniformGrid) {
  // Irregular times; every signal is linear in t, so interpolation must reproduce it.
  const double times[] = {0.0, 0.0007, 0.0021, 0.0030, 0.00455, 0.0052};
  std::string csv = "t,x,i1,i2,u1,u2,r1,r2\n";
  for (double t : times) {
    const std::string line_value = std::to_string(2.0 + 1000.0 * t);
    csv += std::to_string(t) + "," + line_value + ",0.5,0.5,8.75,8.75," + line_value + ",0\n";
  }
  write_pair(good_sidecar(), csv);
  EXPECT_THAT(refusal(), HasSubstr("line 3: sampling is not uniform"));

  const ReadResult result = read({.resample = true});
  const Experiment& e = result.experiment;
  ASSERT_EQ(e.samples(), 6);  // 0 .. 5 ms; 5.2 ms is beyond the last whole step
  for (Eigen::Index k = 0; k < e.samples(); ++k) {
    EXPECT_DOUBLE_EQ(e.t(k), static_cast<double>(k) * 1e-3);
    EXPECT_NEAR(e.signal("x")(k), 2.0 + static_cast<double>(k), 1e-12);
    EXPECT_NEAR(e.signal("r1")(k), 2.0 + static_cast<double>(k), 1e-12);
  }
  EXPECT_NO_THROW(e.validate());
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_THAT(result.warnings[0], AllOf(HasSubstr(csv_file() + "sampling is not uniform (first at line 3"),
                                        HasSubstr("resampled 6 rows onto 6 samples every 0.001 s")));
}

TEST_F(ReadExperiment, ResampleLeavesUniformDataUntouched) {
  write_pair(good_sidecar(), with_cell(good_csv(), 4, 0, "0.0020099"));
  const ReadResult result = read({.resample = true});
  EXPECT_TRUE(result.warnings.empty());
  EXPECT_EQ(result.experiment.t(2), 0.0020099);
}

TEST_F(ReadExperiment, ResampleRefusesDataShorterThanOneStep) {
  write_pair(good_sidecar(), "t,x,i1,i2,u1,u2,r1,r2\n0,0,0,0,0,0,0,0\n0.0005,0,0,0,0,0,0,0\n");
  EXPECT_THAT(refusal({.resample = true}), HasSubstr(csv_file() + "spans 5e-4 s, less than one sample_time 0.001 s"));
}

TEST_F(ReadExperiment, ResampleRefusesToInventMostOfTheData) {
  write_pair(good_sidecar(), with_cell(good_csv(), 6, 0, "1e6"));  // a broken clock
  EXPECT_THAT(refusal({.resample = true}),
              AllOf(HasSubstr(csv_file() + "resampling 5 rows spanning t = 0 to 1e+6 (line 6)"),
                    HasSubstr("more than 10 samples per row")));
}

// ---------------------------------------------------------------- sidecar rules

TEST_F(ReadExperiment, MissingSidecarIsNamed) {
  write("run.csv", good_csv());
  EXPECT_THAT(refusal(), HasSubstr("cannot open " + (dir_ / "run.json").string()));
}

TEST_F(ReadExperiment, MalformedJsonNamesFileAndPosition) {
  write("run.json", "{\n  \"format\": \"ambid-experiment/1\",\n  'name': \"quoted wrongly\"\n}\n");
  write("run.csv", good_csv());
  EXPECT_THAT(refusal(),
              AllOf(HasSubstr(json_file() + "malformed JSON: "), HasSubstr("parse error at line 3, column")));
}

TEST_F(ReadExperiment, KeyRepeatedInAnObjectIsRefused) {
  std::string text = good_sidecar().dump();
  text.replace(text.find("\"m\":1.8"), 7, "\"m\":1.8,\"m\":2.0");
  write("run.json", text);
  write("run.csv", good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "key `plant.parameters.m` appears twice in one object"));
  write("run.json", R"({"rig": {"runs": [{"id": 1}, {"id": 2, "id": 3}]}})");
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "key `rig.runs[].id` appears twice in one object"));
}

TEST_F(ReadExperiment, RootMustBeAnObject) {
  write_pair(json::array({1, 2}), good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "key `(root)` must be an object, got array"));
}

TEST_F(ReadExperiment, FormatMustBeVersionOne) {
  json sidecar = good_sidecar();
  sidecar["format"] = "ambid-experiment/2";
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(),
              HasSubstr(json_file() + "key `format` must be \"ambid-experiment/1\", got 'ambid-experiment/2'"));
}

// A missing required key is an error naming its path.
class MissingKey : public ReadExperiment, public ::testing::WithParamInterface<const char*> {};

TEST_P(MissingKey, IsNamed) {
  const std::string path = GetParam();
  json sidecar = good_sidecar();
  const auto dot = path.rfind('.');
  json& parent = dot == std::string::npos ? sidecar : sidecar[json::json_pointer("/" + path.substr(0, dot))];
  parent.erase(path.substr(dot == std::string::npos ? 0 : dot + 1));
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "missing required key `" + path + "` (expected "));
}

INSTANTIATE_TEST_SUITE_P(Sidecar, MissingKey,
                         ::testing::Values("format", "name", "sample_time", "plant", "plant.model", "plant.parameters",
                                           "signals", "signals.y", "signals.u", "operating_point", "controller.kind",
                                           "controller.sample_time", "controller.inputs", "controller.outputs",
                                           "controller.A", "controller.B", "controller.C", "controller.D"));

// A value of the wrong JSON type is an error naming the key and the expected type.
struct WrongType {
  const char* pointer;  // JSON pointer of the value to replace
  const char* value;    // JSON text put there
  const char* message;
};

class WrongTypeOf : public ReadExperiment, public ::testing::WithParamInterface<WrongType> {};

TEST_P(WrongTypeOf, IsNamedWithTheExpectedType) {
  json sidecar = good_sidecar();
  sidecar[json::json_pointer(GetParam().pointer)] = json::parse(GetParam().value);
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + GetParam().message));
}

INSTANTIATE_TEST_SUITE_P(
    Sidecar, WrongTypeOf,
    ::testing::Values(
        WrongType{"/name", "7", "key `name` must be a string, got number '7'"},
        WrongType{"/sample_time", "\"1e-3\"", "key `sample_time` must be a number, got string '\"1e-3\"'"},
        WrongType{"/plant", "[]", "key `plant` must be an object, got array"},
        WrongType{"/plant/parameters/m", "\"heavy\"", "key `plant.parameters.m` must be a number, got string"},
        WrongType{"/signals/y", "\"x\"", "key `signals.y` must be an array of signal names, got string"},
        WrongType{"/signals/u/1", "2", "key `signals.u[1]` must be a string, got number '2'"},
        WrongType{"/signals/r", "null", "key `signals.r` must be an array of signal names, got null"},
        WrongType{"/operating_point/x", "true", "key `operating_point.x` must be a number, got boolean 'true'"},
        WrongType{"/controller", "\"pid\"", "key `controller` must be an object, got string"},
        WrongType{"/controller/A", "0.5",
                  "key `controller.A` must be an array of rows (arrays of numbers), got number"},
        WrongType{"/controller/C/1", "2", "key `controller.C[1]` must be an array of numbers, got number"},
        WrongType{"/controller/D/0/1", "\"0\"", "key `controller.D[0][1]` must be a number, got string"},
        WrongType{"/controller/initial_state", "{}", "key `controller.initial_state` must be an array of numbers"}));

TEST_F(ReadExperiment, SampleTimeMustBePositive) {
  for (double value : {0.0, -1e-3}) {
    json sidecar = good_sidecar();
    sidecar["sample_time"] = value;
    write_pair(sidecar, good_csv());
    EXPECT_THAT(refusal(), HasSubstr(json_file() + "sample_time must be a positive finite number of seconds, got " +
                                     (value == 0.0 ? "0" : "-0.001")));
  }
}

// JSON has no infinity; a number beyond the range of double is where one would slip in.
TEST_F(ReadExperiment, NumberBeyondDoubleRangeIsRefused) {
  std::string text = good_sidecar().dump();
  text.replace(text.find("\"m\":1.8"), 7, "\"m\":-1e999");
  write("run.json", text);
  write("run.csv", good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "malformed JSON: [json.exception.out_of_range.406] number overflow "
                                                 "parsing '-1e999'"));
}

TEST_F(ReadExperiment, PlantModelMustNotBeEmpty) {
  json sidecar = good_sidecar();
  sidecar["plant"]["model"] = "";
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "plant.model must name a plant model"));
}

TEST_F(ReadExperiment, OutputsAndInputsMustNotBeEmpty) {
  json sidecar = good_sidecar();
  sidecar["signals"]["u"] = json::array();
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "signals.u must name at least one plant input signal"));
}

TEST_F(ReadExperiment, DuplicateSignalNamesAreRefused) {
  json sidecar = good_sidecar();
  sidecar["signals"]["r"] = {"r1", "u2"};
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "signals.r names 'u2', already named in signals.u"));
  sidecar = good_sidecar();
  sidecar["signals"]["y"] = {"x", "i1", "x"};
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "signals.y names 'x', already named in signals.y"));
}

TEST_F(ReadExperiment, SignalNamesMustFitAnUnquotedCsvHeader) {
  json sidecar = good_sidecar();
  sidecar["signals"]["y"] = {"x", "i1", "t"};
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "signals.y may not name a signal 't'"));
  sidecar["signals"]["y"] = {"x", "i1", "i,2"};
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "signals.y signal name 'i,2' contains a comma"));
}

TEST_F(ReadExperiment, ExcitationNeedsOneSignalPerPlantInput) {
  json sidecar = good_sidecar();
  sidecar["signals"]["r"] = {"r1"};
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "signals.r must name one excitation per u signal (2), got 1"));
}

TEST_F(ReadExperiment, OperatingValueOfEveryOutputAndInputIsRequired) {
  json sidecar = good_sidecar();
  sidecar["operating_point"].erase("u2");
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "operating_point.u2 is missing: every y and u signal needs"));
}

TEST_F(ReadExperiment, OperatingValueOfNoSignalIsKeptWithAWarning) {
  json sidecar = good_sidecar();
  sidecar["operating_point"]["temp"] = 21.5;
  write_pair(sidecar, good_csv());
  const ReadResult result = read();
  EXPECT_EQ(result.experiment.operating_value("temp"), 21.5);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_THAT(result.warnings[0], HasSubstr(json_file() + "operating_point.temp names no signal"));
}

TEST_F(ReadExperiment, ControllerKindMustBeStateSpace) {
  json sidecar = good_sidecar();
  sidecar["controller"]["kind"] = "pid";
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "controller.kind must be 'state_space', got 'pid'"));
}

TEST_F(ReadExperiment, ControllerMatrixOfWrongShapeIsNamed) {
  json sidecar = good_sidecar();
  sidecar["controller"]["B"] = {{1, 0, 0}};
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "controller.B must be 1x2 (states x inputs), got 1x3"));
  sidecar = good_sidecar();
  sidecar["controller"]["A"] = {{0.5, 0}};
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "controller.A must be 1x1 (states x states), got 1x2"));
}

TEST_F(ReadExperiment, ControllerMatrixRowsMustHaveOneLength) {
  json sidecar = good_sidecar();
  sidecar["controller"]["D"] = {{-700, 0}, {700}};
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "key `controller.D[1]` has 1 entries, but row 0 of "
                                                 "`controller.D` has 2; every row must have the same length"));
}

TEST_F(ReadExperiment, ControllerInputsMustBeSignals) {
  json sidecar = good_sidecar();
  sidecar["controller"]["inputs"] = {"x", "z"};
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "controller.inputs names 'z', which is no y, u or r signal"));
}

TEST_F(ReadExperiment, ControllerOutputsMustBePlantInputs) {
  json sidecar = good_sidecar();
  sidecar["controller"]["outputs"] = {"u1", "r2"};
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "controller.outputs names 'r2', which is not a u signal"));
}

TEST_F(ReadExperiment, ControllerFeedingAPlantInputThroughDIsAnAlgebraicLoop) {
  json sidecar = good_sidecar();
  sidecar["controller"]["inputs"] = {"x", "u2"};
  sidecar["controller"]["D"] = {{-700, 0}, {700, 0.5}};
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), AllOf(HasSubstr(json_file() + "controller.D column 1 (input 'u2') must be zero"),
                               HasSubstr("algebraic loop; got D[1][1] = 0.5")));
  // A zero D column for a u input is fine.
  sidecar["controller"]["D"] = {{-700, 0}, {700, 0}};
  write_pair(sidecar, good_csv());
  EXPECT_NO_THROW(read());
}

TEST_F(ReadExperiment, ControllerSampleTimeMustEqualTheExperiments) {
  json sidecar = good_sidecar();
  sidecar["controller"]["sample_time"] = 1.001e-3;
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "controller.sample_time 0.001001 must equal sample_time 0.001"));
  sidecar["controller"]["sample_time"] = 1e-3 * (1 + 1e-12);  // rounding noise is fine
  write_pair(sidecar, good_csv());
  EXPECT_NO_THROW(read());
}

TEST_F(ReadExperiment, ControllerInitialStateNeedsOneEntryPerState) {
  json sidecar = good_sidecar();
  sidecar["controller"]["initial_state"] = {1, 2};
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "key `controller.initial_state` must have 1 entries (states), got 2"));
}

TEST_F(ReadExperiment, UnknownKeysAreKeptAndWrittenBack) {
  json sidecar = good_sidecar();
  sidecar["rig"] = {{"id", "bench-3"}};
  sidecar["plant"]["serial"] = "SN-42";
  sidecar["signals"]["units"] = {{"x", "m"}};
  sidecar["controller"]["design"] = "lqr";
  write_pair(sidecar, good_csv());
  const ReadResult first = read();
  EXPECT_TRUE(first.warnings.empty());
  const json expected = {{"rig", {{"id", "bench-3"}}},
                         {"plant", {{"serial", "SN-42"}}},
                         {"signals", {{"units", {{"x", "m"}}}}},
                         {"controller", {{"design", "lqr"}}}};
  EXPECT_EQ(first.experiment.extra.json(), expected);
  write_experiment(first.experiment, dir_ / "copy");
  EXPECT_EQ(read_experiment(dir_ / "copy").experiment.extra.json(), expected);
  std::ifstream copy(dir_ / "copy.json");
  EXPECT_EQ(json::parse(copy), sidecar);
}

// ---------------------------------------------------------------- bounded JSON (issue 18)

TEST_F(ReadExperiment, RefusesDeepNestingBeforeTheParserSeesIt) {
  std::string sidecar = good_sidecar().dump();
  sidecar.pop_back();  // the closing brace
  sidecar += ", \"deep\": " + std::string(30000, '[') + std::string(30000, ']') + "}";
  write("run.json", sidecar);
  write("run.csv", good_csv());
  EXPECT_THAT(refusal(), HasSubstr(json_file() + "JSON nested deeper than 64 levels (at byte"));
}

TEST_F(ReadExperiment, AcceptsNestingToTheLimitAndBracketsInsideStrings) {
  json sidecar = good_sidecar();
  sidecar["name"] = std::string(300, '[') + "\\\"{";
  json deep = 1.0;
  for (int level = 0; level < 63; ++level) deep = json::array({deep});  // the root object is level 1
  sidecar["deep"] = deep;
  write_pair(sidecar, good_csv());
  EXPECT_EQ(read().experiment.name, std::string(300, '[') + "\\\"{");
  sidecar["deep"] = json::array({deep});
  write_pair(sidecar, good_csv());
  EXPECT_THAT(refusal(), HasSubstr("JSON nested deeper than 64 levels"));
}

TEST_F(ReadExperiment, RefusesAnOversizeSidecarWithoutReadingIt) {
  std::string sidecar = good_sidecar().dump();
  sidecar += std::string(kMaxJsonBytes, ' ');
  write("run.json", sidecar);
  write("run.csv", good_csv());
  EXPECT_THAT(refusal(), HasSubstr((dir_ / "run.json").string() + ": " + std::to_string(sidecar.size()) +
                                   " bytes, more than the 16777216 bytes a JSON file may have"));
}

TEST_F(ReadExperiment, RefusesADirectoryNamingIt) {
  fs::create_directories(dir_ / "run.json");
  write("run.csv", good_csv());
  EXPECT_THAT(refusal(), HasSubstr("cannot read " + (dir_ / "run.json").string() + ": Is a directory"));
}

}  // namespace experiment_read_test
}  // namespace ambid
