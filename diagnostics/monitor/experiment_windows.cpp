#include "diagnostics/experiment_windows.hpp"

#include <string>

#include "core/error.hpp"

namespace ambid::diag {

std::vector<Experiment> split_experiment(const Experiment& experiment, Eigen::Index window_samples) {
  const Eigen::Index n = experiment.samples();
  if (window_samples < 2 || window_samples > n)
    throw Error("experiment '" + experiment.name + "': window of " + std::to_string(window_samples) +
                " samples, the record has " + std::to_string(n) + " (need 2 <= window <= record)");
  if (!experiment.controller)
    throw Error("experiment '" + experiment.name + "' has no controller: its state at each window is needed");
  const StateSpaceController& k = *experiment.controller;
  Eigen::MatrixXd v(n, static_cast<Eigen::Index>(k.inputs.size()));
  for (std::size_t j = 0; j < k.inputs.size(); ++j)
    v.col(static_cast<Eigen::Index>(j)) =
        experiment.signal(k.inputs[j]).array() - experiment.operating_value(k.inputs[j]);
  Eigen::VectorXd state = k.initial_state.size() ? k.initial_state : Eigen::VectorXd::Zero(k.states());

  std::vector<Experiment> windows;
  for (Eigen::Index first = 0; first + window_samples <= n; first += window_samples) {
    Experiment w = experiment;
    w.controller->initial_state = state;
    w.t = experiment.t.segment(first, window_samples);
    w.y = experiment.y.middleRows(first, window_samples);
    w.u = experiment.u.middleRows(first, window_samples);
    if (experiment.r.size()) w.r = experiment.r.middleRows(first, window_samples);
    windows.push_back(std::move(w));
    for (Eigen::Index s = first; s < first + window_samples; ++s) state = k.A * state + k.B * v.row(s).transpose();
  }
  return windows;
}

}  // namespace ambid::diag
