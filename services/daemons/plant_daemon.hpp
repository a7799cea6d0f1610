#pragma once
// `ambid daemon plant`: publishes the samples of its plant source in batches, paced at `speed`
// times real time, swaps the source on a PlantSourceCommand and announces every source
// (PlantSourceState, transient-local), checks ExcitationCommands against its limits, and
// publishes the plant description of the source's samples (PlantDescription, transient-local)
// whenever it changes; every batch names it.
//
// Config (JSON, every key optional):
//   {"source": "sim" | "replay" | "rig", "target": FILE (scenario or experiment) or A.B.C.D:PORT,
//    "batch_samples": 500, "speed": 10.0 (sim and replay; a rig paces itself),
//    "max_amplitude": 0.5 (V), "max_frequency": 2000 (Hz),
//    "rig_silence": 1.0 (s), "rig_reply_timeout": 0.5 (s), "rig_allow_remote": false,
//    "rig_description": FILE (the rig board's plant description, a sidecar JSON; required for a
//    rig, services/rig/RIG_PROTOCOL.md)}
#include "services/daemons/daemon_options.hpp"

namespace ambid::daemons {

int run_plant_daemon(const DaemonOptions& options);

}  // namespace ambid::daemons
