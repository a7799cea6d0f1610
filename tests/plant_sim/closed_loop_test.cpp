// The closed-loop runner against independent truth: on a linear plant the recorded loop must
// equal the exact ZOH closed loop, and any recording must replay through its own controller.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/controller_replay.hpp"
#include "core/error.hpp"
#include "core/state_space.hpp"
#include "plant_sim/closed_loop.hpp"
#include "plant_sim/linear_plant.hpp"
#include "plant_sim/observer_controller.hpp"
#include "plant_sim/sales_rotor.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::sim {
namespace closed_loop_test {

using ::testing::HasSubstr;

// Sales rotor (unstable, +52.9 rad/s) under an observer controller with integral action.
struct RotorLoop {
  NamedSystem named = sales_rotor();
  LinearPlant plant{named};
  Experiment header;

  RotorLoop() {
    header.name = "rotor";
    header.sample_time = 1e-3;
    header.plant.model = named.model;
    header.y_names = named.output_names;
    header.u_names = named.input_names;
    header.r_names = {"r"};
    ObserverControllerOptions o;
    o.integral_outputs = named.output_names;
    o.Q = Eigen::MatrixXd::Identity(2, 2) * 1e2;
    o.Q_integral = Eigen::MatrixXd::Identity(1, 1) * 1e3;
    o.R = Eigen::MatrixXd::Identity(1, 1);
    o.W = Eigen::MatrixXd::Identity(2, 2);
    o.V = Eigen::MatrixXd::Identity(1, 1) * 1e-2;
    header.controller = design_observer_controller(named.system, header.sample_time, header.u_names, header.y_names, o);
  }
};

TEST(ClosedLoop, LinearPlantMatchesExactZohClosedLoop) {
  RotorLoop loop;
  ClosedLoopOptions options;
  options.samples = 400;
  options.excitation = Eigen::MatrixXd::Random(400, 1);
  options.substeps = 8;
  const Experiment e = run_closed_loop(loop.plant, loop.header, options);

  const DiscreteSystem plant_d = c2d_zoh(loop.named.system, loop.header.sample_time);
  const DiscreteSystem cl =
      linear_closed_loop(plant_d, loop.header.u_names, loop.header.y_names, *loop.header.controller);
  ASSERT_LT(spectral_radius(cl), 1.0);
  const Eigen::MatrixXd expected = simulate(cl, options.excitation);  // outputs [y; u]
  const double scale = expected.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  // RK4 with 8 sub-steps of 1.25e-4 s on a 53 rad/s plant: error ~ (53 * 1.25e-4)^4 / 120.
  EXPECT_LT((e.y.col(0) - expected.col(0)).cwiseAbs().maxCoeff(), 1e-9 * scale);
  EXPECT_LT((e.u.col(0) - expected.col(1)).cwiseAbs().maxCoeff(), 1e-9 * scale);
  EXPECT_EQ(e.r, options.excitation);
  for (Eigen::Index k = 0; k < e.samples(); ++k) EXPECT_DOUBLE_EQ(e.t(k), double(k) * 1e-3);
}

// Replays the recorded y and u of `e` through its recorded controller (inputs [u; y], as the
// observer design orders them) and returns the largest |u - r - uf| over the record.
double replay_error(const Experiment& e) {
  const StateSpaceController& c = *e.controller;
  const Eigen::RowVectorXd y_op = e.operating_values(e.y_names).transpose();
  const Eigen::RowVectorXd u_op = e.operating_values(e.u_names).transpose();
  const Eigen::RowVectorXd r_op = e.operating_values(e.r_names).transpose();
  Eigen::VectorXd xc = Eigen::VectorXd::Zero(c.states());
  double worst = 0.0;
  for (Eigen::Index k = 0; k < e.samples(); ++k) {
    Eigen::VectorXd v(c.B.cols());
    v << (e.u.row(k) - u_op).transpose(), (e.y.row(k) - y_op).transpose();
    const Eigen::VectorXd uf = c.C * xc + c.D * v;
    worst = std::max(worst, ((e.u.row(k) - u_op - e.r.row(k) + r_op).transpose() - uf).cwiseAbs().maxCoeff());
    xc = c.A * xc + c.B * v;
  }
  return worst;
}

// The contract's promise: the recorded y and u replay through the recorded controller.
TEST(ClosedLoop, RecordingReplaysThroughItsController) {
  RotorLoop loop;
  ClosedLoopOptions options;
  options.samples = 300;
  options.excitation = Eigen::MatrixXd::Random(300, 1) * 0.1;
  options.measurement_noise_std = Eigen::VectorXd::Constant(1, 0.05);
  options.process_noise_std = Eigen::VectorXd::Constant(1, 0.2);
  options.seed = 11;
  EXPECT_LT(replay_error(run_closed_loop(loop.plant, loop.header, options)), 1e-12);
}

// The same for the amb1dof observer controller, which the runner evaluates with fixed-size
// matrices (the rotor's takes the dynamic path).
TEST(ClosedLoop, Amb1dofRecordingReplaysThroughItsController) {
  ScenarioOptions o;
  o.duration = 0.05;
  o.position_noise = 1e-7;
  o.current_noise = 1e-4;
  o.force_noise = 0.1;
  const Experiment e = simulate_scenario(o);
  ASSERT_EQ(e.controller->states(), 5);
  EXPECT_GT((e.u.rowwise() - e.u.row(0)).cwiseAbs().maxCoeff(), 0.05);  // the loop really moved
  EXPECT_LT(replay_error(e), 1e-12);
}

// A record logged at a coarse resolution, followed: the controller reads the logged value
// while the plant lies within half a step of it, so the same plant driven by the excitation
// reconstructed from the rounded record (u - the controller's answer to the logged y) gives
// the recorded commands back; read as it is, the plant's output makes the controller answer
// the rounding, and the replay parts from the record.
TEST(ClosedLoop, ARoundedRecordIsFollowedWithinHalfAStep) {
  RotorLoop loop;
  ClosedLoopOptions options;
  options.samples = 400;
  options.excitation = Eigen::MatrixXd::Random(400, 1) * 0.1;
  Experiment logged = run_closed_loop(loop.plant, loop.header, options);
  const Eigen::MatrixXd commanded = logged.u;
  const double step = 1e-2 * logged.y.cwiseAbs().maxCoeff(), u_scale = commanded.cwiseAbs().maxCoeff();
  ASSERT_GT(step, 0.0);
  logged.y = (logged.y / step).array().round().matrix() * step;
  options.excitation = logged.u - replay_controller(logged).output;  // no operating point: deviations

  ClosedLoopOptions followed = options;
  followed.followed = logged.y;
  followed.followed_resolution = Eigen::VectorXd::Constant(1, step);
  const Experiment replay = run_closed_loop(loop.plant, loop.header, followed);
  EXPECT_LT((replay.u - commanded).cwiseAbs().maxCoeff(), 1e-9 * u_scale);
  EXPECT_LE((replay.y - logged.y).cwiseAbs().maxCoeff(), 0.5 * step * (1.0 + 1e-9));

  const Experiment unfollowed = run_closed_loop(loop.plant, loop.header, options);
  EXPECT_GT((unfollowed.u - commanded).cwiseAbs().maxCoeff(), 1e-3 * u_scale);

  followed.followed_resolution = Eigen::VectorXd::Constant(2, step);
  EXPECT_THAT([&] { run_closed_loop(loop.plant, loop.header, followed); },
              ::testing::ThrowsMessage<Error>(HasSubstr("followed_resolution has 2 entries, expected 1")));
}

// A plant error inside the loop surfaces with the time it happened: 100 V on coil 1 pulls the
// rotor into the bearing within milliseconds.
TEST(ClosedLoop, TouchdownNamesTheTime) {
  ScenarioOptions o;
  o.duration = 0.05;
  Scenario s = build_scenario(o);
  s.options.excitation.col(0).setConstant(100.0);
  EXPECT_THAT([&] { run_closed_loop(*s.truth, s.header, s.options); },
              ::testing::ThrowsMessage<Error>(
                  ::testing::AllOf(HasSubstr("closed loop: at t = 0.00"), HasSubstr("rotor touched the bearing"))));
}

TEST(ClosedLoop, SeedReproducesNoiseExactly) {
  RotorLoop loop;
  ClosedLoopOptions options;
  options.samples = 50;
  options.excitation = Eigen::MatrixXd::Zero(50, 1);
  options.measurement_noise_std = Eigen::VectorXd::Constant(1, 0.01);
  options.seed = 5;
  const Experiment a = run_closed_loop(loop.plant, loop.header, options);
  const Experiment b = run_closed_loop(loop.plant, loop.header, options);
  EXPECT_EQ(a.y, b.y);
  options.seed = 6;
  const Experiment c = run_closed_loop(loop.plant, loop.header, options);
  EXPECT_NE(a.y, c.y);
}

TEST(ClosedLoop, ActuatorLimitsAreCounted) {
  RotorLoop loop;
  ClosedLoopOptions options;
  options.samples = 100;
  options.excitation = Eigen::MatrixXd::Constant(100, 1, 5.0);
  options.input_lower = Eigen::VectorXd::Constant(1, -1.0);
  options.input_upper = Eigen::VectorXd::Constant(1, 1.0);
  ClosedLoopStatistics stats;
  const Experiment e = run_closed_loop(loop.plant, loop.header, options, &stats);
  EXPECT_GT(stats.saturated_samples, 0);
  EXPECT_GT(e.u.cwiseAbs().maxCoeff(), 1.0);  // the commanded value is recorded, not the clipped one
}

TEST(ClosedLoop, BadInputsAreNamed) {
  RotorLoop loop;
  ClosedLoopOptions options;
  options.samples = 10;
  options.excitation = Eigen::MatrixXd::Zero(9, 1);
  EXPECT_THAT([&] { run_closed_loop(loop.plant, loop.header, options); },
              ::testing::ThrowsMessage<Error>(HasSubstr("excitation must be 10x1")));
  options.excitation = Eigen::MatrixXd::Zero(10, 1);
  options.measurement_noise_std = Eigen::VectorXd::Constant(2, 0.1);
  EXPECT_THAT([&] { run_closed_loop(loop.plant, loop.header, options); },
              ::testing::ThrowsMessage<Error>(HasSubstr("measurement_noise_std has 2 entries, expected 1")));
  Experiment no_controller = loop.header;
  no_controller.controller.reset();
  options.measurement_noise_std.resize(0);
  EXPECT_THAT([&] { run_closed_loop(loop.plant, no_controller, options); },
              ::testing::ThrowsMessage<Error>(HasSubstr("no controller")));
}

TEST(ClosedLoop, DivergenceIsReportedWithTime) {
  RotorLoop loop;
  loop.header.controller->C.setZero();  // open loop: the rotor diverges at +52.9 rad/s
  loop.header.controller->D.setZero();
  ClosedLoopOptions options;
  options.samples = 200000;
  options.excitation = Eigen::MatrixXd::Constant(200000, 1, 1.0);
  EXPECT_THAT([&] { run_closed_loop(loop.plant, loop.header, options); },
              ::testing::ThrowsMessage<Error>(HasSubstr("non-finite at t =")));
}

}  // namespace closed_loop_test
}  // namespace ambid::sim
