#include "stack_support.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
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

std::string http_get(int port, const std::string& path) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(std::uint16_t(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::string response;
  if (connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0) {
    const std::string request = "GET " + path + " HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n";
    if (write(fd, request.data(), request.size()) == ssize_t(request.size())) {
      std::array<char, 4096> buffer{};
      for (ssize_t n; (n = read(fd, buffer.data(), buffer.size())) > 0;) response.append(buffer.data(), std::size_t(n));
    }
  }
  close(fd);
  const auto body = response.find("\r\n\r\n");
  return body == std::string::npos ? std::string{} : response.substr(body + 4);
}

double metric(const std::string& text, const std::string& line) {
  const auto at = text.find(line + " ");
  return at == std::string::npos ? -1.0 : std::stod(text.substr(at + line.size() + 1));
}

std::string sim_recording_file(const std::filesystem::path& dir, const SimRecording& recording) {
  return (dir / (recording.controller + ".json")).string();
}

CommandResult record_sim(const std::filesystem::path& dir, const SimRecording& recording) {
  std::ostringstream args;
  args << "sim --controller " << recording.controller << " --excitation prbs --amplitude 1.0"
       << " --position-noise " << recording.position_noise << " --current-noise " << recording.current_noise
       << " --duration " << recording.duration << " --seed " << recording.seed << " --out "
       << (dir / recording.controller).string();
  return run_ambid(args.str());
}

Stack::Stack(const std::string& name, int domain, const std::map<std::string, std::string>& vendors)
    : dir_(fs::path(AMBID_BINARY_DIR) / "test-output" / name), domain_(domain), vendors_(vendors) {
  fs::remove_all(dir_);
  fs::create_directories(dir_);
  // The bearing with 1 nm / 1 uA sensor noise and the closed-loop method: these tests are about
  // the plumbing, and closed-loop identifies this bearing in 0.25 s windows at 10x real time
  // (pem, the default, needs 30-50 iterations on such nearly noise-free windows; the stack's
  // deploy/config bearing has realistic noise and uses pem).
  // A swap to the rig emulator (nominal bearing, lqr) reads it with the board's description.
  const fs::path rig_description = fs::path(AMBID_SOURCE_DIR) / "deploy" / "config" / "rig-description.json";
  const fs::path config = fs::path(AMBID_SOURCE_DIR) / "tests" / "integration" / "scenarios";
  std::ofstream(dir_ / "plant.json") << R"({"source": "sim", "target": ")" << (config / "quiet-bearing.json").string()
                                     << R"(", "rig_description": ")" << rig_description.string()
                                     << R"(", "batch_samples": 500, "speed": 10})";
  std::ofstream(dir_ / "identifier.json") << R"({"window": 0.25, "settle": 0.25, "method": "closed-loop"})";
  std::ofstream(dir_ / "diagnostics.json")
      << R"({"store": ")" << store().string()
      << R"(", "learning_windows": 40, "persist_windows": 20, "stale_timeout": 1.0, "silence": 2.0})";
}

Stack::~Stack() {
  for (const auto& [daemon, pid] : pids_) ::kill(pid, SIGTERM);
  for (const auto& [daemon, pid] : pids_) waitpid(pid, nullptr, 0);
}

void Stack::start(const std::string& daemon, const std::vector<std::string>& extra_args) {
  const std::string vendor = vendors_.count(daemon) ? vendors_.at(daemon) : "cyclone";
  const std::string config = (dir_ / (daemon + ".json")).string();
  const std::string domain = std::to_string(domain_);
  std::vector<std::string> args{"daemon", daemon, "--dds", vendor, "--domain", domain, "--config", config};
  args.insert(args.end(), extra_args.begin(), extra_args.end());
  start_process(daemon, args);
}

void Stack::start_process(const std::string& daemon, const std::vector<std::string>& ambid_args) {
  std::vector<std::string> args{AMBID_BINARY};
  args.insert(args.end(), ambid_args.begin(), ambid_args.end());
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

void Stack::pause(const std::string& daemon) { ::kill(pids_.at(daemon), SIGSTOP); }

void Stack::resume(const std::string& daemon) { ::kill(pids_.at(daemon), SIGCONT); }

bool Stack::running(const std::string& daemon) {
  const auto it = pids_.find(daemon);
  if (it == pids_.end()) return false;
  int status = 0;
  if (waitpid(it->second, &status, WNOHANG) == 0) return true;
  std::ofstream(dir_ / (daemon + ".log"), std::ios::app)
      << "[test harness] process ended: "
      << (WIFEXITED(status) ? "exit " + std::to_string(WEXITSTATUS(status))
                            : "signal " + std::to_string(WTERMSIG(status)))
      << "\n";
  pids_.erase(it);
  return false;
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
