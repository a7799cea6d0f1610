// Nothing leaves loopback: while both vendors discover each other and exchange every topic, a
// packet socket watches every interface of this host. No UDP packet from or to the test domain's
// ports (7400 + 250 domain + 0..249, which includes the SPDP multicast port) may appear on any
// interface but lo, and lo must carry the exchange (proof that the capture works). Traffic of
// other programs on this shared host is not counted. Needs CAP_NET_RAW; skipped without.
// Domains 160..161.
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
#include <cstring>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "dds/harness.hpp"

namespace ambid::bus::test {
namespace {

// Counts the UDP packets of one domain's port range, on lo and elsewhere.
class Capture {
 public:
  explicit Capture(int domain)
      : first_port_(7400 + 250 * domain), last_port_(first_port_ + 249),
        loopback_index_(static_cast<int>(if_nametoindex("lo"))) {
    fd_ = socket(AF_PACKET, SOCK_DGRAM, htons(ETH_P_ALL));
    if (fd_ < 0) return;
    const int buffer = 8 << 20;
    setsockopt(fd_, SOL_SOCKET, SO_RCVBUFFORCE, &buffer, sizeof buffer);
    thread_ = std::thread([this] { run(); });
  }
  ~Capture() {
    stop();
    if (fd_ >= 0) close(fd_);
  }

  bool available() const { return fd_ >= 0; }
  void stop() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
  }
  int on_loopback() const { return on_loopback_; }
  const std::vector<std::string>& elsewhere() const { return elsewhere_; }
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
      const ssize_t n = recvfrom(fd_, packet.data(), packet.size(), 0,
                                 reinterpret_cast<sockaddr*>(&from), &size);
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
    if (from.sll_ifindex == loopback_index_) {
      ++on_loopback_;
      return;
    }
    std::ostringstream what;
    what << "interface " << from.sll_ifindex << ", protocol 0x" << std::hex << protocol
         << (multicast ? ", multicast" : "") << ", ports " << std::dec << source << " -> "
         << destination << ", " << n << " bytes";
    const std::lock_guard lock(mutex_);
    elsewhere_.push_back(what.str());
  }

  bool in_range(int port) const { return port >= first_port_ && port <= last_port_; }

  int first_port_, last_port_, loopback_index_;
  int fd_ = -1;
  std::atomic<bool> running_{true};
  std::thread thread_;
  std::atomic<int> on_loopback_{0};
  std::mutex mutex_;
  std::vector<std::string> elsewhere_;
};

void exchange_both_ways(Bus& fast, Bus& cyclone) {
  for (auto [from, to] : {std::pair{&fast, &cyclone}, std::pair{&cyclone, &fast}}) {
    AllReaders readers(*to);
    AllWriters writers(*from);
    ASSERT_TRUE(eventually([&] { return writers.all_matched() && readers.all_matched(); }));
    write_all(writers);
    expect_all(readers);
  }
}

void expect_nothing_left_loopback(int domain, const std::string& fast_profile,
                                  const std::string& cyclone_profile) {
  Capture capture(domain);
  if (!capture.available()) GTEST_SKIP() << "no packet socket (needs CAP_NET_RAW)";
  {
    const auto fast = make_bus("fastdds", domain, fast_profile);
    const auto cyclone = make_bus("cyclone", domain, cyclone_profile);
    exchange_both_ways(*fast, *cyclone);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // goodbyes
  capture.stop();
  EXPECT_GT(capture.on_loopback(), 0) << "the capture saw nothing at all";
  EXPECT_EQ(capture.dropped(), 0u) << "the capture dropped packets: the result is incomplete";
  EXPECT_TRUE(capture.elsewhere().empty())
      << capture.elsewhere().size() << " packets left loopback, first: "
      << capture.elsewhere().front();
}

TEST(LoopbackOnly, BuiltInProfilesSendNothingElsewhere) {
  expect_nothing_left_loopback(160, std::string(loopback_profile), std::string(loopback_profile));
}

TEST(LoopbackOnly, ProfileFilesSendNothingElsewhere) {
  const std::string dir = AMBID_SOURCE_DIR "/deploy/dds/";
  expect_nothing_left_loopback(161, dir + "fastdds-loopback.xml", dir + "cyclone-loopback.xml");
}

}  // namespace
}  // namespace ambid::bus::test
