#include "services/cli/operator_commands.hpp"

#include "services/cli/commands.hpp"

namespace ambid::cli {

void add_operator_commands(CLI::App& app) {
  add_alerts_command(app);
  add_source_command(app);
  add_status_command(app);
  add_record_command(app);
}

}  // namespace ambid::cli
