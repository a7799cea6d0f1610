#include "services/rig/rig_frame.hpp"

#include <array>
#include <bit>
#include <cmath>

#include "core/error.hpp"

namespace ambid::rig {
namespace {

constexpr std::size_t kBatchFixed = 4 + 8 + 8 + 1 + 3 + 2;  // + model name bytes

class Writer {
 public:
  void u8(std::uint8_t v) { bytes_.push_back(v); }
  void u16(std::uint16_t v) { little(v, 2); }
  void u32(std::uint32_t v) { little(v, 4); }
  void u64(std::uint64_t v) { little(v, 8); }
  void f64(double v) {
    if (!std::isfinite(v)) throw Error("rig frame: a value is not finite");
    u64(std::bit_cast<std::uint64_t>(v));
  }
  void text(const std::string& s, std::size_t limit, const char* what) {
    if (s.size() > limit)
      throw Error(std::string("rig frame: ") + what + " of " + std::to_string(s.size()) + " bytes, at most " +
                  std::to_string(limit));
    u8(std::uint8_t(s.size()));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
  }
  void names(const std::vector<std::string>& n, const char* what) {
    if (n.size() > kMaxChannels)
      throw Error(std::string("rig frame: ") + std::to_string(n.size()) + " " + what + " channels, at most " +
                  std::to_string(kMaxChannels));
    u8(std::uint8_t(n.size()));
    for (const auto& s : n) text(s, kMaxName, "channel name");
  }
  std::vector<std::uint8_t>& bytes() { return bytes_; }

 private:
  void little(std::uint64_t v, int n) {
    for (int k = 0; k < n; ++k) bytes_.push_back(std::uint8_t(v >> (8 * k)));
  }
  std::vector<std::uint8_t> bytes_;
};

// Thrown inside decode only; becomes a Decoded with its fault.
struct Malformed {
  Fault fault;
  std::string reason;
};

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> b) : b_(b) {}
  std::uint8_t u8(const char* field) { return std::uint8_t(little(1, field)); }
  std::uint16_t u16(const char* field) { return std::uint16_t(little(2, field)); }
  std::uint32_t u32(const char* field) { return std::uint32_t(little(4, field)); }
  std::uint64_t u64(const char* field) { return little(8, field); }
  double f64(const char* field) {
    const double v = std::bit_cast<double>(little(8, field));
    if (!std::isfinite(v)) throw Malformed{Fault::bad_value, std::string(field) + " is not finite"};
    return v;
  }
  std::string text(std::size_t limit, const char* field) {
    const std::size_t n = u8(field);
    if (n > limit)
      throw Malformed{Fault::bad_payload,
                      std::string(field) + " of " + std::to_string(n) + " bytes, at most " + std::to_string(limit)};
    need(n, field);
    std::string s(b_.begin() + std::ptrdiff_t(at_), b_.begin() + std::ptrdiff_t(at_ + n));
    at_ += n;
    return s;
  }
  std::vector<std::string> names(const char* field) {
    const std::size_t n = u8(field);
    if (n > kMaxChannels)
      throw Malformed{Fault::bad_payload,
                      std::to_string(n) + " " + field + ", at most " + std::to_string(kMaxChannels)};
    std::vector<std::string> out;
    for (std::size_t k = 0; k < n; ++k) out.push_back(text(kMaxName, field));
    return out;
  }
  std::size_t left() const { return b_.size() - at_; }
  void need(std::size_t n, const char* field) const {
    if (left() < n)
      throw Malformed{Fault::bad_payload, std::string("payload ends inside ") + field + " (" + std::to_string(left()) +
                                              " of " + std::to_string(n) + " bytes)"};
  }

 private:
  std::uint64_t little(int n, const char* field) {
    need(std::size_t(n), field);
    std::uint64_t v = 0;
    for (int k = 0; k < n; ++k) v |= std::uint64_t(b_[at_ + std::size_t(k)]) << (8 * k);
    at_ += std::size_t(n);
    return v;
  }
  std::span<const std::uint8_t> b_;
  std::size_t at_ = 0;
};

std::uint32_t load32(std::span<const std::uint8_t> b, std::size_t at) {
  return std::uint32_t(b[at]) | std::uint32_t(b[at + 1]) << 8 | std::uint32_t(b[at + 2]) << 16 |
         std::uint32_t(b[at + 3]) << 24;
}

void check_batch_shape(const SampleBatch& s) {
  const std::size_t n = s.count();
  if (n == 0) throw Error("rig frame: a sample batch without samples");
  if (s.ny > kMaxChannels || s.nu > kMaxChannels || s.nr > kMaxChannels)
    throw Error("rig frame: more than " + std::to_string(kMaxChannels) + " channels in a group");
  if (s.y.size() != n * s.ny || s.u.size() != n * s.nu || s.r.size() != n * s.nr)
    throw Error("rig frame: y, u, r do not hold count x channel values");
  if (n > max_batch_samples(s.ny, s.nu, s.nr, s.model.size()))
    throw Error("rig frame: " + std::to_string(n) + " samples do not fit one datagram (at most " +
                std::to_string(max_batch_samples(s.ny, s.nu, s.nr, s.model.size())) + ")");
}

struct EncodePayload {
  Writer& w;
  FrameType operator()(const Hello& h) const {
    w.text(h.gateway, kMaxText, "gateway id");
    return FrameType::hello;
  }
  FrameType operator()(const KeepAlive&) const { return FrameType::keepalive; }
  FrameType operator()(const RigStatus& s) const {
    w.u8(std::uint8_t(s.state));
    w.f64(s.board_time);
    w.f64(s.sample_time);
    w.text(s.model, kMaxName, "model name");
    w.names(s.y_names, "y");
    w.names(s.u_names, "u");
    w.names(s.r_names, "r");
    w.text(s.message, kMaxText, "status message");
    return FrameType::status;
  }
  FrameType operator()(const SampleBatch& s) const {
    check_batch_shape(s);
    w.u32(s.record);
    w.u64(s.first_index);
    w.f64(s.sample_time);
    w.text(s.model, kMaxName, "model name");
    w.u8(s.ny);
    w.u8(s.nu);
    w.u8(s.nr);
    w.u16(std::uint16_t(s.count()));
    for (std::size_t k = 0; k < s.count(); ++k) {
      w.f64(s.t[k]);
      for (std::size_t j = 0; j < s.ny; ++j) w.f64(s.y[k * s.ny + j]);
      for (std::size_t j = 0; j < s.nu; ++j) w.f64(s.u[k * s.nu + j]);
      for (std::size_t j = 0; j < s.nr; ++j) w.f64(s.r[k * s.nr + j]);
    }
    return FrameType::samples;
  }
  FrameType operator()(const Excite& e) const {
    w.u32(e.command);
    w.text(e.kind, kMaxName, "excitation kind");
    w.f64(e.amplitude);
    w.f64(e.f_min);
    w.f64(e.f_max);
    return FrameType::excite;
  }
  FrameType operator()(const ExciteReply& r) const {
    w.u32(r.command);
    w.u8(r.accepted ? 1 : 0);
    w.text(r.reason, kMaxText, "reason");
    return FrameType::excite_reply;
  }
};

SampleBatch decode_batch(Reader& r) {
  SampleBatch s;
  s.record = r.u32("record");
  s.first_index = r.u64("first index");
  s.sample_time = r.f64("sample time");
  if (!(s.sample_time > 0))
    throw Malformed{Fault::bad_value, "sample time " + std::to_string(s.sample_time) + " s is not > 0"};
  s.model = r.text(kMaxName, "model name");
  s.ny = r.u8("y count");
  s.nu = r.u8("u count");
  s.nr = r.u8("r count");
  const std::size_t count = r.u16("sample count");
  if (s.ny > kMaxChannels || s.nu > kMaxChannels || s.nr > kMaxChannels)
    throw Malformed{Fault::bad_payload, "channel counts " + std::to_string(s.ny) + "/" + std::to_string(s.nu) + "/" +
                                            std::to_string(s.nr) + ", at most " + std::to_string(kMaxChannels) +
                                            " each"};
  if (count == 0) throw Malformed{Fault::bad_payload, "a sample batch without samples"};
  const std::size_t needed = count * 8 * (1 + std::size_t(s.ny) + s.nu + s.nr);
  if (needed != r.left())
    throw Malformed{Fault::bad_payload,
                    std::to_string(count) + " samples of " + std::to_string(1 + s.ny + s.nu + s.nr) + " values need " +
                        std::to_string(needed) + " bytes, the payload holds " + std::to_string(r.left())};
  for (std::size_t k = 0; k < count; ++k) {
    s.t.push_back(r.f64("sample time stamp"));
    for (std::size_t j = 0; j < s.ny; ++j) s.y.push_back(r.f64("y value"));
    for (std::size_t j = 0; j < s.nu; ++j) s.u.push_back(r.f64("u value"));
    for (std::size_t j = 0; j < s.nr; ++j) s.r.push_back(r.f64("r value"));
    // Uniform sampling, the contract of an experiment (core/experiment.hpp).
    if (k > 0 && !(std::abs(s.t[k] - s.t[k - 1] - s.sample_time) <= 0.01 * s.sample_time))
      throw Malformed{Fault::bad_value, "sample " + std::to_string(k) + " is not one sample time after the previous"};
  }
  return s;
}

Payload decode_payload(FrameType type, Reader& r) {
  switch (type) {
    case FrameType::hello:
      return Hello{r.text(kMaxText, "gateway id")};
    case FrameType::keepalive:
      return KeepAlive{};
    case FrameType::status: {
      RigStatus s;
      const std::uint8_t state = r.u8("state");
      if (state > 1)
        throw Malformed{Fault::bad_payload, "rig state " + std::to_string(state) + " unknown (0 running, 1 fault)"};
      s.state = RigState(state);
      s.board_time = r.f64("board time");
      s.sample_time = r.f64("sample time");
      if (!(s.sample_time > 0))
        throw Malformed{Fault::bad_value, "sample time " + std::to_string(s.sample_time) + " s is not > 0"};
      s.model = r.text(kMaxName, "model name");
      s.y_names = r.names("y names");
      s.u_names = r.names("u names");
      s.r_names = r.names("r names");
      s.message = r.text(kMaxText, "status message");
      return s;
    }
    case FrameType::samples:
      return decode_batch(r);
    case FrameType::excite: {
      Excite e;
      e.command = r.u32("command");
      e.kind = r.text(kMaxName, "excitation kind");
      e.amplitude = r.f64("amplitude");
      e.f_min = r.f64("f_min");
      e.f_max = r.f64("f_max");
      return e;
    }
    case FrameType::excite_reply: {
      ExciteReply e;
      e.command = r.u32("command");
      const std::uint8_t accepted = r.u8("accepted");
      if (accepted > 1)
        throw Malformed{Fault::bad_payload, "accepted flag " + std::to_string(accepted) + " is not 0 or 1"};
      e.accepted = accepted == 1;
      e.reason = r.text(kMaxText, "reason");
      return e;
    }
  }
  throw Malformed{Fault::unknown_type, "frame type " + std::to_string(int(type)) + " unknown"};
}

}  // namespace

std::string_view fault_name(Fault fault) {
  switch (fault) {
    case Fault::oversize:
      return "oversize";
    case Fault::short_frame:
      return "short";
    case Fault::bad_magic:
      return "magic";
    case Fault::bad_version:
      return "version";
    case Fault::bad_length:
      return "length";
    case Fault::bad_crc:
      return "crc";
    case Fault::unknown_type:
      return "type";
    case Fault::bad_payload:
      return "payload";
    case Fault::bad_value:
      break;
  }
  return "value";
}

std::string fit_text(std::string_view text, std::size_t max_bytes) {
  if (text.size() <= max_bytes) return std::string(text);
  constexpr std::string_view kCut = "...";
  if (max_bytes < kCut.size()) return std::string(max_bytes, '.');
  std::size_t keep = max_bytes - kCut.size();
  while (keep > 0 && (static_cast<unsigned char>(text[keep]) & 0xC0) == 0x80) --keep;  // inside a character
  return std::string(text.substr(0, keep)) + std::string(kCut);
}

std::uint32_t crc32(std::span<const std::uint8_t> bytes) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::uint8_t b : bytes) c = table[(c ^ b) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

std::size_t max_batch_samples(std::size_t ny, std::size_t nu, std::size_t nr, std::size_t model_length) {
  return (kMaxFrameSize - kHeaderSize - kBatchFixed - model_length) / (8 * (1 + ny + nu + nr));
}

std::vector<std::uint8_t> encode(const Frame& frame) {
  Writer w;
  w.u32(kMagic);
  w.u16(kVersion);
  w.u16(0);  // type, set below
  w.u32(0);  // length, set below
  w.u32(frame.seq);
  w.u32(0);  // CRC, computed with this field zero
  const FrameType type = std::visit(EncodePayload{w}, frame.payload);
  std::vector<std::uint8_t>& b = w.bytes();
  if (b.size() > kMaxFrameSize)
    throw Error("rig frame: " + std::to_string(b.size()) + " bytes, at most " + std::to_string(kMaxFrameSize));
  const auto put32 = [&b](std::size_t at, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) b[at + std::size_t(k)] = std::uint8_t(v >> (8 * k));
  };
  b[6] = std::uint8_t(std::uint16_t(type));
  b[7] = std::uint8_t(std::uint16_t(type) >> 8);
  put32(8, std::uint32_t(b.size()));
  put32(16, crc32(b));
  return b;
}

Decoded decode(std::span<const std::uint8_t> d) {
  try {
    if (d.size() > kMaxFrameSize)
      throw Malformed{Fault::oversize,
                      "datagram of " + std::to_string(d.size()) + " bytes, at most " + std::to_string(kMaxFrameSize)};
    if (d.size() < kHeaderSize)
      throw Malformed{Fault::short_frame, "datagram of " + std::to_string(d.size()) + " bytes, shorter than the " +
                                              std::to_string(kHeaderSize) + "-byte header"};
    Reader h(d.first(kHeaderSize));
    if (const std::uint32_t magic = h.u32("magic"); magic != kMagic)
      throw Malformed{Fault::bad_magic, "magic 0x" + [&] {
                        static const char* hex = "0123456789abcdef";
                        std::string s;
                        for (int k = 7; k >= 0; --k) s += hex[(magic >> (4 * k)) & 0xF];
                        return s;
                      }() + " is not an ambid rig frame"};
    if (const std::uint16_t version = h.u16("version"); version != kVersion)
      throw Malformed{Fault::bad_version,
                      "protocol version " + std::to_string(version) + ", this end speaks " + std::to_string(kVersion)};
    const std::uint16_t type = h.u16("type");
    if (const std::uint32_t length = h.u32("length"); length != d.size())
      throw Malformed{Fault::bad_length, "length field " + std::to_string(length) + " bytes, the datagram has " +
                                             std::to_string(d.size())};
    Frame frame;
    frame.seq = h.u32("sequence number");
    std::vector<std::uint8_t> zeroed(d.begin(), d.end());
    for (std::size_t k = 16; k < 20; ++k) zeroed[k] = 0;
    if (load32(d, 16) != crc32(zeroed)) throw Malformed{Fault::bad_crc, "CRC-32 does not match the frame"};
    if (type < 1 || type > 6) throw Malformed{Fault::unknown_type, "frame type " + std::to_string(type) + " unknown"};
    Reader r(d.subspan(kHeaderSize));
    frame.payload = decode_payload(FrameType(type), r);
    if (r.left() != 0)
      throw Malformed{Fault::bad_payload, std::to_string(r.left()) + " bytes after the end of the payload"};
    return {std::move(frame), Fault::bad_payload, {}};
  } catch (const Malformed& m) {
    return {std::nullopt, m.fault, m.reason};
  }
}

}  // namespace ambid::rig
