#pragma once
// Two-process tests: the test program starts itself again as a peer that runs one test only,
// told what to do by AMBID_DDS_PEER. The peer reports "ready" through fd 3.
#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>

namespace ambid::bus::test {

class PeerProcess {
 public:
  // Runs this program with --gtest_filter=test_name and AMBID_DDS_PEER=spec.
  PeerProcess(const std::string& test_name, const std::string& spec);
  ~PeerProcess();  // kills the peer if it still runs
  PeerProcess(const PeerProcess&) = delete;
  PeerProcess& operator=(const PeerProcess&) = delete;

  // True once the peer called signal_ready(); false on timeout or when it died first.
  bool wait_ready(std::chrono::milliseconds limit);
  // The exit code (128 + signal when killed), nothing on timeout.
  std::optional<int> wait_exit(std::chrono::milliseconds limit);
  void kill();

 private:
  pid_t pid_ = -1;
  int ready_fd_ = -1;
};

// In the peer: its AMBID_DDS_PEER spec; nothing when this process is not a peer.
std::optional<std::string> peer_spec();
void signal_ready();

}  // namespace ambid::bus::test
