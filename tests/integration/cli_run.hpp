#pragma once
// Running the `ambid` binary from integration tests.
#include <filesystem>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace ambid::cli_test {

struct CommandResult {
  int status;          // exit code, -1 when the program did not exit normally
  std::string output;  // stdout and stderr
};

// Runs a shell command line and collects its output (stdout and stderr) and exit status.
CommandResult run_command(const std::string& command);

// Runs `ambid ARGS` (a shell command line) and collects its output and exit status.
CommandResult run_ambid(const std::string& args);

// An empty directory under the build tree for one test's files.
std::filesystem::path fresh_dir(const std::string& name);

// The JSON document in `path` (a file the command under test wrote).
nlohmann::json read_json(const std::filesystem::path& path);

// True when libxml2's parser accepts the file as well-formed XML (xmllint from libxml2-utils).
bool well_formed_xml(const std::filesystem::path& file);

}  // namespace ambid::cli_test
