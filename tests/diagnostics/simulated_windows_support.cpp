#include "diagnostics/simulated_windows.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "diagnostics/experiment_windows.hpp"
#include "diagnostics/identified_estimates.hpp"
#include "diagnostics/synthetic_estimates.hpp"
#include "identifier/identify_experiment.hpp"
#include "plant_sim/amb1dof_parameters.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::diag::testing {

EstimateWindow SimulatedBearing::estimate(std::size_t n) const {
  sim::ScenarioOptions o;
  o.duration = settle + window;
  o.amplitude = amplitude;
  o.position_noise = position_noise;
  o.current_noise = current_noise;
  o.seed = seed + n;
  const auto nominal = sim::Amb1dofParameters::nominal().to_map();
  for (const auto& [name, relative] : change(n)) o.true_parameters[name] = nominal.at(name) * (1.0 + relative);
  const Experiment run = sim::simulate_scenario(o);
  const auto samples = static_cast<Eigen::Index>(std::lround(window / o.sample_time));
  const Experiment last = split_experiment(run, samples).back();
  ident::IdentifyOptions options;
  options.method = "closed-loop";  // the window starts after `settle`, controller state carried: no skip
  options.validation_fraction = 0.0;
  options.jackknife_segments = 0;  // as `ambid diagnose` and the identifier daemon: scatter-based sigmas
  const Model m = ident::identify_experiment(last, options);
  return estimate_window(m.plant_model, m.physical, m.uncertainty, static_cast<double>(n + 1) * window, plant_id,
                         Source::sim);
}

SimulatedSequence run_simulated_sequence(const SimulatedBearing& bearing, std::size_t windows,
                                         const std::string& store_name, const EngineConfig& config) {
  TrendStore store(fresh_store_path(store_name));
  DiagnosticsEngine engine(store, config);
  SimulatedSequence r;
  for (std::size_t n = 0; n < windows; ++n) {
    r.windows.push_back(bearing.estimate(n));
    for (Alert& a : engine.process(r.windows.back())) r.alerts.push_back(std::move(a));
  }
  return r;
}

bool raised(const Alert& a) { return a.level == Level::warn || a.level == Level::error; }

std::string describe_alerts(const std::vector<Alert>& alerts) {
  std::string text;
  for (const Alert& a : alerts) text += "\n  " + to_json(a).dump();
  return text;
}

}  // namespace ambid::diag::testing
