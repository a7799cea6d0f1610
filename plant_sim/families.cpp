#include "plant_sim/families.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "plant_sim/amb1dof_extended.hpp"
#include "plant_sim/amb1dof_scenario.hpp"
#include "plant_sim/amb1dof_voltage.hpp"
#include "plant_sim/lamstf.hpp"
#include "plant_sim/lamstf_scenario.hpp"
#include "plant_sim/linear_plant.hpp"
#include "plant_sim/maglev1coil_voltage.hpp"
#include "plant_sim/maglev_effects.hpp"
#include "plant_sim/maglev_extended.hpp"
#include "plant_sim/maglev_linearize.hpp"
#include "plant_sim/maglev_scenario.hpp"

namespace ambid::sim {
namespace {

std::unique_ptr<Plant> amb1dof_plant(const Experiment& header) {
  return std::make_unique<Amb1dofVoltage>(Amb1dofParameters::from_map(header.plant.parameters));
}

ContinuousSystem amb1dof_linearize(const Experiment& header) {
  return Amb1dofVoltage(Amb1dofParameters::from_map(header.plant.parameters)).linearize();
}

ScenarioOptions amb1dof_default_options() { return ScenarioOptions{}; }

std::unique_ptr<Plant> amb1dof_extended_plant(const Experiment& header, const std::vector<Effect>& effects) {
  return std::make_unique<Amb1dofExtended>(Amb1dofParameters::from_map(header.plant.parameters), effects,
                                           header.sample_time);
}

bool measured_point(const Experiment& header) {
  const nlohmann::json& extra = header.extra.json();
  return extra.is_object() && extra.value("operating_point_source", std::string()) == "measured";
}

MaglevOperatingPoint maglev_point(const Experiment& header) {
  for (const char* name : {"x", "i", "u"})
    if (!header.operating_point.count(name))
      throw Error(std::string("maglev1coil_voltage: operating_point.") + name + " is missing");
  return {header.operating_point.at("x"), header.operating_point.at("i"), header.operating_point.at("u")};
}

std::unique_ptr<Plant> maglev_plant(const Experiment& header) {
  return std::make_unique<Maglev1coilVoltage>(MaglevParameters::from_map(header.plant.parameters),
                                              maglev_point(header).x);
}

// The step at which the rig logged the command (extra.rig.settings.log_u), 0 when not given.
double maglev_command_resolution(const Experiment& header) {
  const nlohmann::json& extra = header.extra.json();
  if (!extra.is_object() || !extra.contains("rig") || !extra["rig"].is_object()) return 0.0;
  const nlohmann::json settings = extra["rig"].value("settings", nlohmann::json::object());
  const auto it = settings.is_object() ? settings.find("log_u") : settings.end();
  return it != settings.end() && it->is_number() && it->get<double>() > 0.0 ? it->get<double>() : 0.0;
}

std::unique_ptr<Plant> maglev_extended_plant(const Experiment& header, const std::vector<Effect>& effects) {
  return std::make_unique<MaglevExtended>(MaglevParameters::from_map(header.plant.parameters), maglev_point(header),
                                          measured_point(header), effects, header.sample_time,
                                          maglev_command_resolution(header));
}

ContinuousSystem maglev_linearize_header(const Experiment& header) {
  const MaglevParameters p = MaglevParameters::from_map(header.plant.parameters);
  const MaglevOperatingPoint op = maglev_point(header);
  return (measured_point(header) ? maglev_linearize_measured(p, op) : maglev_linearize(p, op.x)).system;
}

const std::vector<std::string>& no_parameters() {
  static const std::vector<std::string> none;
  return none;
}

std::unique_ptr<Plant> lamstf_plant(const Experiment&) { return std::make_unique<LinearPlant>(lamstf()); }

ContinuousSystem lamstf_linearize(const Experiment&) { return lamstf().system; }

}  // namespace

const std::vector<PlantFamily>& plant_families() {
  static const std::vector<PlantFamily> families = {
      {"amb1dof_voltage", "one bearing axis, two opposing voltage-driven coils (seed 000)", Amb1dofParameters::names,
       [] { return Amb1dofParameters::nominal().to_map(); }, amb1dof_plant, amb1dof_linearize, build_amb1dof_scenario,
       simulate_amb1dof, amb1dof_default_options, effect_catalogue, amb1dof_extended_plant},
      {"maglev1coil_voltage", "one electromagnet levitating a body against gravity (maglev-rig.md)",
       MaglevParameters::names, [] { return MaglevParameters::nominal().to_map(); }, maglev_plant,
       maglev_linearize_header, nullptr, simulate_maglev, maglev_default_options, maglev_effect_catalogue,
       maglev_extended_plant},
      {"lamstf", "LAMSTF 5-DOF magnetic suspension, seed 002's linear analytical model under its LQR", no_parameters,
       [] { return std::map<std::string, double>{}; }, lamstf_plant, lamstf_linearize, build_lamstf_scenario,
       simulate_lamstf, lamstf_default_options, nullptr, nullptr},
  };
  return families;
}

std::string plant_family_names() {
  std::string out;
  for (const PlantFamily& f : plant_families()) out += (out.empty() ? "" : ", ") + f.name;
  return out;
}

const PlantFamily& plant_family(const std::string& name, const std::string& who) {
  const auto& families = plant_families();
  const auto it = std::find_if(families.begin(), families.end(), [&](const auto& f) { return f.name == name; });
  if (it == families.end()) throw Error(who + ": unknown plant '" + name + "' (known: " + plant_family_names() + ")");
  return *it;
}

void family_lacks(const PlantFamily& family, const std::string& piece, const std::string& who) {
  throw Error(who + ": plant model '" + family.name + "' has no " + piece + " yet");
}

}  // namespace ambid::sim
