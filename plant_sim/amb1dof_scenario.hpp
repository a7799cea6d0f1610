#pragma once
// The amb1dof_voltage family's scenario (families.hpp): the true bearing, a controller designed
// on the nominal model (lqr or pid), an excitation and noise, run by the generic closed-loop
// runner. Callers go through build_scenario / simulate_scenario (scenario.hpp).
#include "plant_sim/scenario.hpp"

namespace ambid::sim {

Scenario build_amb1dof_scenario(const ScenarioOptions& options);
Experiment simulate_amb1dof(const ScenarioOptions& options, ClosedLoopStatistics* statistics);

}  // namespace ambid::sim
