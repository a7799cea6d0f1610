#include "plant_sim/scenario.hpp"

#include "plant_sim/families.hpp"

namespace ambid::sim {

Scenario build_scenario(const ScenarioOptions& options) {
  const PlantFamily& family = plant_family(options.plant, "simulation");
  if (!family.build_scenario)
    family_lacks(family, "scenario for the generic closed-loop runner (it runs its rig's own loop)", "simulation");
  return family.build_scenario(options);
}

Experiment simulate_scenario(const ScenarioOptions& options, ClosedLoopStatistics* statistics) {
  return plant_family(options.plant, "simulation").simulate(options, statistics);
}

}  // namespace ambid::sim
