// `ambid source set sim FILE | replay FILE | rig ADDR`: swaps the source of the running plant
// daemon and prints its answer (PlantSourceState for this command: accepted or why refused).
#include <chrono>
#include <iostream>
#include <memory>

#include "core/error.hpp"
#include "services/cli/operator_commands.hpp"
#include "services/convert/source_kind.hpp"
#include "services/daemons/daemon_options.hpp"

namespace ambid::cli {
namespace {

struct SourceArguments {
  daemons::BusOptions bus;
  std::string kind, target;
  double timeout = 10.0;
};

void run(const SourceArguments& args) {
  bus::PlantSourceCommand command;
  command.plant_id = args.bus.plant_id;
  command.kind = convert::parse_source_kind(args.kind);
  command.target = args.target;
  command.seq = std::uint64_t(std::chrono::system_clock::now().time_since_epoch().count());
  auto bus = args.bus.connect();
  auto states = bus->reader<bus::PlantSourceState>();
  auto commands = bus->writer<bus::PlantSourceCommand>();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(args.timeout);
  while (commands->matched() == 0) {  // commands are volatile: write only once the plant listens
    if (std::chrono::steady_clock::now() > deadline)
      throw Error("no plant daemon on domain " + std::to_string(args.bus.domain));
    bus->wait(std::chrono::milliseconds(50));
  }
  // Matched here does not mean the plant's reader matched this writer yet (a volatile command
  // would be lost): send again every second until the plant answers; it acts on a seq once.
  auto next_send = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() < deadline) {
    if (std::chrono::steady_clock::now() >= next_send) {
      commands->write(command);
      next_send += std::chrono::seconds(1);
    }
    bus->wait(std::chrono::milliseconds(100));
    for (const bus::PlantSourceState& s : states->take()) {
      if (s.plant_id != command.plant_id || s.command_seq != command.seq) continue;
      if (!s.command_accepted) throw Error("plant " + s.plant_id + " refused the source: " + s.message);
      std::cout << "plant " << s.plant_id << ": source " << args.kind << " " << s.target << " (" << s.message
                << ", plant time " << s.time << " s)" << std::endl;
      return;
    }
  }
  throw Error("plant " + command.plant_id + " did not answer within " + std::to_string(args.timeout) + " s");
}

}  // namespace

void add_source_command(CLI::App& app) {
  auto args = std::make_shared<SourceArguments>();
  CLI::App* source = app.add_subcommand("source", "the plant daemon's source of samples");
  source->require_subcommand(1);
  CLI::App* set = source->add_subcommand("set", "swap the source: sim SCENARIO.json | replay EXPERIMENT | rig ADDR");
  daemons::add_bus_options(*set, args->bus);
  set->add_option("kind", args->kind, "sim | replay | rig")->required();
  set->add_option("target", args->target, "scenario file, experiment file or rig address")->required();
  set->add_option("--timeout", args->timeout, "seconds to wait for the plant's answer")->capture_default_str();
  set->callback([args] { run(*args); });
}

}  // namespace ambid::cli
