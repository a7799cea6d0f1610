#pragma once
// A packet socket (AF_PACKET) on every interface of this host counting the UDP packets of one
// DDS domain's port range (7400 + 250 domain + 0..249, which includes the SPDP multicast
// port): on lo, elsewhere (each described), and multicast on any interface. Traffic of other
// programs on this shared host is not counted. Needs CAP_NET_RAW: available() is false
// without. Shared by tests/dds/loopback_only_test.cpp (two participants) and
// tests/integration/stack_loopback_test.cpp (the whole stack as processes).
#include <arpa/inet.h>
#include <linux/if_ether.h>
#include <linux/if_packet.h>
#include <net/if.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace ambid::test {

class PacketCapture {
 public:
  explicit PacketCapture(int domain)
      : first_port_(7400 + 250 * domain),
        last_port_(first_port_ + 249),
        loopback_index_(static_cast<int>(if_nametoindex("lo"))) {
    fd_ = socket(AF_PACKET, SOCK_DGRAM, htons(ETH_P_ALL));
    if (fd_ < 0) return;
    const int buffer = 32 << 20;  // the stack's sample stream must not overrun it
    setsockopt(fd_, SOL_SOCKET, SO_RCVBUFFORCE, &buffer, sizeof buffer);
    thread_ = std::thread([this] { run(); });
  }
  ~PacketCapture() {
    stop();
    if (fd_ >= 0) close(fd_);
  }
  PacketCapture(const PacketCapture&) = delete;
  PacketCapture& operator=(const PacketCapture&) = delete;

  bool available() const { return fd_ >= 0; }
  void stop() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
  }
  int on_loopback() const { return on_loopback_; }
  int multicast() const { return multicast_; }  // on any interface, lo included
  // Call after stop().
  const std::vector<std::string>& elsewhere() const { return elsewhere_; }
  // Packets the kernel dropped because the socket's buffer was full (the count is incomplete).
  unsigned dropped() const {
    tpacket_stats stats{};
    socklen_t size = sizeof stats;
    getsockopt(fd_, SOL_PACKET, PACKET_STATISTICS, &stats, &size);
    return stats.tp_drops;
  }

 private:
  void run() {
    std::vector<unsigned char> packet(65536);
    while (running_) {
      pollfd p{fd_, POLLIN, 0};
      if (poll(&p, 1, 50) != 1) continue;
      sockaddr_ll from{};
      socklen_t size = sizeof from;
      const ssize_t n = recvfrom(fd_, packet.data(), packet.size(), 0, reinterpret_cast<sockaddr*>(&from), &size);
      if (n > 0) classify(packet.data(), static_cast<std::size_t>(n), from);
    }
  }

  void classify(const unsigned char* ip, std::size_t n, const sockaddr_ll& from) {
    bool multicast = false;
    std::size_t udp = 0;  // offset of the UDP header, 0: none
    const unsigned protocol = ntohs(from.sll_protocol);
    if (protocol == ETH_P_IP && n >= 20) {
      multicast = (ip[16] & 0xF0) == 0xE0;
      if (ip[9] == IPPROTO_UDP) udp = static_cast<std::size_t>(ip[0] & 0x0F) * 4;
    } else if (protocol == ETH_P_IPV6 && n >= 40) {
      multicast = ip[24] == 0xFF;
      if (ip[6] == IPPROTO_UDP) udp = 40;
    }
    if (udp == 0 || n < udp + 4) return;
    const int source = ip[udp] << 8 | ip[udp + 1];
    const int destination = ip[udp + 2] << 8 | ip[udp + 3];
    if (!in_range(source) && !in_range(destination)) return;
    if (multicast) ++multicast_;
    if (from.sll_ifindex == loopback_index_) {
      ++on_loopback_;
      return;
    }
    std::ostringstream what;
    what << "interface " << from.sll_ifindex << ", protocol 0x" << std::hex << protocol
         << (multicast ? ", multicast" : "") << ", ports " << std::dec << source << " -> " << destination << ", " << n
         << " bytes";
    const std::lock_guard lock(mutex_);
    elsewhere_.push_back(what.str());
  }

  bool in_range(int port) const { return port >= first_port_ && port <= last_port_; }

  int first_port_, last_port_, loopback_index_;
  int fd_ = -1;
  std::atomic<bool> running_{true};
  std::thread thread_;
  std::atomic<int> on_loopback_{0}, multicast_{0};
  std::mutex mutex_;
  std::vector<std::string> elsewhere_;
};

}  // namespace ambid::test
