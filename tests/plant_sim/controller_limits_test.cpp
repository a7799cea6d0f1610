// The closed loop applies the sidecar's controller.output_limits and state_limits, and the
// reader's replay of the recorded controller (core/controller_replay.hpp) finds the same
// clamped samples and the same controller output at every sample.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/controller_replay.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::sim {
namespace controller_limits_test {

TEST(ControllerLimits, SimulationAndReplayAgreeOnClampsAndControllerOutput) {
  ScenarioOptions o;
  o.controller = "pid";
  o.amplitude = 0.3;
  o.duration = 0.3;
  o.seed = 5;
  Scenario s = build_scenario(o);
  // First without clamps: the range of each controller state gives limits that act sometimes.
  const Experiment free = run_closed_loop(*s.truth, s.header, s.options);
  const ControllerReplay unclamped = replay_controller(free);
  ASSERT_EQ(unclamped.clamped_samples, 0);
  StateSpaceController& k = *s.header.controller;
  k.state_limits.assign(std::size_t(k.states()), Limit{});
  const double reach = unclamped.states.col(0).cwiseAbs().maxCoeff();
  k.state_limits.front() = Limit{-0.8 * reach, 0.8 * reach};  // the first state only
  k.output_limits.assign(k.outputs.size(), Limit{});
  k.output_limits[0] = Limit{0.0, 9.2};  // amplifier 1 cannot exceed 9.2 V (operating 8.75 V)

  ClosedLoopStatistics statistics;
  const Experiment e = run_closed_loop(*s.truth, s.header, s.options, &statistics);
  const ControllerReplay replay = replay_controller(e);
  EXPECT_GT(statistics.saturated_samples, e.samples() / 100);
  EXPECT_LT(statistics.saturated_samples, e.samples() / 2);
  EXPECT_EQ(replay.clamped_samples, statistics.saturated_samples);
  // u = u_op + uf + r at every sample, the state clamps included.
  const Eigen::MatrixXd uf = e.u_deviation() - e.r_deviation();
  EXPECT_LT((uf - replay.output).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_GT((free.u - e.u).cwiseAbs().maxCoeff(), 1e-3);               // the clamps changed the run
  EXPECT_EQ(replay.states.col(0).cwiseAbs().maxCoeff(), 0.8 * reach);  // the state clamp held it
}

}  // namespace controller_limits_test
}  // namespace ambid::sim
