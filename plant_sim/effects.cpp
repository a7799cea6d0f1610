#include "plant_sim/effects.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace ambid::sim {
namespace {

constexpr auto switching = switching_parameter;
constexpr auto shape = shape_parameter;

std::vector<EffectSpec> build_catalogue() {
  return {
      {"coil_resistance",
       true,
       {switching("dR", "ohm", 3.5, -15.0, 100.0, "true resistance of the coil minus its nominal Rj")},
       "the coil resistance differs from the nominal (a hot or damaged coil)"},
      {"amplifier_gain",
       true,
       {switching("dkw", "V/V", 0.2, -0.9, 10.0, "true amplifier gain minus its nominal kwj")},
       "the amplifier gain differs from the nominal"},
      {"amplifier_bandwidth",
       true,
       {switching("tau", "s", 2e-4, 0.0, 1e-2, "time constant of the amplifier's first-order lag")},
       "the amplifier output voltage lags its command (finite bandwidth)"},
      {"eddy_current",
       false,
       {switching("tau", "s", 2e-4, 0.0, 1e-2, "time constant of the force lag behind the coil currents")},
       "eddy currents in the iron delay the magnetic force behind the coil currents"},
      {"sensor_delay",
       false,
       {switching("delay", "s", 5e-5, 0.0, 1e-2, "dead time of the position measurement")},
       "the position measurement arrives late (conversion, filtering, bus)"},
      {"sensor_gain",
       false,
       {switching("dgain", "1", 0.1, -0.9, 10.0, "relative error of the position sensor gain")},
       "the position sensor is mis-calibrated"},
      {"flexible_mode",
       false,
       {switching("coupling", "1", 0.1, -10.0, 10.0,
                  "modal displacement seen by the sensor per unit rigid-body acceleration times w^2"),
        shape("f", "Hz", 800.0, 50.0, 1e5, "natural frequency of the mode"),
        shape("zeta", "1", 0.01, 1e-4, 0.05,
              "damping ratio of the mode (a lightly damped bending mode; a broader resonance is no mode)")},
       "a bending mode of the rotor, excited by the bearing force, is seen by the position sensor"},
      {"magnetic_saturation",
       false,
       {switching("beta", "1", 0.3, 0.0, 100.0,
                  "saturation coefficient: force flux falls by 1/sqrt(1 + beta) at the operating flux")},
       "the iron saturates: the force grows slower than the square of the flux"},
      {"air_gap",
       false,
       {switching("dx0", "m", 3.5e-5, -3e-4, 1e-3, "true air gap minus the nominal x0")},
       "the air gap differs from the nominal (assembly, thermal growth, wear of the touchdown path)"},
      {"rotor_mass",
       false,
       {switching("dm", "kg", 0.18, -1.7, 100.0, "true rotor mass minus the nominal m")},
       "the rotor mass differs from the nominal (an added part, a different rotor)"},
      {"harmonic_disturbance",
       false,
       {shape("f", "Hz", 50.0, 0.1, 5000.0, "frequency of the disturbance force"),
        switching("Fc", "N", 0.5, -1e4, 1e4, "cosine amplitude of the force"),
        switching("Fs", "N", 0.5, -1e4, 1e4, "sine amplitude of the force")},
       "a periodic force acts on the rotor (unbalance at a fixed speed, a mains-frequency field)"},
      {"force_factor",
       true,
       {switching("dratio", "1", 0.1, -0.9, 1.0,
                  "true force factor K_j of the coil over its nominal, minus 1 (ratio - 1)")},
       "the force and back-EMF factor of one coil alone differs from the nominal (shorted turns, a cracked "
       "lamination)"},
  };
}

std::string join_names(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

EffectParameterSpec switching_parameter(std::string name, std::string unit, double scale, double lower, double upper,
                                        std::string meaning) {
  return {std::move(name), std::move(unit), 0.0, scale, lower, upper, true, std::move(meaning)};
}

EffectParameterSpec shape_parameter(std::string name, std::string unit, double value, double lower, double upper,
                                    std::string meaning) {
  return {std::move(name), std::move(unit), value, value, lower, upper, false, std::move(meaning)};
}

const std::vector<EffectSpec>& effect_catalogue() {
  static const std::vector<EffectSpec> catalogue = build_catalogue();
  return catalogue;
}

std::vector<std::string> effect_names() {
  std::vector<std::string> names;
  for (const auto& e : effect_catalogue()) names.push_back(e.name);
  return names;
}

const EffectSpec& effect_spec(const std::string& name) { return effect_spec(effect_catalogue(), name); }

const EffectSpec& effect_spec(const std::vector<EffectSpec>& catalogue, const std::string& name) {
  std::vector<std::string> names;
  for (const auto& e : catalogue) {
    if (e.name == name) return e;
    names.push_back(e.name);
  }
  throw Error("unknown effect '" + name + "' (known: " + join_names(names) + ")");
}

double Effect::at(const std::string& parameter) const {
  const auto it = parameters.find(parameter);
  if (it == parameters.end()) throw Error("effect " + name + " has no parameter '" + parameter + "'");
  return it->second;
}

bool Effect::neutral() const { return neutral(effect_spec(name)); }

bool Effect::neutral(const EffectSpec& spec) const {
  return std::all_of(spec.parameters.begin(), spec.parameters.end(),
                     [&](const EffectParameterSpec& p) { return !p.switches || at(p.name) == p.neutral; });
}

Effect make_effect(const std::string& name, const std::map<std::string, double>& values) {
  return make_effect(effect_catalogue(), name, values);
}

Effect make_effect(const std::vector<EffectSpec>& catalogue, const std::string& name,
                   const std::map<std::string, double>& values) {
  const EffectSpec& spec = effect_spec(catalogue, name);
  Effect e{name, spec.has_channel ? 1 : 0, {}};
  for (const auto& p : spec.parameters) e.parameters[p.name] = p.neutral;
  for (const auto& [key, value] : values) {
    if (spec.has_channel && key == "channel") {
      if (value != 1.0 && value != 2.0)
        throw Error("effect " + name + ": channel must be 1 or 2, got " + std::to_string(value));
      e.channel = int(value);
      continue;
    }
    const auto p = std::find_if(spec.parameters.begin(), spec.parameters.end(),
                                [&](const EffectParameterSpec& s) { return s.name == key; });
    if (p == spec.parameters.end()) {
      std::vector<std::string> valid;
      for (const auto& s : spec.parameters) valid.push_back(s.name);
      if (spec.has_channel) valid.push_back("channel");
      throw Error("effect " + name + " has no parameter '" + key + "' (valid: " + join_names(valid) + ")");
    }
    if (!std::isfinite(value) || value < p->lower || value > p->upper) {
      std::ostringstream msg;
      msg << "effect " << name << ": " << key << " = " << value << " " << p->unit << " is outside [" << p->lower << ", "
          << p->upper << "]";
      throw Error(msg.str());
    }
    e.parameters[key] = value;
  }
  return e;
}

}  // namespace ambid::sim
