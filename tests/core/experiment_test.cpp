// The Experiment type, its validation, and write/read round trips.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

#include "core/error.hpp"
#include "core/experiment.hpp"
#include "core/experiment_io.hpp"

namespace ambid {
namespace experiment_test {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

// The message of the Error that `f` throws, or a failure when it throws none.
template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no ambid::Error thrown";
  return {};
}

StateSpaceController example_controller() {
  StateSpaceController c;
  c.sample_time = 1e-4;
  c.inputs = {"u1", "u2", "x", "i1", "i2"};
  c.outputs = {"u1", "u2"};
  c.A = Eigen::MatrixXd::Identity(4, 4) * 0.9;
  c.A(0, 1) = 1.0 / 3.0;
  c.B = Eigen::MatrixXd::Zero(4, 5);
  c.B(1, 2) = -2.5e3;
  c.C = Eigen::MatrixXd::Constant(2, 4, 0.1);
  c.D = Eigen::MatrixXd::Zero(2, 5);
  c.D(0, 2) = -7e4;  // x feeds through; u1, u2 (columns 0, 1) must not
  c.D(1, 2) = 7e4;
  c.initial_state = Eigen::VectorXd::LinSpaced(4, -1.0, 1.0 / 7.0);
  return c;
}

// The amb1dof_voltage example of experiment-format.md with 20 samples of awkward doubles.
Experiment example_experiment() {
  Experiment e;
  e.name = "round trip, \"quoted\" and ünïcode";
  e.sample_time = 1e-4;
  e.plant.model = "amb1dof_voltage";
  e.plant.parameters = {{"m", 1.8}, {"x0", 3.5e-4}, {"i0", 0.5}, {"R1", 17.5}, {"K1", 2.401e-4}};
  e.y_names = {"x", "i1", "i2"};
  e.u_names = {"u1", "u2"};
  e.r_names = {"r1", "r2"};
  e.operating_point = {{"x", 0.0}, {"i1", 0.5}, {"i2", 0.5}, {"u1", 8.75}, {"u2", 8.75}, {"r1", 0.1}};
  e.controller = example_controller();
  const Eigen::Index n = 20;
  e.t = Eigen::VectorXd::LinSpaced(n, 0.0, static_cast<double>(n - 1)) * 1e-4;
  std::mt19937_64 random(7);
  std::normal_distribution<double> noise;
  auto fill = [&](Eigen::MatrixXd& m, Eigen::Index cols, double scale) {
    m.resize(n, cols);
    for (Eigen::Index k = 0; k < n; ++k)
      for (Eigen::Index j = 0; j < cols; ++j) m(k, j) = scale * noise(random);
  };
  fill(e.y, 3, 1e-5);
  fill(e.u, 2, 8.0);
  fill(e.r, 2, 0.3);
  e.extra.json() = {{"rig", {{"id", "A"}, {"temperatures", {20.5, 21}}}},
                    {"plant", {{"serial", 7}}},
                    {"signals", {{"units", {{"x", "m"}}}}},
                    {"controller", {{"design", "lqr"}}}};
  return e;
}

class ExperimentFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("ambid-experiment-test-" + std::string(info->name()) + "-" + std::to_string(std::random_device{}()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

void expect_identical(const Experiment& a, const Experiment& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.sample_time, b.sample_time);
  EXPECT_EQ(a.plant.model, b.plant.model);
  EXPECT_EQ(a.plant.parameters, b.plant.parameters);
  EXPECT_EQ(a.y_names, b.y_names);
  EXPECT_EQ(a.u_names, b.u_names);
  EXPECT_EQ(a.r_names, b.r_names);
  EXPECT_EQ(a.operating_point, b.operating_point);
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.u, b.u);
  EXPECT_EQ(a.r.cols(), b.r.cols());
  if (a.r.cols() > 0) {
    EXPECT_EQ(a.r, b.r);
  }
  EXPECT_EQ(a.extra.json(), b.extra.json());
  ASSERT_EQ(a.controller.has_value(), b.controller.has_value());
  if (!a.controller) return;
  const StateSpaceController &ca = *a.controller, &cb = *b.controller;
  EXPECT_EQ(ca.kind, cb.kind);
  EXPECT_EQ(ca.sample_time, cb.sample_time);
  EXPECT_EQ(ca.inputs, cb.inputs);
  EXPECT_EQ(ca.outputs, cb.outputs);
  EXPECT_EQ(ca.A, cb.A);
  EXPECT_EQ(ca.B, cb.B);
  EXPECT_EQ(ca.C, cb.C);
  EXPECT_EQ(ca.D, cb.D);
  EXPECT_EQ(ca.initial_state, cb.initial_state);
}

TEST(Experiment, ExampleIsValid) { EXPECT_NO_THROW(example_experiment().validate()); }

TEST(Experiment, OperatingValueOfUnlistedSignalIsZero) {
  const Experiment e = example_experiment();
  EXPECT_EQ(e.operating_value("i1"), 0.5);
  EXPECT_EQ(e.operating_value("r1"), 0.1);
  EXPECT_EQ(e.operating_value("r2"), 0.0);
  EXPECT_EQ(e.operating_values({"u2", "r2", "x"}), Eigen::Vector3d(8.75, 0.0, 0.0));
}

TEST(Experiment, DeviationsSubtractTheOperatingPoint) {
  const Experiment e = example_experiment();
  EXPECT_EQ(e.y_deviation().col(1), (e.y.col(1).array() - 0.5).matrix());
  EXPECT_EQ(e.u_deviation().col(0), (e.u.col(0).array() - 8.75).matrix());
  EXPECT_EQ(e.r_deviation().col(0), (e.r.col(0).array() - 0.1).matrix());
  EXPECT_EQ(e.r_deviation().col(1), e.r.col(1));
}

TEST(Experiment, SignalFindsAnyNamedColumn) {
  const Experiment e = example_experiment();
  EXPECT_EQ(e.signal("i2"), e.y.col(2));
  EXPECT_EQ(e.signal("u1"), e.u.col(0));
  EXPECT_EQ(e.signal("r2"), e.r.col(1));
  EXPECT_THAT(error_of([&] { e.signal("z"); }), HasSubstr("no signal 'z'; its signals are x, i1, i2, u1"));
}

TEST(Experiment, ValidateRequiresOperatingValueOfEveryYAndU) {
  Experiment e = example_experiment();
  e.operating_point.erase("i2");
  EXPECT_THAT(error_of([&] { e.validate(); }), HasSubstr("operating_point.i2 is missing"));
}

TEST(Experiment, ValidateRefusesSamplesThatDoNotMatchTheNames) {
  Experiment e = example_experiment();
  e.u.conservativeResize(Eigen::NoChange, 1);
  EXPECT_THAT(error_of([&] { e.validate(); }), HasSubstr("u must be 20x2 (samples x signals), got 20x1"));
}

TEST(Experiment, ValidateRefusesNonFiniteSample) {
  Experiment e = example_experiment();
  e.y(3, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(error_of([&] { e.validate(); }), HasSubstr("sample 3 of signal 'i1' must be finite, got nan"));
}

TEST(Experiment, ValidateRefusesNonUniformSampling) {
  Experiment e = example_experiment();
  e.t.tail(5).array() += 2e-6;  // a 2 % longer step between samples 14 and 15
  EXPECT_THAT(error_of([&] { e.validate(); }), HasSubstr("t[15] - t[14] = "));
}

TEST(Experiment, ValidateRefusesNonFiniteParameter) {
  Experiment e = example_experiment();
  e.plant.parameters["m"] = -std::numeric_limits<double>::infinity();
  EXPECT_THAT(error_of([&] { e.validate(); }), HasSubstr("plant.parameters.m must be finite, got -inf"));
}

TEST(Experiment, ValidateRefusesNonPositiveSampleTime) {
  Experiment e = example_experiment();
  e.sample_time = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(error_of([&] { e.validate(); }),
              HasSubstr("sample_time must be a positive finite number of seconds, got nan"));
}

TEST(Experiment, ValidateRefusesExtraThatShadowsADefinedKey) {
  Experiment e = example_experiment();
  e.extra.json()["plant"]["model"] = "other";
  EXPECT_THAT(error_of([&] { e.validate(); }), HasSubstr("extra.plant holds 'model', a key the format defines"));
  e.extra.json() = {{"sample_time", 1.0}};
  EXPECT_THAT(error_of([&] { e.validate(); }), HasSubstr("extra holds 'sample_time'"));
}

TEST(StateSpaceController, ValidateNamesTheMatrixAndItsExpectedShape) {
  StateSpaceController c = example_controller();
  c.B = Eigen::MatrixXd::Zero(4, 3);
  EXPECT_THAT(error_of([&] {
                c.validate({"u1", "u2"});
              }),
              HasSubstr("controller.B must be 4x5 (states x inputs), got 4x3"));
}

TEST(StateSpaceController, ValidateRefusesAnAlgebraicLoopThroughD) {
  StateSpaceController c = example_controller();
  c.D(1, 1) = 0.25;
  const std::string message = error_of([&] { c.validate({"u1", "u2"}); });
  EXPECT_THAT(message, HasSubstr("controller.D column 1 (input 'u2') must be zero"));
  EXPECT_THAT(message, HasSubstr("algebraic loop"));
  EXPECT_THAT(message, HasSubstr("D[1][1] = 0.25"));
}

TEST(StateSpaceController, ValidateRefusesAnOutputThatIsNoPlantInput) {
  StateSpaceController c = example_controller();
  c.outputs = {"u1", "x"};
  EXPECT_THAT(error_of([&] {
                c.validate({"u1", "u2"});
              }),
              HasSubstr("controller.outputs names 'x', which is not a u signal (signals.u: u1, u2)"));
}

TEST(StateSpaceController, ValidateRefusesNonFiniteEntry) {
  StateSpaceController c = example_controller();
  c.A(2, 3) = std::numeric_limits<double>::infinity();
  EXPECT_THAT(error_of([&] { c.validate({"u1", "u2"}); }), HasSubstr("controller.A[2][3] must be finite, got inf"));
}

TEST_F(ExperimentFiles, RoundTripIsBitIdentical) {
  const Experiment e = example_experiment();
  write_experiment(e, dir_ / "run7");
  const ReadResult back = read_experiment(dir_ / "run7.json");
  EXPECT_TRUE(back.warnings.empty());
  expect_identical(e, back.experiment);
}

TEST_F(ExperimentFiles, RoundTripOfAwkwardDoubles) {
  Experiment e = example_experiment();
  const double awkward[] = {-0.0,      5e-324,    2.2250738585072014e-308, 1.7976931348623157e308,
                            0.1 + 0.2, 1.0 / 3.0, -123456789.123456789,    1e21,
                            1e-7};
  for (std::size_t i = 0; i < std::size(awkward); ++i) e.y(static_cast<Eigen::Index>(i), 0) = awkward[i];
  e.plant.parameters["tiny"] = 5e-324;
  e.controller->A(3, 3) = 0.1 + 0.2;
  write_experiment(e, dir_ / "awkward");
  const Experiment back = read_experiment(dir_ / "awkward").experiment;
  expect_identical(e, back);
  EXPECT_TRUE(std::signbit(back.y(0, 0)));
}

TEST_F(ExperimentFiles, RoundTripWithoutExcitationControllerOrExtra) {
  Experiment e = example_experiment();
  e.r_names.clear();
  e.r.resize(0, 0);
  e.operating_point.erase("r1");
  e.controller.reset();
  e.extra = JsonValue();
  write_experiment(e, dir_ / "plain");
  const Experiment back = read_experiment(dir_ / "plain.csv").experiment;
  EXPECT_FALSE(back.has_excitation());
  EXPECT_FALSE(back.controller.has_value());
  EXPECT_EQ(back.r.rows(), e.samples());
  EXPECT_EQ(back.r.cols(), 0);
  e.extra = JsonValue::object();  // the reader always gives an object
  expect_identical(e, back);
}

TEST_F(ExperimentFiles, RoundTripOfAStatelessController) {
  Experiment e = example_experiment();
  StateSpaceController& c = *e.controller;
  c.A.resize(0, 0);
  c.B.resize(0, 5);
  c.C.resize(2, 0);
  c.initial_state.resize(0);
  write_experiment(e, dir_ / "static");
  expect_identical(e, read_experiment(dir_ / "static").experiment);
}

TEST_F(ExperimentFiles, SidecarKeepsUnknownKeysWhereTheyWere) {
  const nlohmann::json j = sidecar_json(example_experiment());
  EXPECT_EQ(j["format"], "ambid-experiment/1");
  EXPECT_EQ(j["rig"]["id"], "A");
  EXPECT_EQ(j["plant"]["serial"], 7);
  EXPECT_EQ(j["plant"]["model"], "amb1dof_voltage");
  EXPECT_EQ(j["signals"]["units"]["x"], "m");
  EXPECT_EQ(j["controller"]["design"], "lqr");
  EXPECT_EQ(j["controller"]["kind"], "state_space");
}

TEST_F(ExperimentFiles, WriterRefusesAnInvalidExperimentAndWritesNothing) {
  Experiment e = example_experiment();
  e.controller->sample_time = 2e-4;
  EXPECT_THAT(error_of([&] { write_experiment(e, dir_ / "sub" / "bad"); }),
              HasSubstr("controller.sample_time 2e-4 must equal sample_time 1e-4"));
  EXPECT_FALSE(fs::exists(dir_ / "sub"));
}

TEST_F(ExperimentFiles, WriterCreatesTheDirectoryAndLeavesOnlyTheTwoFiles) {
  write_experiment(example_experiment(), dir_ / "a" / "b" / "run.json");
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir_ / "a" / "b")) names.push_back(entry.path().filename());
  EXPECT_THAT(names, ::testing::UnorderedElementsAre("run.csv", "run.json"));
}

TEST_F(ExperimentFiles, WriterReplacesExistingFiles) {
  Experiment e = example_experiment();
  write_experiment(e, dir_ / "run");
  e.name = "second";
  e.t = e.t.head(5).eval();
  e.y = e.y.topRows(5).eval();
  e.u = e.u.topRows(5).eval();
  e.r = e.r.topRows(5).eval();
  write_experiment(e, dir_ / "run.csv");
  expect_identical(e, read_experiment(dir_ / "run").experiment);
}

TEST_F(ExperimentFiles, WriterReportsAnUnwritableTarget) {
  fs::create_directories(dir_ / "run.csv");  // a directory where the CSV should go
  EXPECT_THAT(error_of([&] { write_experiment(example_experiment(), dir_ / "run"); }),
              HasSubstr("cannot replace " + (dir_ / "run.csv").string()));
  EXPECT_FALSE(fs::exists(dir_ / "run.json"));
}

}  // namespace experiment_test
}  // namespace ambid
