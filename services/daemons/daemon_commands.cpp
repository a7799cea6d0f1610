// `ambid daemon plant|identifier|diagnostics|frf`: the daemons as subcommands of the one `ambid`
// binary (services/daemons/README.md says why).
#include <memory>
#include <string>

#include "identifier/methods.hpp"
#include "services/cli/commands.hpp"
#include "services/daemons/daemon_options.hpp"
#include "services/daemons/diagnostics_daemon.hpp"
#include "services/daemons/frf_daemon.hpp"
#include "services/daemons/identifier_daemon.hpp"
#include "services/daemons/identify_window.hpp"
#include "services/daemons/plant_daemon.hpp"

namespace ambid::cli {
namespace {

CLI::App* add_daemon(CLI::App& daemon, const char* name, const char* what, int (*run)(const daemons::DaemonOptions&)) {
  auto options = std::make_shared<daemons::DaemonOptions>();
  CLI::App* command = daemon.add_subcommand(name, what);
  daemons::add_daemon_options(*command, *options);
  command->callback([options, run] {
    if (const int code = run(*options); code != 0) throw CLI::RuntimeError(code);
  });
  return command;
}

}  // namespace

void add_daemon_commands(CLI::App& app) {
  CLI::App* daemon = app.add_subcommand("daemon", "run one daemon of the distributed service (DDS)");
  daemon->require_subcommand(1);
  add_daemon(*daemon, "plant", "publish plant samples from a source (sim | replay | rig); swap it on command",
             daemons::run_plant_daemon);
  add_daemon(*daemon, "identifier", "identify windows of plant samples -> identified models",
             daemons::run_identifier_daemon)
      ->footer("config key \"method\" (default " + std::string(daemons::kDefaultDaemonMethod) + "):\n" +
               ident::method_table());
  add_daemon(*daemon, "diagnostics", "identified models -> trend store -> alerts (STALE when silent)",
             daemons::run_diagnostics_daemon);
  add_daemon(*daemon, "frf", "excitation experiment through the plant -> frequency response, ISO zone",
             daemons::run_frf_daemon);
}

}  // namespace ambid::cli
