#pragma once
// Runs the `ambid` binary as a user would, for the integration tests.
#include <filesystem>
#include <string>

namespace ambid::testing {

struct CommandResult {
  int status;          // exit code; -1 when killed by a signal
  std::string output;  // stdout and stderr
};

// `ambid ARGS` through the shell.
CommandResult run_ambid(const std::string& args);

// An empty directory build/test-output/NAME.
std::filesystem::path fresh_dir(const std::string& name);

}  // namespace ambid::testing
