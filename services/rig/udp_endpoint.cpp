#include "services/rig/udp_endpoint.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.hpp"

namespace ambid::rig {
namespace {

sockaddr_in to_sockaddr(const Endpoint& e) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(e.port);
  a.sin_addr.s_addr = htonl(e.address);
  return a;
}

Endpoint from_sockaddr(const sockaddr_in& a) { return {ntohl(a.sin_addr.s_addr), ntohs(a.sin_port)}; }

}  // namespace

std::string Endpoint::text() const {
  return std::to_string(address >> 24) + "." + std::to_string((address >> 16) & 0xFF) + "." +
         std::to_string((address >> 8) & 0xFF) + "." + std::to_string(address & 0xFF) + ":" + std::to_string(port);
}

Endpoint parse_endpoint(const std::string& text, bool allow_any_port) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos)
    throw Error("rig address '" + text + "': expected A.B.C.D:PORT (a numeric IPv4 address and a port)");
  const std::string host = text.substr(0, colon), port = text.substr(colon + 1);
  in_addr address{};
  if (inet_pton(AF_INET, host.c_str(), &address) != 1)
    throw Error("rig address '" + text + "': '" + host +
                "' is not a numeric IPv4 address (host names are not looked up)");
  if (port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos)
    throw Error("rig address '" + text + "': port '" + port + "' is not a number");
  const unsigned long p = std::stoul(port);
  if (p > 65535 || (p == 0 && !allow_any_port))
    throw Error("rig address '" + text + "': port " + port + " outside 1..65535");
  return {ntohl(address.s_addr), std::uint16_t(p)};
}

UdpSocket::UdpSocket(const Endpoint& local) : fd_(socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0)) {
  if (fd_ < 0) throw Error(std::string("UDP socket: ") + std::strerror(errno));
  // Room for bursts while the owner is busy; the kernel caps it at net.core.rmem_max.
  const int size = 4 << 20;
  setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &size, sizeof size);
  const sockaddr_in a = to_sockaddr(local);
  if (bind(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
    const std::string why = std::strerror(errno);
    close(fd_);
    throw Error("UDP socket on " + local.text() + ": " + why);
  }
}

UdpSocket::~UdpSocket() { close(fd_); }

Endpoint UdpSocket::local() const {
  sockaddr_in a{};
  socklen_t n = sizeof a;
  getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &n);
  return from_sockaddr(a);
}

bool UdpSocket::send_to(const Endpoint& to, std::span<const std::uint8_t> bytes) {
  const sockaddr_in a = to_sockaddr(to);
  return sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&a), sizeof a) ==
         ssize_t(bytes.size());
}

std::optional<UdpSocket::Datagram> UdpSocket::receive(std::chrono::milliseconds wait) {
  pollfd p{fd_, POLLIN, 0};
  if (poll(&p, 1, int(wait.count())) <= 0 || !(p.revents & POLLIN)) return std::nullopt;
  sockaddr_in from{};
  socklen_t n = sizeof from;
  const ssize_t got =
      recvfrom(fd_, buffer_.data(), buffer_.size(), MSG_DONTWAIT, reinterpret_cast<sockaddr*>(&from), &n);
  if (got < 0) return std::nullopt;  // e.g. ECONNREFUSED from an earlier send: nothing to read
  return Datagram{{buffer_.begin(), buffer_.begin() + got}, from_sockaddr(from)};
}

}  // namespace ambid::rig
