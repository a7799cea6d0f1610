#pragma once
// The operator's subcommands that talk to the running service over the bus.
#include <CLI/CLI.hpp>

namespace ambid::cli {

void add_alerts_command(CLI::App& app);
void add_source_command(CLI::App& app);
void add_status_command(CLI::App& app);
void add_record_command(CLI::App& app);

}  // namespace ambid::cli
