#pragma once
// The effect catalogue of `amb1dof_voltage` (experiment-format.md, effect vocabulary): the
// physical effects a real bearing shows and the nominal model leaves out, each with its
// parameters (SI units), the parameter values that make it vanish (its defaults), a typical
// magnitude, and whether it belongs to one coil/amplifier (`channel` 1 or 2). Equations and
// the signature of each effect in measured data: plant_sim/EFFECTS.md.
#include <map>
#include <string>
#include <vector>

namespace ambid::sim {

struct EffectParameterSpec {
  std::string name;
  std::string unit;
  double neutral = 0.0;                  // default: the value at which the effect vanishes (or a shape default)
  double scale = 1.0;                    // a typical moderate magnitude (fit scaling, test ranges)
  double lower = -1e300, upper = 1e300;  // physically admissible range (inclusive)
  bool switches = false;                 // the effect vanishes exactly when every switching parameter is neutral
  std::string meaning;
};

// A parameter that switches its effect on (neutral 0), and a shape parameter (neutral = typical
// = `value`), for building catalogues.
EffectParameterSpec switching_parameter(std::string name, std::string unit, double scale, double lower, double upper,
                                        std::string meaning);
EffectParameterSpec shape_parameter(std::string name, std::string unit, double value, double lower, double upper,
                                    std::string meaning);

struct EffectSpec {
  std::string name;
  bool has_channel = false;  // belongs to coil/amplifier 1 or 2 (parameter `channel`)
  std::vector<EffectParameterSpec> parameters;
  std::string summary;
};

// The twelve effects of amb1dof_voltage in vocabulary order. Other families bring their own
// catalogue (plant_sim/families.hpp); the functions that take a `catalogue` work on any.
const std::vector<EffectSpec>& effect_catalogue();
std::vector<std::string> effect_names();
// Error listing the valid names for an unknown one.
const EffectSpec& effect_spec(const std::string& name);
const EffectSpec& effect_spec(const std::vector<EffectSpec>& catalogue, const std::string& name);

// One effect with all its parameter values; channel is 1 or 2 for channel effects, else 0.
struct Effect {
  std::string name;
  int channel = 0;
  std::map<std::string, double> parameters;

  double at(const std::string& parameter) const;  // Error for an unknown parameter
  // True when the effect changes nothing (every switching parameter of `spec`, or of its
  // amb1dof_voltage entry, at its neutral value).
  bool neutral(const EffectSpec& spec) const;
  bool neutral() const;
};

// The effect with its defaults, overridden by `values` (parameter names of the effect, plus
// `channel` for channel effects, default 1). Error naming an unknown parameter (listing the
// valid ones), a value outside its range, or a channel other than 1 or 2.
Effect make_effect(const std::string& name, const std::map<std::string, double>& values = {});
Effect make_effect(const std::vector<EffectSpec>& catalogue, const std::string& name,
                   const std::map<std::string, double>& values = {});

}  // namespace ambid::sim
