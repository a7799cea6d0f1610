#pragma once
// Fuzz targets of the file and datagram readers (mutator.hpp): experiment CSV and sidecar,
// model JSON, scenario JSON (the plant daemon's sim source and `ambid rig-emulator --fault`),
// rig frames. Each mutates a real input `iterations` times.
#include "fuzz/mutator.hpp"

namespace ambid::fuzz {

FuzzCount fuzz_experiment_csv(int iterations);
FuzzCount fuzz_experiment_sidecar(int iterations);
FuzzCount fuzz_model_json(int iterations);
FuzzCount fuzz_scenario_json(int iterations);
FuzzCount fuzz_rig_frame(int iterations);

}  // namespace ambid::fuzz
