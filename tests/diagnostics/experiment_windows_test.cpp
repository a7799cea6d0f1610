// split_experiment against the recorded loop: the controller state each window starts from,
// run through the window's own signals, reproduces what the controller commanded.
#include "diagnostics/experiment_windows.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "identifier/identify_window.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::diag {
namespace experiment_windows_test {

Experiment simulated() {
  sim::ScenarioOptions o;
  o.duration = 0.1;
  o.seed = 3;
  return sim::simulate_scenario(o);
}

// uf = C xc + D v over a window, from its controller.initial_state.
Eigen::MatrixXd replay(const Experiment& w) {
  const StateSpaceController& k = *w.controller;
  Eigen::VectorXd xc = k.initial_state;
  Eigen::MatrixXd uf(w.samples(), k.C.rows());
  for (Eigen::Index s = 0; s < w.samples(); ++s) {
    Eigen::VectorXd v(k.inputs.size());
    for (std::size_t j = 0; j < k.inputs.size(); ++j)
      v(Eigen::Index(j)) = w.signal(k.inputs[j])(s) - w.operating_value(k.inputs[j]);
    uf.row(s) = (k.C * xc + k.D * v).transpose();
    xc = k.A * xc + k.B * v;
  }
  return uf;
}

TEST(SplitExperiment, EachWindowStartsFromTheRecordedControllerState) {
  const Experiment e = simulated();
  const std::vector<Experiment> windows = split_experiment(e, 300);
  ASSERT_EQ(windows.size(), 3u);  // 1000 samples: 3 windows of 300, 100 dropped
  for (std::size_t i = 0; i < windows.size(); ++i) {
    SCOPED_TRACE(i);
    const Experiment& w = windows[i];
    EXPECT_EQ(w.samples(), 300);
    EXPECT_DOUBLE_EQ(w.t(0), e.t(Eigen::Index(300 * i)));
    w.validate();
    // u = uf + r (deviations): the recorded command minus the excitation.
    const Eigen::MatrixXd uf = replay(w);
    const Eigen::MatrixXd expected = w.u_deviation() - w.r_deviation();
    EXPECT_LT((uf - expected).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + expected.cwiseAbs().maxCoeff()));
  }
  // Without the state the replay of a later window is wrong: the check above can fail.
  Experiment wrong = windows[2];
  wrong.controller->initial_state.setZero();
  EXPECT_GT((replay(wrong) - (wrong.u_deviation() - wrong.r_deviation())).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(SplitExperiment, LaterWindowIdentifiesTheNominalPlant) {
  sim::ScenarioOptions o;
  o.duration = 0.5;
  o.amplitude = 1.0;
  const std::vector<Experiment> windows = split_experiment(sim::simulate_scenario(o), 2500);
  const Model id = ident::identify_window(windows.back(), ident::window_identify_options("deadbeat")).model;
  EXPECT_NEAR(id.physical.at("R1"), 17.5, 0.02 * 17.5);
  EXPECT_NEAR(id.physical.at("kw2"), 1.0, 0.01);
}

TEST(SplitExperiment, BadWindowsAreRefused) {
  const Experiment e = simulated();
  EXPECT_THROW(split_experiment(e, 1), Error);
  EXPECT_THROW(split_experiment(e, e.samples() + 1), Error);
  Experiment no_controller = e;
  no_controller.controller.reset();
  EXPECT_THROW(split_experiment(no_controller, 100), Error);
}

}  // namespace experiment_windows_test
}  // namespace ambid::diag
