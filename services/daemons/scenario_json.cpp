#include "services/daemons/scenario_json.hpp"

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "services/daemons/config_json.hpp"

namespace ambid::daemons {

sim::ScenarioOptions scenario_from_json(const nlohmann::json& j) {
  if (!j.is_object()) throw Error("scenario: expected a JSON object, got " + std::string(j.type_name()));
  reject_unknown_keys(
      j, "scenario",
      {"name", "plant", "true_parameters", "controller", "excitation", "amplitude", "f_min", "f_max", "duration",
       "sample_time", "position_noise", "current_noise", "force_noise", "input_limit", "seed"});
  sim::ScenarioOptions o;
  o.name = config_value(j, "name", o.name);
  o.plant = config_value(j, "plant", o.plant);
  o.controller = config_value(j, "controller", o.controller);
  o.excitation = config_value(j, "excitation", o.excitation);
  o.amplitude = config_value(j, "amplitude", o.amplitude);
  o.f_min = config_value(j, "f_min", o.f_min);
  o.f_max = config_value(j, "f_max", o.f_max);
  o.duration = config_value(j, "duration", o.duration);
  o.sample_time = config_value(j, "sample_time", o.sample_time);
  o.position_noise = config_value(j, "position_noise", o.position_noise);
  o.current_noise = config_value(j, "current_noise", o.current_noise);
  o.force_noise = config_value(j, "force_noise", o.force_noise);
  o.input_limit = config_value(j, "input_limit", o.input_limit);
  o.seed = config_value(j, "seed", o.seed);
  const nlohmann::json parameters = config_value(j, "true_parameters", nlohmann::json::object());
  if (!parameters.is_object()) throw Error("scenario key 'true_parameters': expected an object of NAME: VALUE");
  for (const auto& [name, value] : parameters.items()) {
    if (!value.is_number())
      throw Error("scenario true_parameters." + name + ": expected a number, got " + value.dump());
    o.true_parameters[name] = value.get<double>();
  }
  sim::build_scenario(o);  // refuses unknown plants, parameters and bad values now, not mid-run
  return o;
}

sim::ScenarioOptions read_scenario_file(const std::string& path) {
  try {
    return scenario_from_json(load_config(path));
  } catch (const Error& e) {
    const std::string what = e.what();
    throw Error(what.rfind("config " + path, 0) == 0 ? what : "scenario " + path + ": " + what);
  }
}

}  // namespace ambid::daemons
