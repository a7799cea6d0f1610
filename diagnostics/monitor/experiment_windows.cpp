#include "diagnostics/experiment_windows.hpp"

#include <string>

#include "core/error.hpp"
#include "diagnostics/identified_estimates.hpp"
#include "diagnostics/plant_families.hpp"
#include "identifier/identify_experiment.hpp"

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

ExperimentWindows identify_experiment_windows(const Experiment& experiment, Eigen::Index window_samples,
                                              const std::string& method, double start, const std::string& plant_id,
                                              Source source, const WindowCallbacks& callbacks) {
  const MonitoredFamily& family = monitored_family(experiment.plant.model, "diagnose");
  ident::IdentifyOptions options = ident::window_identify_options(method);
  ident::require_method_inputs(experiment, method);
  const std::vector<Experiment> parts = split_experiment(experiment, window_samples);
  ExperimentWindows out;
  out.time_to = start;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (callbacks.progress) callbacks.progress(i, parts.size());
    out.time_to = start + double(i + 1) * double(window_samples) * experiment.sample_time;
    options.skip_samples = i == 0 && method != "deadbeat" ? family.settling_samples : 0;
    try {
      out.windows.push_back(estimate_window(ident::identify_window(parts[i], options), out.time_to, plant_id, source));
    } catch (const Error& err) {
      out.skipped.push_back({i + 1, out.time_to, ident::window_failure(err)});
      if (callbacks.skipped) callbacks.skipped(out.skipped.back(), parts.size());
    }
  }
  return out;
}

}  // namespace ambid::diag
