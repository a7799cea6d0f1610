// The identifier daemon's default estimator (ContinuousEstimator: rpem at the daemon's settings,
// published every 0.5 s as deploy/config/identifier.json cuts the windows) through a coil fault,
// on records it did not generate (tests/support/amb1dof_records.hpp: the NONLINEAR bearing, RK4
// at 16 steps per sample) at a real bearing's sensor noise (0.1 um on x, 1 mA on each current)
// and the stack's 1 V PRBS. Truth: the true plant linearised where its loop settles, before and
// after the fault.
// - A step of R1 +20 % in the middle of a record (the plant changes under the running loop,
//   which re-settles at lower bias currents by itself), on the LQR observer loop and the PID
//   loop: no published R1 reads below the baseline by 10 % or more (the diagnostics'
//   error_fraction, deploy/config/diagnostics.json: an ERROR of the wrong sign), and from 1.5 s
//   after the step on every published R1 is within 5 % of the new truth (~3 sigma of one
//   window). Measured (seed 3; R1 against the new truth, the windows held about a theta
//   unless "plain": published from the plain RPEM beside them, see continuous_estimator.hpp):
//   the window holding the step +63 % (lqr, plain) / +37 % (pid, plain), the next ones
//   -1.6..+5.5 % (lqr) / +0.8..+5.0 % (pid; the PID loop re-settles for ~2 s). Before the coil rows' offsets were tied
//   to the bias current and voltage (amb1dof_recursive_pem.hpp) R1 read -88 % to -94 % for 0.5-1 s after such a step.
// - The stack's swap (scripts/run.sh): the nominal record, then a record of the faulty bearing
//   from rest at the nominal operating point, its first 0.25 s dropped (the daemon's settle) and
//   a gap: the same two checks. Measured (seeds 5, 6; against the hot truth): the first window
//   after the swap -8.8 % (lqr) / -3.9 % (pid; plain: a gap), then -0.3..+2.3 % / +1.1..+1.5 %.
//   It read R1 -74 % in the running stack before theta was held for the predictor's warm-up
//   after a restart.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "identifier/identify_experiment.hpp"
#include "services/daemons/continuous_estimator.hpp"
#include "support/amb1dof_records.hpp"

namespace ambid::daemons {
namespace continuous_step_fault_test {

constexpr double kWindow = 0.5;      // s, deploy/config/identifier.json
constexpr double kTolerance = 0.05;  // of the truth
constexpr double kWrongSign = 0.10;  // below the baseline: the diagnostics' error_fraction
constexpr double kTrack = 1.5;       // s after the fault

test_support::Amb1dofRecordOptions stack_record(const std::string& controller, double duration, std::uint64_t seed) {
  test_support::Amb1dofRecordOptions o;
  o.controller = controller;
  o.amplitude = 1.0;
  o.clock_divider = test_support::prbs_clock_divider(controller);
  o.duration = duration;
  o.position_noise = 1e-7;
  o.current_noise = 1e-3;
  o.seed = seed;
  return o;
}

double physical(const bus::IdentifiedModel& m, const std::string& name) {
  for (const bus::Estimate& e : m.physical)
    if (e.name == name) return e.value;
  throw Error(name + " missing");
}

// R1 of the windows published after `fault` (s), checked against the baseline (the mean R1 of the
// windows in the 2 s before the fault) and the truth after it.
struct Published {
  std::vector<double> time, r1;
  std::uint64_t seq = 0;
};

// Feeds `e` from sample `from` to the estimator in daemon windows, its clock moved by `shift`,
// and keeps each published R1.
void publish_windows(ContinuousEstimator& estimator, const Experiment& e, Eigen::Index from, double shift,
                     Published& p) {
  const auto per_window = Eigen::Index(std::lround(kWindow / e.sample_time));
  for (Eigen::Index begin = from; begin + per_window <= e.samples(); begin += per_window) {
    Experiment w = ident::experiment_segment(e, begin, begin + per_window);
    w.t.array() += shift;
    const bus::IdentifiedModel m = estimator.identify(w, "p", p.seq++);
    p.time.push_back(m.time);
    p.r1.push_back(physical(m, "R1"));
  }
}

void expect_tracks(const Published& p, double fault, double truth, const std::string& what) {
  double baseline = 0.0;
  int before = 0;
  for (std::size_t k = 0; k < p.time.size(); ++k)
    if (p.time[k] <= fault && p.time[k] > fault - 2.0) {
      baseline += p.r1[k];
      ++before;
    }
  ASSERT_GT(before, 2) << what;
  baseline /= before;
  double lowest = 1e9, worst_tracked = 0.0;
  for (std::size_t k = 0; k < p.time.size(); ++k) {
    if (p.time[k] <= fault) continue;
    lowest = std::min(lowest, p.r1[k] / baseline - 1.0);
    if (p.time[k] >= fault + kTrack) worst_tracked = std::max(worst_tracked, std::abs(p.r1[k] / truth - 1.0));
    ::testing::Test::RecordProperty(what + "_R1_at_" + std::to_string(p.time[k] - fault), std::to_string(p.r1[k]));
  }
  ::testing::Test::RecordProperty(what + "_baseline", std::to_string(baseline));
  EXPECT_GT(lowest, -kWrongSign) << what << ": R1 read below the baseline after the fault";
  EXPECT_LT(worst_tracked, kTolerance) << what << ": R1 off the truth " << truth << " from " << kTrack << " s on";
}

class ContinuousStepFault : public ::testing::TestWithParam<std::string> {};

TEST_P(ContinuousStepFault, R1FollowsAStepInTheMiddleOfARecord) {
  test_support::Amb1dofRecordOptions o = stack_record(GetParam(), 8.0, 3);
  o.step_parameters["R1"] = 1.2 * sim::Amb1dofParameters::nominal().get("R1");
  o.step_time = 4.25;  // in the middle of a window
  const test_support::Amb1dofRecord record = test_support::simulate_amb1dof_record(o);
  const Experiment& e = record.experiment;
  ContinuousEstimator estimator;
  Published p;
  publish_windows(estimator, e, record.settled, 0.0, p);
  expect_tracks(p, e.t(record.stepped), record.true_parameters_after_step.get("R1"), GetParam());
}

TEST_P(ContinuousStepFault, R1FollowsTheStacksSwapToAHotCoil) {
  const test_support::Amb1dofRecord before = test_support::simulate_amb1dof_record(stack_record(GetParam(), 4.0, 5));
  test_support::Amb1dofRecordOptions o = stack_record(GetParam(), 4.0, 6);
  o.true_parameters["R1"] = 1.2 * sim::Amb1dofParameters::nominal().get("R1");
  o.settle = 0.0;  // from rest at the nominal operating point, as the plant daemon's next record
  const test_support::Amb1dofRecord after = test_support::simulate_amb1dof_record(o);
  const Experiment& a = before.experiment;
  const Experiment& b = after.experiment;
  ContinuousEstimator estimator;
  Published p;
  publish_windows(estimator, a, before.settled, 0.0, p);
  // The swap: the faulty record continues the clock; the daemon drops its first 0.25 s (settle).
  const double swap = a.t(a.samples() - 1) + a.sample_time;
  const auto settle = Eigen::Index(std::lround(0.25 / b.sample_time));
  publish_windows(estimator, b, settle, swap - b.t(0), p);
  expect_tracks(p, swap, after.true_parameters.get("R1"), GetParam() + "_swap");
}

INSTANTIATE_TEST_SUITE_P(Controllers, ContinuousStepFault, ::testing::Values("lqr", "pid"),
                         [](const auto& param_info) { return param_info.param; });

}  // namespace continuous_step_fault_test
}  // namespace ambid::daemons
