#pragma once
// Running the `ambid` binary from integration tests.
#include <filesystem>
#include <string>

namespace ambid::cli_test {

struct CommandResult {
  int status;
  std::string output;  // stdout and stderr
};

// Runs `ambid ARGS` (a shell command line) and collects its output and exit status.
CommandResult run_ambid(const std::string& args);

// An empty directory under the build tree for one test's files.
std::filesystem::path fresh_dir(const std::string& name);

}  // namespace ambid::cli_test
