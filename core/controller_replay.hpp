#pragma once
// The recorded controller run over an experiment's own samples: what it put out at every
// sample, and where one of its clamps (controller.output_limits, state_limits) acted. A sample
// where a clamp acted is not exogenous (experiment-format.md): fits and scores leave it out.
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"

namespace ambid {

struct ControllerReplay {
  // uf = C xc + D v per sample, deviations, one column per u signal (in u_names order; 0 for a
  // u signal the controller does not drive).
  Eigen::MatrixXd output;
  Eigen::MatrixXd states;     // xc[k] per sample (samples x controller states), as clamped
  std::vector<bool> clamped;  // per sample: an output or a state clamp acted
  Eigen::Index clamped_samples = 0;
};

// Runs e.controller on the deviations of the recorded y, u (and r, where the controller reads
// an r signal) from controller.initial_state. An output clamp acts at sample k when the
// recorded u of that output is at or beyond its limit; a state clamp acts at k when it changes
// the state update xc[k+1] computed at k (the replayed state is then the clamped one). Throws
// Error when the experiment has no controller, or the controller reads an r signal that the
// experiment does not record.
ControllerReplay replay_controller(const Experiment& e);

// The clamp mask alone: all false (and no replay) when the controller has no limits or there is
// no controller.
ControllerReplay clamped_samples(const Experiment& e);

}  // namespace ambid
