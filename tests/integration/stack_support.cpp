#include "stack_support.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

extern char** environ;

namespace ambid::testing {

namespace fs = std::filesystem;

CommandResult run_ambid(const std::string& args) {
  const std::string command = std::string(AMBID_BINARY) + " " + args + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), int(buffer.size()), pipe)) output += buffer.data();
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

Stack::Stack(const std::string& name, int domain, const std::map<std::string, std::string>& vendors)
    : dir_(fs::path(AMBID_BINARY_DIR) / "test-output" / name), domain_(domain), vendors_(vendors) {
  fs::remove_all(dir_);
  fs::create_directories(dir_);
  const fs::path config = fs::path(AMBID_SOURCE_DIR) / "deploy" / "config";
  std::ofstream(dir_ / "plant.json") << R"({"source": "sim", "target": ")"
                                     << (config / "nominal-bearing.json").string()
                                     << R"(", "batch_samples": 500, "speed": 10})";
  std::ofstream(dir_ / "identifier.json") << R"({"window": 0.25, "settle": 0.25})";
  std::ofstream(dir_ / "diagnostics.json")
      << R"({"store": ")" << store().string()
      << R"(", "learning_windows": 10, "persist_windows": 3, "stale_timeout": 1.0, "silence": 2.0})";
}

Stack::~Stack() {
  for (const auto& [daemon, pid] : pids_) ::kill(pid, SIGTERM);
  for (const auto& [daemon, pid] : pids_) waitpid(pid, nullptr, 0);
}

void Stack::start(const std::string& daemon) {
  const std::string vendor = vendors_.count(daemon) ? vendors_.at(daemon) : "cyclone";
  const std::string config = (dir_ / (daemon + ".json")).string();
  const std::string domain = std::to_string(domain_);
  std::vector<std::string> args{AMBID_BINARY, "daemon", daemon, "--dds", vendor, "--domain", domain, "--config", config};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  const std::string log_file = (dir_ / (daemon + ".log")).string();
  posix_spawn_file_actions_addopen(&actions, 1, log_file.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, AMBID_BINARY, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + daemon);
  pids_[daemon] = pid;
}

void Stack::kill(const std::string& daemon) {
  const pid_t pid = pids_.at(daemon);
  ::kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  pids_.erase(daemon);
}

CommandResult Stack::ambid(const std::string& args) const {
  return run_ambid(args + " --domain " + std::to_string(domain_));
}

std::string Stack::log(const std::string& daemon) const {
  std::ifstream in(dir_ / (daemon + ".log"));
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace ambid::testing
