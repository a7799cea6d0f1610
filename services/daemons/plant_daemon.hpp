#pragma once
// `ambid daemon plant`: publishes the samples of its plant source in batches, paced at `speed`
// times real time, swaps the source on a PlantSourceCommand and announces every source
// (PlantSourceState, transient-local), checks ExcitationCommands against its limits.
//
// Config (JSON, every key optional):
//   {"source": "sim" | "replay", "target": FILE (scenario or experiment),
//    "batch_samples": 500, "speed": 10.0,
//    "max_amplitude": 0.5 (V), "max_frequency": 2000 (Hz)}
#include "services/daemons/daemon_options.hpp"

namespace ambid::daemons {

int run_plant_daemon(const DaemonOptions& options);

}  // namespace ambid::daemons
