// controller.output_limits / state_limits: read, validated, written back; the replayed
// controller marks exactly the samples where a clamp acted (hand-computed scalar loop).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <random>

#include "core/controller_replay.hpp"
#include "core/error.hpp"
#include "core/experiment_io.hpp"

namespace ambid {
namespace controller_replay_test {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

// An integrator xc[k+1] = xc[k] + y[k], uf = xc (a scalar I controller), u = uf + r.
Experiment integrator_loop() {
  Experiment e;
  e.name = "integrator";
  e.sample_time = 0.01;
  e.plant.model = "test";
  e.y_names = {"y"};
  e.u_names = {"u"};
  e.r_names = {"r"};
  e.operating_point = {{"y", 0.0}, {"u", 5.0}};
  StateSpaceController k;
  k.sample_time = 0.01;
  k.inputs = {"y"};
  k.outputs = {"u"};
  k.A = Eigen::MatrixXd::Constant(1, 1, 1.0);
  k.B = Eigen::MatrixXd::Constant(1, 1, 1.0);
  k.C = Eigen::MatrixXd::Constant(1, 1, 1.0);
  k.D = Eigen::MatrixXd::Zero(1, 1);
  e.controller = k;
  const Eigen::Index n = 6;
  e.t = Eigen::VectorXd::LinSpaced(n, 0.0, 0.05);
  e.y.resize(n, 1);
  e.y << 1, 1, 1, -1, -1, 0;  // xc: 0, 1, 2, 3, 2, 1
  e.r.resize(n, 1);
  e.r << 0.5, 0, 0, 0, 0, 0;
  e.u.resize(n, 1);
  e.u << 5.5, 6, 7, 8, 7, 6;  // 5 + xc + r
  return e;
}

TEST(ControllerReplay, OutputAndStateClampsMarkTheirSamples) {
  Experiment e = integrator_loop();
  // Unclamped replay: uf = xc = 0, 1, 2, 3, 2, 1 (deviations).
  ControllerReplay free = replay_controller(e);
  EXPECT_EQ(free.output.col(0), (Eigen::VectorXd(6) << 0, 1, 2, 3, 2, 1).finished());
  EXPECT_EQ(free.clamped_samples, 0);

  // The state clamped to [-1, 2]: the update at k = 2 (2 + 1 = 3) is cut to 2, so from then
  // xc = 2, 1, 0; only sample 2 had a clamp acting.
  e.controller->state_limits = {Limit{-1.0, 2.0}};
  const ControllerReplay clamped = replay_controller(e);
  EXPECT_EQ(clamped.output.col(0), (Eigen::VectorXd(6) << 0, 1, 2, 2, 1, 0).finished());
  EXPECT_EQ(clamped.clamped, (std::vector<bool>{false, false, true, false, false, false}));

  // An output limit on the absolute u = 5.5, 6, 7, 8, 7, 6: at (7) or beyond (8) the bound 7.
  e.controller->state_limits.clear();
  e.controller->output_limits = {Limit{-std::numeric_limits<double>::infinity(), 7.0}};
  const ControllerReplay output = clamped_samples(e);
  EXPECT_EQ(output.clamped, (std::vector<bool>{false, false, true, true, true, false}));
  EXPECT_EQ(output.clamped_samples, 3);
}

TEST(ControllerReplay, LimitsTravelThroughTheSidecarAndBadOnesAreRefused) {
  Experiment e = integrator_loop();
  e.controller->output_limits = {Limit{0.0, std::numeric_limits<double>::infinity()}};
  e.controller->state_limits = {Limit{-1.0, 2.0}};
  const fs::path dir = fs::temp_directory_path() / ("ambid-limits-" + std::to_string(std::random_device{}()));
  write_experiment(e, dir / "run");
  std::ifstream in(dir / "run.json");
  const nlohmann::json sidecar = nlohmann::json::parse(in);
  EXPECT_EQ(sidecar["controller"]["output_limits"], nlohmann::json::parse("[[0, null]]"));
  EXPECT_EQ(sidecar["controller"]["state_limits"], nlohmann::json::parse("[[-1, 2]]"));
  const ReadResult read = read_experiment(dir / "run");
  ASSERT_EQ(read.experiment.controller->state_limits.size(), 1u);
  EXPECT_EQ(read.experiment.controller->state_limits[0].hi, 2.0);
  EXPECT_EQ(read.experiment.controller->output_limits[0].lo, 0.0);
  EXPECT_EQ(read.experiment.controller->output_limits[0].hi, std::numeric_limits<double>::infinity());
  EXPECT_EQ(read.clamped_samples, 1);  // the state clamp at sample 2
  EXPECT_THAT(read.warnings.back(), HasSubstr("1 of 6 samples have a controller clamp acting"));

  e.controller->state_limits = {Limit{2.0, 1.0}};
  EXPECT_THAT(
      [&] {
        try {
          e.validate();
        } catch (const Error& error) {
          return std::string(error.what());
        }
        return std::string("(accepted)");
      }(),
      HasSubstr("controller.state_limits[0] must be [lo, hi] with lo < hi, got [2, 1]"));
  e.controller->state_limits = {Limit{}, Limit{}};
  EXPECT_THROW(e.validate(), Error);
  fs::remove_all(dir);
}

}  // namespace controller_replay_test
}  // namespace ambid
