#include "services/cli/commands.hpp"

namespace ambid::cli {

void add_sim_command(CLI::App& app) {
  app.add_subcommand("sim", "simulate a plant in closed loop and write an experiment");
}

}  // namespace ambid::cli
