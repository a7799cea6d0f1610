#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "audit_independent_cases.hpp"

namespace ambid::diag::testing {

test_support::EffectRecordOptions realistic_record(const std::string& controller, std::uint64_t seed) {
  test_support::EffectRecordOptions o;
  o.controller = controller;
  o.seed = seed;
  o.amplitude = 1.5;
  o.duration = 1.0;
  o.position_noise = 1e-7;
  o.current_noise = 1e-3;
  return o;
}

std::vector<std::string> independent_effect_names() {
  std::vector<std::string> names = sim::effect_names();
  if (std::find(names.begin(), names.end(), "force_factor") == names.end()) names.push_back("force_factor");
  return names;
}

sim::Effect effect_at(const std::string& name, double multiple, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  const double sign = uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0;
  const int channel = uniform(0.0, 1.0) < 0.5 ? 1 : 2;
  const sim::EffectSpec& spec = sim::effect_spec(name);
  std::map<std::string, double> v;
  if (spec.has_channel) v["channel"] = channel;
  if (name == "flexible_mode") {
    v["f"] = std::exp(uniform(std::log(300.0), std::log(1500.0)));
    v["zeta"] = uniform(0.01, 0.02);
  }
  if (name == "harmonic_disturbance") v["f"] = uniform(20.0, 400.0);
  const double phase = uniform(0.0, 2.0 * std::numbers::pi);
  for (const auto& p : spec.parameters) {
    if (!p.switches) continue;
    // Signs where both are physical; a harmonic's amplitude split by its phase.
    double value = (p.lower < 0.0 ? sign : 1.0) * multiple * p.scale;
    if (p.name == "Fc") value = multiple * p.scale * std::cos(phase);
    if (p.name == "Fs") value = multiple * p.scale * std::sin(phase);
    v[p.name] = std::clamp(value, p.lower, p.upper);
  }
  return sim::make_effect(name, v);
}

double relative_size(const sim::Effect& effect) {
  if (effect.name == "harmonic_disturbance") return std::hypot(effect.at("Fc"), effect.at("Fs")) / 0.5;
  for (const auto& p : sim::effect_spec(effect.name).parameters)
    if (p.switches) return std::abs(effect.at(p.name)) / p.scale;
  return 0.0;
}

std::vector<std::string> accepted_causes(const std::string& name) {
  static const std::vector<std::vector<std::string>> groups = {{"eddy_current", "sensor_delay"},
                                                               {"coil_resistance", "amplifier_gain"},
                                                               {"rotor_mass", "magnetic_saturation", "air_gap"}};
  for (const auto& group : groups)
    if (std::find(group.begin(), group.end(), name) != group.end()) return group;
  return {name};
}

}  // namespace ambid::diag::testing
