#pragma once
// Cuts one recorded experiment into consecutive windows, each a complete experiment of its
// own that can be identified on its own: the diagnostics watch parameters window by window,
// and the scatter of the windows of the baseline experiments is what the baseline learns.
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"

namespace ambid::diag {

// Windows of `window_samples` consecutive samples from the first; a remainder shorter than a
// window is dropped. Each window keeps the sidecar of the experiment, and its
// controller.initial_state is the state of the recorded controller at the window's first
// sample (the controller run on the recorded signals from the experiment's initial state), so
// the integrator states an identification reconstructs are the recorded ones.
// Throws Error when window_samples < 2 or exceeds the record, when the experiment has no
// controller (it is needed to know its state), or when a controller input is not a signal.
std::vector<Experiment> split_experiment(const Experiment& experiment, Eigen::Index window_samples);

}  // namespace ambid::diag
