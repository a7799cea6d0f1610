#pragma once
// Cuts one recorded experiment into consecutive windows, each a complete experiment of its
// own that can be identified on its own: the diagnostics watch parameters window by window,
// and the scatter of the windows of the baseline experiments is what the baseline learns.
// identify_experiment_windows is what `ambid diagnose` does with each experiment it is given.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "diagnostics/estimate.hpp"
#include "identifier/identify_window.hpp"

namespace ambid::diag {

// Windows of `window_samples` consecutive samples from the first; a remainder shorter than a
// window is dropped. Each window keeps the sidecar of the experiment, and its
// controller.initial_state is the state of the recorded controller at the window's first
// sample (the controller run on the recorded signals from the experiment's initial state), so
// the integrator states an identification reconstructs are the recorded ones.
// Throws Error when window_samples < 2 or exceeds the record, when the experiment has no
// controller (it is needed to know its state), or when a controller input is not a signal.
std::vector<Experiment> split_experiment(const Experiment& experiment, Eigen::Index window_samples);

struct SkippedWindow {
  std::size_t window = 0;  // 1-based within its experiment
  double time = 0.0;       // the window's end
  ident::WindowFailure failure;
};

struct ExperimentWindows {
  std::vector<EstimateWindow> windows;
  std::vector<SkippedWindow> skipped;
  double time_to = 0.0;  // end of the last window, identified or skipped
};

struct WindowCallbacks {
  std::function<void(std::size_t done, std::size_t total)> progress;             // before each window
  std::function<void(const SkippedWindow& skipped, std::size_t total)> skipped;  // after a skipped one
};

// Every window of `experiment` (split_experiment, `window_samples` each) identified by
// `method` (ident::identify_window, the family's settling_samples dropped from the first:
// plant_families.hpp; deadbeat drops none), stamped with the
// window's end on a clock where the experiment starts at `start`. A window that cannot be
// identified is skipped with its reason (ident::window_failure), never the end of the run.
// Throws Error when the method cannot use the experiment at all (ident::require_method_inputs),
// when diagnostics does not monitor its plant family, and what split_experiment throws.
ExperimentWindows identify_experiment_windows(const Experiment& experiment, Eigen::Index window_samples,
                                              const std::string& method, double start, const std::string& plant_id,
                                              Source source, const WindowCallbacks& callbacks = {});

}  // namespace ambid::diag
