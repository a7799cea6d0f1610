// `ambid rig-emulator --listen 127.0.0.1:PORT [--scenario FILE] [--fault FILE --fault-at T]`:
// a controller board in software for the plant daemon's rig source (services/rig/rig_emulator.hpp).
// A subcommand, not a separate program, for the reason the daemons are (services/daemons/README.md):
// one binary for the tests and the install, and it reads the same scenario files.
#include <iostream>
#include <memory>

#include "core/error.hpp"
#include "services/cli/commands.hpp"
#include "services/daemons/scenario_json.hpp"
#include "services/daemons/stop_signal.hpp"
#include "services/rig/rig_emulator.hpp"

namespace ambid::cli {
namespace {

struct RigEmulatorArguments {
  std::string listen, scenario, fault;
  double fault_at = 0.0, speed = 1.0, max_amplitude = 1.0, lease = 2.0;
};

void run(const RigEmulatorArguments& args) {
  rig::EmulatorOptions o;
  o.listen = rig::parse_endpoint(args.listen);
  if (!o.listen.loopback())
    throw Error("rig emulator: --listen " + args.listen + " is not a loopback address (127.x.x.x)");
  if (!args.scenario.empty()) o.scenario = daemons::read_scenario_file(args.scenario);
  if (!args.fault.empty()) o.fault = daemons::read_scenario_file(args.fault);
  o.fault_at = args.fault_at;
  o.speed = args.speed;
  o.max_amplitude = args.max_amplitude;
  o.lease = args.lease;
  daemons::install_stop_handlers();
  rig::run_emulator(
      o, [] { return !daemons::stop_requested(); },
      [](const std::string& line) { std::cerr << "rig-emulator: " << line << std::endl; });
}

}  // namespace

void add_rig_emulator_command(CLI::App& app) {
  auto args = std::make_shared<RigEmulatorArguments>();
  CLI::App* c = app.add_subcommand("rig-emulator",
                                   "a controller board in software: plant_sim closed loop over the UDP rig protocol");
  c->add_option("--listen", args->listen, "UDP address to serve, 127.0.0.1:PORT")->required();
  c->add_option("--scenario", args->scenario, "scenario JSON of the board's plant and loop (default: nominal)");
  c->add_option("--fault", args->fault, "scenario JSON of the truth from --fault-at on");
  c->add_option("--fault-at", args->fault_at,
                "board time (s, from the first HELLO) from which records run the --fault scenario")
      ->capture_default_str();
  c->add_option("--speed", args->speed, "board time per wall time")->capture_default_str();
  c->add_option("--max-amplitude", args->max_amplitude, "amplifier limit (V): larger excitations are NACKed")
      ->capture_default_str();
  c->add_option("--lease", args->lease, "seconds without HELLO/KEEPALIVE before streaming stops")
      ->capture_default_str();
  c->callback([args] { run(*args); });
}

}  // namespace ambid::cli
