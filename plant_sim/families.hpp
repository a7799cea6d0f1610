#pragma once
// The plant families plant_sim knows, in one place (experiment-format.md, "Plant families"):
// each brings its parameter names and nominal values, its nonlinear simulator, its
// linearisation at the operating point of an experiment, its effect catalogue with the
// simulator that switches those effects on, and says which optional pieces it lacks.
// Everything that dispatches on a plant model name
// (`ambid sim`, the scenario builder, the audit's replay) looks the family up here; an unknown
// name is refused with the list of known ones.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/experiment.hpp"
#include "core/state_space.hpp"
#include "plant_sim/effects.hpp"
#include "plant_sim/plant.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::sim {

struct PlantFamily {
  std::string name;
  std::string summary;  // one line
  const std::vector<std::string>& (*parameter_names)() = nullptr;
  std::map<std::string, double> (*nominal_parameters)() = nullptr;
  // The nonlinear plant with these parameters (every name required; Error naming a missing or
  // bad one), held at the operating point of `header` where it names the plant's states.
  std::unique_ptr<Plant> (*make_plant)(const Experiment& header) = nullptr;
  // The linearisation (deviations, the plant's states and signals) at the operating point of
  // `header` with its nominal parameters; a *measured* point where the header says so.
  ContinuousSystem (*linearize)(const Experiment& header) = nullptr;
  // The scenario of the generic closed-loop runner (closed_loop.hpp); null for a family that
  // runs its rig's own loop.
  Scenario (*build_scenario)(const ScenarioOptions& options) = nullptr;
  // A closed-loop simulation of the scenario (scenario.hpp) with this family's loop.
  Experiment (*simulate)(const ScenarioOptions& options, ClosedLoopStatistics* statistics) = nullptr;
  // The options `ambid sim` starts from for this family (sample time, duration, excitation).
  ScenarioOptions (*default_options)() = nullptr;
  // The effects a real plant of the family shows and the nominal model leaves out (the
  // audit's candidates, effects.hpp); null for a family without a catalogue.
  const std::vector<EffectSpec>& (*effect_catalogue)() = nullptr;
  // The nonlinear plant of `header` (nominal parameters, operating point, sample time) with
  // `effects` of the catalogue switched on; null without a catalogue.
  std::unique_ptr<Plant> (*make_extended_plant)(const Experiment& header, const std::vector<Effect>& effects) = nullptr;
};

// Every family, amb1dof_voltage first, then maglev1coil_voltage and lamstf.
const std::vector<PlantFamily>& plant_families();
// "amb1dof_voltage, maglev1coil_voltage, lamstf".
std::string plant_family_names();
// The family called `name`. Error "WHO: unknown plant 'NAME' (known: ...)".
const PlantFamily& plant_family(const std::string& name, const std::string& who);
// Error "WHO: plant model 'NAME' has no PIECE yet" for a piece a family lacks.
[[noreturn]] void family_lacks(const PlantFamily& family, const std::string& piece, const std::string& who);

}  // namespace ambid::sim
