#include "audit_cases.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include "plant_sim/scenario.hpp"

namespace ambid::diag::testing {

sim::Effect draw_effect(const std::string& name, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  const double sign = uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0;
  std::map<std::string, double> v;
  if (sim::effect_spec(name).has_channel) v["channel"] = uniform(0.0, 1.0) < 0.5 ? 1 : 2;
  if (name == "coil_resistance") v["dR"] = sign * uniform(2.0, 5.0);
  if (name == "amplifier_gain") v["dkw"] = sign * uniform(0.1, 0.3);
  if (name == "amplifier_bandwidth") v["tau"] = uniform(1e-4, 3e-4);
  if (name == "eddy_current") v["tau"] = uniform(5e-5, 2e-4);
  if (name == "sensor_delay") v["delay"] = uniform(4e-5, 1e-4);
  if (name == "sensor_gain") v["dgain"] = sign * uniform(0.05, 0.15);
  if (name == "flexible_mode") {
    // The resonance gain coupling / (2 zeta) decides what the sensor sees: from 2.5 (clearly
    // above the noise) to 5 (beyond that the recorded controller goes unstable by spillover).
    v["zeta"] = uniform(0.01, 0.02);
    v["coupling"] = 2 * v["zeta"] * uniform(2.5, 5.0);
    v["f"] = uniform(250.0, 450.0);
  }
  if (name == "magnetic_saturation") v["beta"] = uniform(0.2, 0.5);
  if (name == "air_gap") v["dx0"] = sign * uniform(2e-5, 5e-5);
  if (name == "rotor_mass") v["dm"] = sign * uniform(0.1, 0.3);
  if (name == "force_factor") v["dratio"] = sign * uniform(0.05, 0.15);
  if (name == "harmonic_disturbance") {
    const double amplitude = uniform(0.1, 0.5), phase = uniform(0.0, 2 * std::numbers::pi);
    v["f"] = uniform(20.0, 400.0);
    v["Fc"] = amplitude * std::cos(phase);
    v["Fs"] = amplitude * std::sin(phase);
  }
  return sim::make_effect(name, v);
}

Experiment simulate_hidden(const sim::Effect& effect, double duration, std::uint64_t seed) {
  sim::ScenarioOptions o;
  o.duration = duration;
  o.seed = seed;
  o.amplitude = 0.3;
  o.position_noise = 2e-9;
  o.current_noise = 2e-5;
  if (!effect.name.empty()) o.effects = {effect};
  return sim::simulate_scenario(o);
}

double effect_size(const sim::Effect& effect) {
  if (effect.name == "harmonic_disturbance") return std::hypot(effect.at("Fc"), effect.at("Fs"));
  for (const auto& p : sim::effect_spec(effect.name).parameters)
    if (p.switches) return effect.at(p.name);
  return 0.0;
}

}  // namespace ambid::diag::testing
