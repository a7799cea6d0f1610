// `ambid alerts [--follow]`: the current alerts of the service (transient-local, so a new
// subscriber gets them), and with --follow every new one until interrupted. --until LEVEL:PARAM
// ends with exit 0 at the first alert of that level about that parameter (scripts, tests);
// --timeout ends with exit 3 when it has not come.
#include <deque>
#include <iomanip>
#include <iostream>
#include <memory>
#include <set>
#include <string>

#include "core/error.hpp"
#include "services/cli/operator_commands.hpp"
#include "services/convert/alert.hpp"
#include "services/daemons/daemon_options.hpp"
#include "services/daemons/stop_signal.hpp"

namespace ambid::cli {
namespace {

struct AlertsArguments {
  daemons::BusOptions bus;
  bool follow = false;
  double wait = 2.0;
  double timeout = 0.0;
  std::string until;
  bool all_plants = false;
};

void print(const bus::Alert& a) {
  std::cout << std::fixed << std::setprecision(3) << "t=" << a.time << " s  " << std::left << std::setw(5)
            << convert::level_name(a.level) << "  " << a.plant_id << "  " << a.parameter << "  " << a.fault;
  if (a.channel != 0) std::cout << " (channel " << a.channel << ")";
  std::cout << std::defaultfloat << std::setprecision(6) << "  value " << a.value;
  if (a.baseline != 0.0) std::cout << " baseline " << a.baseline;
  std::cout << "  " << a.message << std::endl;
}

// The alerts already printed. A reconnecting or restarted diagnostics daemon sends its current
// alerts again (transient-local history): each is printed once. The oldest are forgotten beyond
// kRemembered, far more alerts than a follow session sees.
class PrintedAlerts {
 public:
  // True the first time `a` is seen.
  bool first(const bus::Alert& a) {
    std::string key = a.plant_id + '\n' + a.parameter + '\n' + a.fault + '\n' + std::to_string(a.channel) + '\n' +
                      std::to_string(static_cast<int>(a.level)) + '\n' + std::to_string(a.time);
    if (!keys_.insert(key).second) return false;
    order_.push_back(std::move(key));
    if (order_.size() > kRemembered) {
      keys_.erase(order_.front());
      order_.pop_front();
    }
    return true;
  }

 private:
  static constexpr std::size_t kRemembered = 100000;
  std::set<std::string> keys_;
  std::deque<std::string> order_;
};

void run(const AlertsArguments& args) {
  std::string until_level, until_parameter;
  if (!args.until.empty()) {
    const auto colon = args.until.find(':');
    if (colon == std::string::npos) throw Error("--until: expected LEVEL:PARAMETER, e.g. ERROR:R1, got " + args.until);
    until_level = args.until.substr(0, colon);
    until_parameter = args.until.substr(colon + 1);
  }
  daemons::install_stop_handlers();
  auto bus = args.bus.connect();
  auto alerts = bus->reader<bus::Alert>();
  const bool follow = args.follow || !args.until.empty();
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  PrintedAlerts printed;
  while (!daemons::stop_requested()) {
    if (!follow && elapsed() > args.wait) return;
    if (args.timeout > 0 && elapsed() > args.timeout) {
      std::cout << "ambid alerts: no " << args.until << " alert within " << args.timeout << " s" << std::endl;
      throw CLI::RuntimeError(3);
    }
    bus->wait(std::chrono::milliseconds(100));
    for (const bus::Alert& a : alerts->take()) {
      if (!args.all_plants && a.plant_id != args.bus.plant_id) continue;
      if (!printed.first(a)) continue;
      print(a);
      if (!until_level.empty() && convert::level_name(a.level) == until_level && a.parameter == until_parameter) return;
    }
  }
}

}  // namespace

void add_alerts_command(CLI::App& app) {
  auto args = std::make_shared<AlertsArguments>();
  CLI::App* c = app.add_subcommand("alerts", "show the alerts of the running service");
  daemons::add_bus_options(*c, args->bus);
  c->add_flag("--follow", args->follow, "keep printing new alerts until interrupted");
  c->add_option("--wait", args->wait, "without --follow: how long to collect alerts (s)")->capture_default_str();
  c->add_option("--until", args->until, "LEVEL:PARAMETER: exit 0 at the first such alert (implies --follow)");
  c->add_option("--timeout", args->timeout, "give up after this many seconds (exit 3); 0: never")
      ->capture_default_str();
  c->add_flag("--all-plants", args->all_plants, "alerts of every plant, not only --plant-id");
  c->callback([args] { run(*args); });
}

}  // namespace ambid::cli
