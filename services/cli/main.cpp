// ambid: the operator's command line. Each subcommand lives in its own file and registers
// itself here; errors from the libraries become a one-line message and exit code 1.
#include <iostream>

#include <CLI/CLI.hpp>

#include "core/error.hpp"
#include "services/cli/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"ambid: closed-loop identification and diagnostics of magnetic bearings"};
  app.require_subcommand(1);
  ambid::cli::add_sim_command(app);
  ambid::cli::add_diagnose_command(app);
  ambid::cli::add_identify_command(app);
  ambid::cli::add_frf_command(app);
  ambid::cli::add_audit_command(app);
  ambid::cli::add_import_command(app);
  ambid::cli::add_daemon_commands(app);
  ambid::cli::add_operator_commands(app);
  ambid::cli::add_rig_emulator_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const ambid::Error& e) {
    std::cerr << "ambid: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "ambid: internal error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
