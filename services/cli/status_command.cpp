// `ambid status`: what the running service says about itself: each daemon's latest Health and
// the plant's current source and plant description (id, plant family, controller kind),
// collected for --wait seconds. A daemon that died leaves nothing on the bus (its
// transient-local Health goes with it), so the roles the operator expects are named (--expect)
// and each one without a live daemon is listed as LOST, exit 4.
#include <chrono>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "services/cli/operator_commands.hpp"
#include "services/convert/alert.hpp"
#include "services/convert/plant_description.hpp"
#include "services/convert/source_kind.hpp"
#include "services/daemons/daemon_options.hpp"

namespace ambid::cli {
namespace {

struct StatusArguments {
  daemons::BusOptions bus;
  double wait = 3.0;
  std::string expect = "plant,identifier,diagnostics";  // the local stack's roles
};

std::vector<std::string> comma_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) items.push_back(item);
  return items;
}

void run(const StatusArguments& args) {
  auto bus = args.bus.connect();
  auto health = bus->reader<bus::Health>();
  auto sources = bus->reader<bus::PlantSourceState>();
  std::map<std::string, bus::Health> nodes;
  std::map<std::string, bus::PlantSourceState> plants;
  auto responses = bus->reader<bus::FrequencyResponse>();
  std::map<std::string, bus::FrequencyResponse> frfs;
  auto descriptions = bus->reader<bus::PlantDescription>();
  std::map<std::string, bus::PlantDescription> described;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(args.wait);
  while (std::chrono::steady_clock::now() < end) {
    bus->wait(std::chrono::milliseconds(100));
    for (const auto& h : health->take()) nodes[h.node] = h;
    for (const auto& s : sources->take()) plants[s.plant_id] = s;
    for (const auto& r : responses->take()) frfs[r.plant_id] = r;
    for (const auto& d : descriptions->take()) described[d.plant_id] = d;
  }
  if (nodes.empty() && plants.empty()) {
    std::cout << "no daemon answered on domain " << args.bus.domain << " within " << args.wait << " s" << std::endl;
    throw CLI::RuntimeError(3);
  }
  for (const auto& [id, s] : plants)
    std::cout << "plant " << id << ": source " << convert::source_kind_name(s.kind) << " " << s.target
              << " since plant time " << s.time << " s"
              << (s.command_accepted ? (s.message.empty() ? "" : " (" + s.message + ")")
                                     : " (last command refused: " + s.message + ")")
              << "\n";
  for (const auto& [id, d] : described)
    std::cout << "plant " << id << ": description " << d.description_id << ", plant " << d.model << ", controller "
              << convert::controller_summary(d) << "\n";
  constexpr const char* zones = "-ABCD";
  for (const auto& [id, r] : frfs) {
    std::cout << "plant " << id << ": frequency response at plant time " << r.time << " s, " << r.frequencies.size()
              << " lines, ISO 14839-3 zone " << zones[int(r.zone)] << "\n";
    for (const auto& p : r.peaks)
      std::cout << "  sensitivity peak " << p.output << ": " << p.magnitude << " at " << p.frequency << " Hz, zone "
                << zones[int(p.zone)] << "\n";
  }
  std::set<std::string> roles;
  for (const auto& [node, h] : nodes) {
    roles.insert(h.role);
    std::cout << node << " (" << h.role << "): " << convert::level_name(h.level) << " " << h.message << ", received "
              << h.received << ", published " << h.published << ", rejected " << h.errors << ", up " << h.time
              << " s\n";
  }
  bool lost = false;
  for (const std::string& role : comma_list(args.expect))
    if (!roles.count(role)) {
      std::cout << role << " (expected): LOST, no daemon of this role answered within " << args.wait
                << " s (stopped, crashed or unreachable)\n";
      lost = true;
    }
  std::cout << std::flush;
  if (lost) throw CLI::RuntimeError(4);
}

}  // namespace

void add_status_command(CLI::App& app) {
  auto args = std::make_shared<StatusArguments>();
  CLI::App* c = app.add_subcommand("status", "health of the running daemons and the plant's source");
  daemons::add_bus_options(*c, args->bus);
  c->add_option("--wait", args->wait, "seconds to listen")->capture_default_str();
  c->add_option("--expect", args->expect,
                "comma-separated roles that should be running; each one missing is listed as LOST (exit 4); "
                "empty: none")
      ->capture_default_str();
  c->callback([args] { run(*args); });
}

}  // namespace ambid::cli
