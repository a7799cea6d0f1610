#pragma once
// The maglev1coil_voltage family's scenario (families.hpp): the scenario options mapped onto
// the rig loop (maglev_loop.hpp). Options that have no meaning on the rig are refused by name.
#include "plant_sim/scenario.hpp"

namespace ambid::sim {

// Error for effects (the rig loop takes its truth's errors as rig settings), a controller other than the rig's
// pid, an excitation other than uniform or none, an input limit (the rig's is v_ref), and a
// touch of a stop (the message of maglev_loop.hpp; run_maglev_rig gives the record up to it).
Experiment simulate_maglev(const ScenarioOptions& options, ClosedLoopStatistics* statistics);
// Rig-like: 3.25 ms, 10 s, pid, uniform noise of +-0.5 V.
ScenarioOptions maglev_default_options();

}  // namespace ambid::sim
