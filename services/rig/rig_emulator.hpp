#pragma once
// A controller board in software, for tests and demos: the closed loop of plant_sim (the
// controller "on the board") runs record after record at `speed` times real time and speaks
// the rig protocol (RIG_PROTOCOL.md) on a UDP port: it answers HELLO with its status, streams
// sample batches to the gateway that said HELLO for as long as it keeps the lease (a HELLO from
// any other sender is refused until then), applies excitation commands it can run (ACK) and
// refuses the others with the reason (NACK, cut to the frame's text field). The
// board's clock starts at the first HELLO and runs on (samples nobody subscribes to are lost).
#include <functional>
#include <optional>
#include <string>

#include "plant_sim/scenario.hpp"
#include "services/rig/udp_endpoint.hpp"

namespace ambid::rig {

struct EmulatorOptions {
  Endpoint listen;
  sim::ScenarioOptions scenario;              // the board's plant and loop; one record = its duration
  std::optional<sim::ScenarioOptions> fault;  // the truth of the records starting at or after fault_at
  double fault_at = 0.0;                      // s of board time
  double speed = 1.0;                         // board time per wall time
  double max_amplitude = 1.0;                 // V, the amplifiers' limit: larger excitations are NACKed
  double lease = 2.0;                         // s without HELLO or KEEPALIVE: streaming stops
};

// Throws Error naming a bad option (scenario, speed, limits) before it opens the socket.
void validate(const EmulatorOptions& options);

// Serves until `running()` turns false; `log` gets one line per event. Throws Error when the
// port cannot be bound.
void run_emulator(const EmulatorOptions& options, const std::function<bool()>& running,
                  const std::function<void(const std::string&)>& log);

}  // namespace ambid::rig
