#pragma once
// The ambid service as real processes for integration tests: the three daemons of
// deploy/local-stack.sh, each a child process of the test on its own domain, with configs
// written into a fresh directory (short windows, fast learning).
#include <sys/types.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cli_run.hpp"

namespace ambid::testing {

using cli_test::CommandResult;
using cli_test::run_ambid;

// The body of http://127.0.0.1:PORT/PATH (empty when nothing answers).
std::string http_get(int port, const std::string& path);
// The number after `line` in the Prometheus exposition `text` (-1 when the line is missing).
double metric(const std::string& text, const std::string& line);

// What a test's `ambid sim` recording of the stack's bearing varies: the 1 V PRBS of
// deploy/config/nominal-bearing.json closed by a controller, at these noise levels.
struct SimRecording {
  std::string controller;
  double position_noise = 1e-7;  // m
  double current_noise = 1e-3;   // A
  double duration = 10.0;        // s
  int seed = 7;
};
// Writes DIR/CONTROLLER.json (+ .csv); the file is `sim_recording_file(dir, recording)`. The
// caller checks the command's status (this file is also linked without GoogleTest).
CommandResult record_sim(const std::filesystem::path& dir, const SimRecording& recording);
std::string sim_recording_file(const std::filesystem::path& dir, const SimRecording& recording);

class Stack {
 public:
  // vendors: "fastdds" or "cyclone" per daemon (plant, identifier, diagnostics).
  Stack(const std::string& name, int domain, const std::map<std::string, std::string>& vendors = {});
  ~Stack();  // SIGTERM to every daemon still running, then waits
  Stack(const Stack&) = delete;
  Stack& operator=(const Stack&) = delete;

  void start(const std::string& daemon, const std::vector<std::string>& extra_args = {});
  // `ambid ARGS` as a child process known as `name` (log, kill), e.g. the rig emulator.
  void start_process(const std::string& name, const std::vector<std::string>& ambid_args);
  void kill(const std::string& daemon);    // SIGKILL: no goodbye on the bus
  void pause(const std::string& daemon);   // SIGSTOP: alive but deaf, as a stalled process
  void resume(const std::string& daemon);  // SIGCONT
  // False when the daemon's process has ended (then forgotten, with its exit status logged).
  bool running(const std::string& daemon);
  // `ambid ARGS --domain D` against this stack.
  CommandResult ambid(const std::string& args) const;
  const std::filesystem::path& dir() const { return dir_; }
  std::filesystem::path store() const { return dir_ / "trend.sqlite"; }
  std::string log(const std::string& daemon) const;

 private:
  std::filesystem::path dir_;
  int domain_;
  std::map<std::string, std::string> vendors_;
  std::map<std::string, pid_t> pids_;
};

}  // namespace ambid::testing
