#include "plant_sim/maglev_scenario.hpp"

#include <cmath>

#include "core/error.hpp"
#include "plant_sim/maglev_loop.hpp"

namespace ambid::sim {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw Error("simulation of maglev1coil_voltage: " + message);
}

}  // namespace

Experiment simulate_maglev(const ScenarioOptions& o, ClosedLoopStatistics* statistics) {
  require(o.effects.empty(),
          "the rig loop of 'maglev1coil_voltage' takes its truth's errors as --rig settings "
          "(sensor_gain, sensor_offset, sensor_exponent, sensor_coupling, sensor_delay, dac_step) and "
          "true parameters (--set), not as effects (its catalogue is the audit's candidate models)");
  require(o.controller == "pid", "the rig runs its board's PID (controller 'pid'), got '" + o.controller + "'");
  require(o.excitation == "uniform" || o.excitation == "none",
          "excitation must be uniform (white noise added to u, not logged) or none, got '" + o.excitation + "'");
  require(o.noise_level == 0.0, "a relative noise level is lamstf's; the rig's noise is its own");
  require(o.input_limit == 0.0, "the rig clamps its command to [0, v_ref]: set --rig v_ref=VALUE, not an input limit");
  require(std::isfinite(o.duration) && o.duration >= 2 * o.sample_time,
          "duration must be at least two samples, got " + std::to_string(o.duration));
  const MaglevParameters nominal = MaglevParameters::nominal();
  MaglevParameters truth = nominal;
  for (const auto& [name, value] : o.true_parameters) truth.set(name, value);
  MaglevRig rig;
  for (const auto& [name, value] : o.rig) rig.set(name, value);
  MaglevRunOptions run;
  run.name = o.name;
  run.sample_time = o.sample_time;
  run.samples = Eigen::Index(std::llround(o.duration / o.sample_time));
  if (!o.levels.empty()) run.levels = o.levels;
  run.step_period = o.step_period;
  run.noise_amplitude = o.excitation == "none" ? 0.0 : o.amplitude;
  run.position_noise = o.position_noise;
  run.current_noise = o.current_noise;
  run.force_noise = o.force_noise;
  run.seed = o.seed;
  MaglevRun result = run_maglev_rig(truth, nominal, rig, run);
  if (!result.ended.empty()) throw Error(result.ended);
  if (statistics) statistics->saturated_samples = result.clamped_samples;
  return std::move(result.experiment);
}

ScenarioOptions maglev_default_options() {
  ScenarioOptions o;
  o.plant = "maglev1coil_voltage";
  o.name = "maglev simulation";
  o.sample_time = 3.25e-3;
  o.duration = 10.0;
  o.controller = "pid";
  o.excitation = "uniform";
  o.amplitude = 0.5;
  return o;
}

}  // namespace ambid::sim
