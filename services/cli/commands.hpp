#pragma once
// Registration of the `ambid` subcommands; each is defined in its own file.
#include <CLI/CLI.hpp>

namespace ambid::cli {

void add_sim_command(CLI::App& app);
void add_diagnose_command(CLI::App& app);
void add_identify_command(CLI::App& app);
void add_frf_command(CLI::App& app);
void add_audit_command(CLI::App& app);
void add_import_command(CLI::App& app);
void add_daemon_commands(CLI::App& app);       // services/daemons/daemon_commands.cpp
void add_operator_commands(CLI::App& app);     // alerts, source, status, record
void add_rig_emulator_command(CLI::App& app);  // rig_emulator_command.cpp

}  // namespace ambid::cli
