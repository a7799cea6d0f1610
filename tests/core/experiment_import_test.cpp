// import_experiment: foreign MAT v5 and CSV records (written here, independently of the
// reader) against the SI experiment they came from; malformed records refused with the file
// and the problem; resampling against analytic values; the vendored labcontrol MagLev records.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "core/error.hpp"
#include "core/experiment_import.hpp"
#include "core/experiment_io.hpp"
#include "mat_writer.hpp"

namespace ambid {
namespace experiment_import_test {

using ::testing::AllOf;
using ::testing::HasSubstr;
namespace fs = std::filesystem;
using test::write_mat;

constexpr double kT = 1e-4;
constexpr Eigen::Index kN = 400;

// An SI experiment with smooth, distinct signals (values that are not round in mm or mA).
Experiment si_experiment() {
  Experiment e;
  e.name = "si original";
  e.sample_time = kT;
  e.plant.model = "amb1dof_voltage";
  e.plant.parameters = {{"m", 1.8}, {"R1", 17.5}};
  e.y_names = {"x", "i1", "i2"};
  e.u_names = {"u1", "u2"};
  e.r_names = {"r1", "r2"};
  e.operating_point = {{"x", 0.0}, {"i1", 0.5}, {"i2", 0.5}, {"u1", 8.75}, {"u2", 8.75}};
  e.t.resize(kN);
  e.y.resize(kN, 3);
  e.u.resize(kN, 2);
  e.r.resize(kN, 2);
  for (Eigen::Index k = 0; k < kN; ++k) {
    const double t = double(k) * kT;
    e.t(k) = t;
    e.y.row(k) << 1.234567e-5 * std::sin(2 * M_PI * 37 * t), 0.5 + 0.0123 * std::cos(2 * M_PI * 53 * t),
        0.5 - 0.0117 * std::sin(2 * M_PI * 71 * t);
    e.u.row(k) << 8.75 + 0.31 * std::sin(2 * M_PI * 29 * t + 0.3), 8.75 - 0.29 * std::cos(2 * M_PI * 43 * t);
    e.r.row(k) << 0.05 * std::sin(2 * M_PI * 101 * t), -0.05 * std::cos(2 * M_PI * 131 * t);
  }
  return e;
}

std::string shortest(double v) {
  char buffer[32];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, v).ptr);
}

class ImportExperiment : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("ambid-import-test-" + std::string(info->name()) + "-" + std::to_string(std::random_device{}()));
    fs::create_directories(dir_);
    write_experiment(original_, dir_ / "original");
    options_.template_sidecar = read_sidecar(dir_ / "original.json");
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path file(const std::string& name) const { return dir_ / name; }
  void write_text(const std::string& name, const std::string& text) const { std::ofstream(file(name)) << text; }

  static ImportMapping mapping(std::optional<std::string> t, const std::vector<std::string>& y,
                               const std::vector<std::string>& u, const std::vector<std::string>& r) {
    ImportMapping m;
    if (t) m.t = parse_signal_source("t", *t);
    for (const auto& s : y) m.y.push_back(parse_signal_mapping(s));
    for (const auto& s : u) m.u.push_back(parse_signal_mapping(s));
    for (const auto& s : r) m.r.push_back(parse_signal_mapping(s));
    return m;
  }

  static std::string refusal_of(const fs::path& path, const ImportMapping& m, const ImportOptions& o) {
    try {
      import_experiment(path, m, o);
    } catch (const Error& e) {
      return e.what();
    }
    return "(accepted)";
  }
  std::string refusal(const std::string& name, const ImportMapping& m, const ImportOptions& o) const {
    return refusal_of(file(name), m, o);
  }

  // Signals of `imported` equal the original's to a relative `tolerance` of each signal's scale.
  void expect_equal_to_original(const Experiment& imported, double tolerance) const {
    ASSERT_EQ(imported.samples(), original_.samples());
    EXPECT_EQ(imported.y_names, original_.y_names);
    EXPECT_EQ(imported.u_names, original_.u_names);
    EXPECT_EQ(imported.r_names, original_.r_names);
    EXPECT_EQ(imported.sample_time, original_.sample_time);
    EXPECT_LE((imported.t - original_.t).cwiseAbs().maxCoeff(), tolerance * kT * double(kN));
    for (const auto& name : original_.signal_names()) {
      const Eigen::VectorXd a = imported.signal(name), b = original_.signal(name);
      EXPECT_LE((a - b).cwiseAbs().maxCoeff(), tolerance * b.cwiseAbs().maxCoeff()) << name;
    }
  }

  Experiment original_ = si_experiment();
  ImportOptions options_;
  fs::path dir_;
};

TEST_F(ImportExperiment, MatMatrixLayoutWithShuffledColumnsEqualsTheOriginal) {
  // One 2-D variable, columns [u2, t, r1, x, i2, r2, u1, i1].
  const Experiment& e = original_;
  Eigen::MatrixXd data(kN, 8);
  data << e.u.col(1), e.t, e.r.col(0), e.y.col(0), e.y.col(2), e.r.col(1), e.u.col(0), e.y.col(1);
  write_mat(file("rig.mat"), {{"data", data}});
  const ImportResult result =
      import_experiment(file("rig.mat"),
                        mapping("data(:,2)", {"i1=data(:,8)", "x=data(:,4)", "i2=data(:,5)"},
                                {"u1=data(:,7)", "u2=data(:,1)"}, {"r1=data(:,3)", "r2=data(:,6)"}),
                        options_);
  EXPECT_EQ(result.file_kind, "MAT v5");
  EXPECT_EQ(result.rows, kN);
  expect_equal_to_original(result.experiment, 0.0);  // doubles travel unchanged
}

TEST_F(ImportExperiment, MatNamedVectorsInMicrometresAndMilliampsWithoutTimeEqualTheOriginal) {
  const Experiment& e = original_;
  write_mat(file("vectors.mat"), {{"pos_um", e.y.col(0) * 1e6},
                                  {"I1_mA", e.y.col(1).transpose() * 1e3},  // a row vector
                                  {"I2_mA", e.y.col(2) * 1e3},
                                  {"U1", e.u.col(0)},
                                  {"U2", e.u.col(1)},
                                  {"w1", e.r.col(0) * 4.0},  // a generator's own scale
                                  {"w2", e.r.col(1) * 4.0}});
  ImportOptions o = options_;
  o.sample_time = kT;
  const ImportResult result = import_experiment(file("vectors.mat"),
                                                mapping(std::nullopt, {"x=pos_um:um", "i1=I1_mA:mA", "i2=I2_mA:mA"},
                                                        {"u1=U1:V", "u2=U2"}, {"r1=w1*0.25", "r2=w2*0.25"}),
                                                o);
  expect_equal_to_original(result.experiment, 1e-15);
}

TEST_F(ImportExperiment, CsvInMillimetresAndMilliampsWithRenamedReorderedColumnsEqualsTheOriginal) {
  const Experiment& e = original_;
  std::string csv = "I2 [mA],time_ms,U1,gap_mm,w2,I1 [mA],U2,w1,comment\n";
  for (Eigen::Index k = 0; k < kN; ++k)
    csv += shortest(e.y(k, 2) * 1e3) + "," + shortest(e.t(k) * 1e3) + "," + shortest(e.u(k, 0)) + "," +
           shortest(e.y(k, 0) * 1e3) + "," + shortest(e.r(k, 1)) + "," + shortest(e.y(k, 1) * 1e3) + "," +
           shortest(e.u(k, 1)) + "," + shortest(e.r(k, 0)) + ",free text\n";
  write_text("logger.csv", csv);
  const ImportResult result = import_experiment(
      file("logger.csv"),
      mapping("time_ms:ms", {"x=gap_mm:mm", "i1=I1 [mA]:mA", "i2=I2 [mA]:mA"}, {"u1=U1", "u2=U2"}, {"r1=w1", "r2=w2"}),
      options_);
  EXPECT_EQ(result.file_kind, "CSV");
  expect_equal_to_original(result.experiment, 1e-14);  // mm -> m rounds in the last bits
}

TEST_F(ImportExperiment, MalformedRecordsAreRefusedNamingTheFileAndTheProblem) {
  const Experiment& e = original_;
  const auto m = [](const std::string& x_source, std::optional<std::string> t = "t") {
    return mapping(t, {"x=" + x_source, "i1=i1", "i2=i2"}, {"u1=u1", "u2=u2"}, {"r1=r1", "r2=r2"});
  };
  std::vector<std::pair<std::string, Eigen::MatrixXd>> vars{{"t", e.t},         {"x", e.y.col(0)},  {"i1", e.y.col(1)},
                                                            {"i2", e.y.col(2)}, {"u1", e.u.col(0)}, {"u2", e.u.col(1)},
                                                            {"r1", e.r.col(0)}, {"r2", e.r.col(1)}};
  auto with = [&](const std::string& name, const Eigen::MatrixXd& value) {
    auto v = vars;
    v.emplace_back(name, value);
    return v;
  };
  const std::string mat = file("bad.mat").string();

  write_mat(file("bad.mat"), vars);
  EXPECT_THAT(refusal("bad.mat", m("pos"), options_),
              AllOf(HasSubstr(mat + ": "), HasSubstr("no variable 'pos'"), HasSubstr("'x'")));
  EXPECT_THAT(
      [] {
        try {
          parse_signal_mapping("x=x:furlong");
        } catch (const Error& error) {
          return std::string(error.what());
        }
        return std::string("(accepted)");
      }(),
      HasSubstr("mapping of 'x' 'x:furlong': unknown unit 'furlong' (known: m (1 m), mm (0.001 m)"));

  write_mat(file("bad.mat"), with("short", e.y.col(0).head(kN - 1)));
  EXPECT_THAT(refusal("bad.mat", m("short"), options_),
              AllOf(HasSubstr(mat + ": "), HasSubstr("'short' (x) has 399 samples, 't' (t) has 400")));

  Eigen::VectorXd nan = e.y.col(0);
  nan(17) = std::nan("");
  write_mat(file("bad.mat"), with("xn", nan));
  EXPECT_THAT(refusal("bad.mat", m("xn"), options_),
              AllOf(HasSubstr(mat + ": "), HasSubstr("'xn': element 18 of 400 is nan")));

  write_mat(file("bad.mat"), with("both", Eigen::MatrixXd::Ones(kN, 2)));
  EXPECT_THAT(refusal("bad.mat", m("both"), options_), HasSubstr("variable 'both' is a 400x2 matrix, not a vector"));
  EXPECT_THAT(refusal("bad.mat", m("both(:,3)"), options_), HasSubstr("it has no column 3"));

  Eigen::VectorXd backwards = e.t;
  std::swap(backwards(200), backwards(201));
  vars[0].second = backwards;
  write_mat(file("bad.mat"), vars);
  EXPECT_THAT(refusal("bad.mat", m("x"), options_),
              AllOf(HasSubstr(mat + ": "), HasSubstr("time is not strictly increasing: row 202")));

  Eigen::VectorXd gap = e.t;
  gap.tail(100).array() += 50 * kT;  // 5 ms missing after row 300
  vars[0].second = gap;
  write_mat(file("bad.mat"), vars);
  EXPECT_THAT(refusal("bad.mat", m("x"), options_),
              AllOf(HasSubstr("sampling is not uniform: t steps by 0.0051"), HasSubstr("--resample")));
  ImportOptions resample = options_;
  resample.resample = true;
  EXPECT_THAT(refusal("bad.mat", m("x"), resample),
              AllOf(HasSubstr(mat + ": "), HasSubstr("a gap of 0.0051"), HasSubstr("at t = 0.0299"),
                    HasSubstr("longer than the 0.001 s")));

  const std::string csv = file("bad.csv").string();
  write_text("bad.csv", "t,x,i1,i2,u1,u2,r1,r2\n0,0,0.5,0.5,8,8,0,0\n1e-4,abc,0.5,0.5,8,8,0,0\n");
  EXPECT_THAT(refusal("bad.csv", m("x"), options_),
              AllOf(HasSubstr(csv + ": line 3, column 'x': expected a finite number, got 'abc'")));
  write_text("bad.csv", "t,x,i1,i2,u1,u2,r1,r2\n0,0,0.5,0.5,8,8,0,0\n1e-4,nan,0.5,0.5,8,8,0,0\n");
  EXPECT_THAT(refusal("bad.csv", m("x"), options_),
              HasSubstr(csv + ": line 3, column 'x': expected a finite number, got 'nan'"));
  write_text("bad.csv", "t,x,i1,i2,u1,u2,r1,r2\n0,0,0.5,0.5,8,8,0,0\n1e-4,0,0.5,0.5,8,8,0\n");
  EXPECT_THAT(refusal("bad.csv", m("x"), options_), HasSubstr(csv + ": line 3 has 7 cells, the header has 8"));
  EXPECT_THAT(refusal("missing.csv", m("x"), options_), HasSubstr(file("missing.csv").string() + ": no such file"));
  EXPECT_THAT(refusal("bad.mat", mapping("t", {"x=x"}, {"u1=u1", "u2=u2"}, {"r1=r1", "r2=r2"}), options_),
              HasSubstr("the template's signals.y are x, i1, i2 but the mapping gives x"));
}

TEST_F(ImportExperiment, MappingFilesAreReadAndTheirErrorsNameTheFileAndKey) {
  write_text("mapping.json", R"json({"t": "time:ms", "y": ["x=pos:mm", "i1=A(:,2)*2"], "u": ["u1=U"],
                                     "sample_time": 1e-4})json");
  const ImportMapping m = read_import_mapping(file("mapping.json"));
  ASSERT_TRUE(m.t);
  EXPECT_EQ(m.t->source, "time");
  EXPECT_EQ(m.t->unit, "ms");
  ASSERT_EQ(m.y.size(), 2u);
  EXPECT_EQ(m.y[0].name, "x");
  EXPECT_EQ(m.y[0].unit, "mm");
  EXPECT_EQ(m.y[1].source, "A(:,2)");
  EXPECT_EQ(m.y[1].scale, 2.0);
  EXPECT_EQ(m.sample_time, 1e-4);
  write_text("mapping.json", R"({"t": "time", "outputs": ["x=pos"]})");
  try {
    read_import_mapping(file("mapping.json"));
    ADD_FAILURE() << "accepted an unknown key";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr(file("mapping.json").string() + ": unknown key `outputs`"));
  }
  write_text("mapping.json", R"({"t": "time:mm"})");
  EXPECT_THROW(read_import_mapping(file("mapping.json")), Error);  // a length is no time unit
}

TEST_F(ImportExperiment, ResamplesANonUniformSineOntoTheMedianStepWithinTheLinearInterpolationBound) {
  // Time stamps jittered by up to +-30 % of the step; y = sin(2 pi f t) in mm.
  const double f = 5.0, T = 1e-3, amplitude_mm = 2.0;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(-0.3 * T, 0.3 * T);
  const Eigen::Index n = 2001;
  Eigen::VectorXd t(n), x(n), u(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    t(k) = double(k) * T + (k == 0 || k == n - 1 ? 0.0 : jitter(rng));
    x(k) = amplitude_mm * std::sin(2 * M_PI * f * t(k));
    u(k) = 3.0;
  }
  write_mat(file("jitter.mat"), {{"time", t}, {"pos", x}, {"cmd", u}});
  ImportOptions o;
  o.plant_model = "maglev1coil_voltage";
  o.resample = true;
  o.sample_time = T;
  const ImportResult result = import_experiment(file("jitter.mat"), mapping("time", {"x=pos:mm"}, {"u=cmd"}, {}), o);
  const Experiment& e = result.experiment;
  ASSERT_EQ(e.samples(), n);  // the span is exactly (n - 1) T
  // Linear interpolation errs by at most h^2/8 max|x''| with h the widest step (1.6 T).
  const double w = 2 * M_PI * f, bound = std::pow(1.6 * T, 2) / 8 * amplitude_mm * 1e-3 * w * w;
  double worst = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) {
    EXPECT_NEAR(e.t(k), double(k) * T, 1e-15);
    worst = std::max(worst, std::abs(e.y(k, 0) - amplitude_mm * 1e-3 * std::sin(w * double(k) * T)));
  }
  EXPECT_LT(worst, bound);
  EXPECT_GT(worst, 1e-3 * bound);  // interpolation did happen (the jittered rows were not copied)
  EXPECT_THAT(result.steps, ::testing::Contains(HasSubstr("sample time 0.001 s (given)")));
}

const fs::path kMaglev = fs::path(AMBID_SOURCE_DIR) / "tests/data/labcontrol-maglev";

// A variable of a MAT file read directly with libmatio (not through the importer).
Eigen::MatrixXd read_mat_matrix(const fs::path& path, const std::string& name) {
  mat_t* mat = Mat_Open(path.c_str(), MAT_ACC_RDONLY);
  if (!mat) throw std::runtime_error("cannot open " + path.string());
  matvar_t* var = Mat_VarRead(mat, name.c_str());
  if (!var || var->class_type != MAT_C_DOUBLE) throw std::runtime_error("no double variable " + name);
  const Eigen::MatrixXd m = Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(var->data),
                                                              Eigen::Index(var->dims[0]), Eigen::Index(var->dims[1]));
  Mat_VarFree(var);
  Mat_Close(mat);
  return m;
}

TEST_F(ImportExperiment, VendoredMaglevRecordsAreRefusedUnresampledAndImportedResampled) {
  // Classic_PID.mat: Aclas = [time s, position V, control], 4847 rows, time rounded to 0.01 s
  // with steps of 0.01 to 0.19 s (tests/data/labcontrol-maglev/README.md).
  const ImportMapping m = mapping("Aclas(:,1)", {"x=Aclas(:,2)"}, {"u=Aclas(:,3)"}, {});
  ImportOptions o;
  o.plant_model = "maglev1coil_voltage";
  const fs::path record = kMaglev / "Classic_PID.mat";
  EXPECT_THAT(refusal_of(record, m, o),
              HasSubstr(record.string() + ": sampling is not uniform: t steps by 0.03 s from t = 0 s (row 1)"));
  o.resample = true;
  const ImportResult result = import_experiment(record, m, o);
  const Experiment& e = result.experiment;
  EXPECT_EQ(result.rows, 4847);
  EXPECT_EQ(e.sample_time, 0.02);  // the median step, without the round-off of 0.03 - 0.01
  const Eigen::MatrixXd raw = read_mat_matrix(record, "Aclas");
  ASSERT_EQ(raw.rows(), 4847);
  EXPECT_EQ(e.t(0), raw(0, 0));
  EXPECT_EQ(e.samples(), Eigen::Index(std::floor((raw(4846, 0) - raw(0, 0)) / 0.02 + 1e-9)) + 1);
  // Where a grid point falls on a recorded time, the resampled values are the recorded ones.
  Eigen::Index matched = 0;
  for (Eigen::Index row = 0; row < raw.rows(); ++row) {
    const double k = (raw(row, 0) - raw(0, 0)) / 0.02;
    if (std::abs(k - std::round(k)) > 1e-6) continue;
    const auto j = Eigen::Index(std::round(k));
    EXPECT_NEAR(e.y(j, 0), raw(row, 1), 1e-9) << "row " << row;
    EXPECT_NEAR(e.u(j, 0), raw(row, 2), 1e-9) << "row " << row;
    ++matched;
  }
  EXPECT_GT(matched, 1000);
  EXPECT_NO_THROW(e.validate());

  // Proposed_PID.mat has steps up to 1.57 s: longer than 10 sample times, so refused unless
  // the limit is raised.
  const fs::path proposed = kMaglev / "Proposed_PID.mat";
  const ImportMapping pm = mapping("A(:,1)", {"x=A(:,2)"}, {"u=A(:,3)"}, {});
  EXPECT_THAT(refusal_of(proposed, pm, o),
              AllOf(HasSubstr(proposed.string() + ": a gap of 1.57"), HasSubstr("refusing to interpolate")));
  o.max_gap = 2.0;
  EXPECT_EQ(import_experiment(proposed, pm, o).rows, 1638);
}

}  // namespace experiment_import_test
}  // namespace ambid
