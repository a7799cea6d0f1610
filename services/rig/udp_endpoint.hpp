#pragma once
// Numeric IPv4 endpoints ("127.0.0.1:5000") and a non-blocking UDP socket for the rig
// protocol. Host names are refused: a rig address is configured, never looked up.
#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace ambid::rig {

struct Endpoint {
  std::uint32_t address = 0;  // host byte order
  std::uint16_t port = 0;
  std::string text() const;
  bool loopback() const { return (address >> 24) == 127; }
  bool operator==(const Endpoint&) const = default;
};

// "A.B.C.D:PORT" with a dotted-quad address and a port 1..65535 (0 too when `allow_any_port`:
// a socket to bind). Throws Error naming the text and what is wrong with it.
Endpoint parse_endpoint(const std::string& text, bool allow_any_port = false);

class UdpSocket {
 public:
  // Bound to `local` (port 0: any free port). Throws Error naming the endpoint and errno text.
  explicit UdpSocket(const Endpoint& local);
  ~UdpSocket();
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;

  Endpoint local() const;
  // False when the kernel refused the datagram (e.g. no listener yet: ICMP port unreachable).
  bool send_to(const Endpoint& to, std::span<const std::uint8_t> bytes);

  struct Datagram {
    std::vector<std::uint8_t> bytes;  // the whole datagram (up to 64 KiB)
    Endpoint from;
  };
  // The next datagram, waiting at most `wait`; nullopt when none arrived.
  std::optional<Datagram> receive(std::chrono::milliseconds wait);

 private:
  int fd_ = -1;
  std::vector<std::uint8_t> buffer_ = std::vector<std::uint8_t>(65536);
};

}  // namespace ambid::rig
