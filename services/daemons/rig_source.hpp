#pragma once
// The plant source `rig HOST:PORT`: the gateway to a controller board over the UDP rig
// protocol (services/rig/RIG_PROTOCOL.md). It subscribes with HELLO (refused when the rig does
// not answer within 3 s), keeps the subscription with KEEPALIVEs, turns sample batches into
// SourceRows (a new record on a sequence gap, a record change or a sample index jump), forwards
// excitation commands and waits for their ACK/NACK, and reports the rig silent after
// `silence` seconds without a frame. Malformed datagrams are counted
// (ambid_rig_frames_rejected_total{reason}) and logged, never fatal.
#include <memory>
#include <string>

#include "core/experiment.hpp"
#include "services/daemons/plant_source.hpp"

namespace ambid::daemons {

// The rows of a rig read with the plant description the plant config names (rig_description,
// a sidecar: the board's controller, nominal parameters, operating point). Throws Error when
// the board's model, signal names or sample time differ from the description's.
Experiment with_description(Experiment rows, Experiment description);

// Throws Error when the address is malformed, not numeric, off loopback without
// allow_remote, or the rig does not answer HELLO.
std::unique_ptr<PlantSource> make_rig_source(const std::string& address, const SourceContext& context);

}  // namespace ambid::daemons
