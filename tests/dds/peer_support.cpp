#include "dds/peer.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <stdexcept>
#include <thread>
#include <vector>

extern char** environ;

namespace ambid::bus::test {
namespace peer_support {

constexpr int ready_fd_in_peer = 3;
constexpr const char* spec_variable = "AMBID_DDS_PEER";

}  // namespace peer_support
using namespace peer_support;

PeerProcess::PeerProcess(const std::string& test_name, const std::string& spec) {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe2 failed");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], ready_fd_in_peer);  // dup2 clears CLOEXEC

  std::string filter = "--gtest_filter=" + test_name;
  std::string exe = "/proc/self/exe";
  std::vector<char*> argv{exe.data(), filter.data(), nullptr};
  std::string variable = std::string(spec_variable) + "=" + spec;
  std::vector<char*> env;
  for (char** e = environ; *e != nullptr; ++e) env.push_back(*e);
  env.push_back(variable.data());
  env.push_back(nullptr);

  const int rc = posix_spawn(&pid_, exe.c_str(), &actions, nullptr, argv.data(), env.data());
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  ready_fd_ = fds[0];
  if (rc != 0) throw std::runtime_error("posix_spawn failed");
}

PeerProcess::~PeerProcess() {
  kill();
  close(ready_fd_);
}

bool PeerProcess::wait_ready(std::chrono::milliseconds limit) {
  pollfd p{ready_fd_, POLLIN, 0};
  if (poll(&p, 1, static_cast<int>(limit.count())) != 1) return false;
  char byte = 0;
  return read(ready_fd_, &byte, 1) == 1;
}

std::optional<int> PeerProcess::wait_exit(std::chrono::milliseconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (pid_ > 0) {
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    if (std::chrono::steady_clock::now() > end) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return std::nullopt;
}

void PeerProcess::kill() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGKILL);
  waitpid(pid_, nullptr, 0);
  pid_ = -1;
}

std::optional<std::string> peer_spec() {
  const char* spec = std::getenv(spec_variable);
  if (spec == nullptr) return std::nullopt;
  return std::string(spec);
}

void signal_ready() {
  const char byte = 'r';
  if (write(ready_fd_in_peer, &byte, 1) != 1) throw std::runtime_error("cannot signal ready");
}

}  // namespace ambid::bus::test
