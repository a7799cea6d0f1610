#pragma once
// The UDP frame protocol between the plant daemon's rig gateway and a controller board
// (services/rig/RIG_PROTOCOL.md is the specification; this is its codec). One frame is one
// datagram of at most kMaxFrameSize bytes: a little-endian header (magic, version, type,
// length, sequence number, CRC-32) and a payload of the frame type.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace ambid::rig {

inline constexpr std::uint32_t kMagic = 0x52424D41;  // the bytes "AMBR"
inline constexpr std::uint16_t kVersion = 1;
inline constexpr std::size_t kHeaderSize = 20;
// 1500-byte Ethernet MTU minus the IPv4 (20) and UDP (8) headers: a frame is never fragmented.
inline constexpr std::size_t kMaxFrameSize = 1472;
inline constexpr std::size_t kMaxChannels = 8;  // per group (y, u, r)
inline constexpr std::size_t kMaxName = 32;     // model and channel names, excitation kind
inline constexpr std::size_t kMaxText = 200;    // gateway id, status message, NACK reason

enum class FrameType : std::uint16_t {
  hello = 1,
  keepalive = 2,
  status = 3,
  samples = 4,
  excite = 5,
  excite_reply = 6
};

// Gateway -> rig: subscribe (start streaming to the sender) and identify the gateway.
struct Hello {
  std::string gateway;
  bool operator==(const Hello&) const = default;
};
// Gateway -> rig: the subscription is still wanted (the rig stops streaming without it).
struct KeepAlive {
  bool operator==(const KeepAlive&) const = default;
};
enum class RigState : std::uint8_t { running = 0, fault = 1 };
// Rig -> gateway: the answer to HELLO and a heartbeat; names the channels of every batch.
struct RigStatus {
  RigState state = RigState::running;
  double board_time = 0.0;  // s, the board's clock
  double sample_time = 0.0;
  std::string model;
  std::vector<std::string> y_names, u_names, r_names;
  std::string message;
  bool operator==(const RigStatus&) const = default;
};
// Rig -> gateway: consecutive samples of one record (a record: the loop running without a
// restart; `first_index` counts its samples from 0).
struct SampleBatch {
  std::uint32_t record = 0;
  std::uint64_t first_index = 0;
  double sample_time = 0.0;
  std::string model;
  std::uint8_t ny = 0, nu = 0, nr = 0;
  std::vector<double> t;        // count entries, s (board clock)
  std::vector<double> y, u, r;  // row-major: count x ny, nu, nr
  std::size_t count() const { return t.size(); }
  bool operator==(const SampleBatch&) const = default;
};
// Gateway -> rig: an excitation for the following records (already within the plant
// daemon's limits); the rig answers with an ExciteReply of the same command number.
struct Excite {
  std::uint32_t command = 0;
  std::string kind;
  double amplitude = 0.0, f_min = 0.0, f_max = 0.0;
  bool operator==(const Excite&) const = default;
};
// Rig -> gateway: ACK (accepted) or NACK with the reason.
struct ExciteReply {
  std::uint32_t command = 0;
  bool accepted = false;
  std::string reason;
  bool operator==(const ExciteReply&) const = default;
};

using Payload = std::variant<Hello, KeepAlive, RigStatus, SampleBatch, Excite, ExciteReply>;

struct Frame {
  std::uint32_t seq = 0;  // the sender's frame counter (every type), wraps at 2^32
  Payload payload;
  bool operator==(const Frame&) const = default;
};

// Why a datagram is not a frame (the metrics label of the gateway's rejected frames).
enum class Fault {
  oversize,
  short_frame,
  bad_magic,
  bad_version,
  bad_length,
  bad_crc,
  unknown_type,
  bad_payload,
  bad_value
};
std::string_view fault_name(Fault fault);

struct Decoded {
  std::optional<Frame> frame;  // empty when rejected
  Fault fault = Fault::bad_payload;
  std::string reason;  // why rejected
};

// The datagram of a frame. Throws Error when the frame breaks a bound (too many channels or
// samples for one datagram, a name too long, counts inconsistent, a non-finite value).
std::vector<std::uint8_t> encode(const Frame& frame);
// Never throws: a malformed datagram comes back with its fault and a reason.
Decoded decode(std::span<const std::uint8_t> datagram);

// `text` cut to at most `max_bytes` at a UTF-8 character boundary, ending in "..." when cut:
// free texts (a NACK reason quoting a huge number, a status message) always fit their field.
std::string fit_text(std::string_view text, std::size_t max_bytes = kMaxText);

// CRC-32 (IEEE 802.3, reflected, as zlib's crc32): "123456789" -> 0xCBF43926.
std::uint32_t crc32(std::span<const std::uint8_t> bytes);

// The most samples one SAMPLES frame can hold for these channel counts and model name.
std::size_t max_batch_samples(std::size_t ny, std::size_t nu, std::size_t nr, std::size_t model_length);

}  // namespace ambid::rig
