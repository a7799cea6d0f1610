// The rig protocol codec (RIG_PROTOCOL.md): every frame type survives a round trip, one frame
// always fits one unfragmented datagram, and every malformed datagram is rejected with its
// fault and a reason naming what is wrong.
#include "services/rig/rig_frame.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <random>

#include "core/error.hpp"

namespace ambid::rig {
namespace rig_frame_test {

using ::testing::HasSubstr;

std::vector<std::uint8_t> bytes_of(const std::string& s) { return {s.begin(), s.end()}; }

// Recomputes the CRC after a test edited the frame (so only the edited field is wrong).
void reseal(std::vector<std::uint8_t>& b) {
  for (std::size_t k = 16; k < 20; ++k) b[k] = 0;
  const std::uint32_t c = crc32(b);
  for (int k = 0; k < 4; ++k) b[16 + std::size_t(k)] = std::uint8_t(c >> (8 * k));
}

void put_u16(std::vector<std::uint8_t>& b, std::size_t at, std::uint16_t v) {
  b[at] = std::uint8_t(v);
  b[at + 1] = std::uint8_t(v >> 8);
}

SampleBatch batch(std::size_t count, std::uint8_t ny = 3, std::uint8_t nu = 2, std::uint8_t nr = 2) {
  SampleBatch b;
  b.record = 7;
  b.first_index = 1234;
  b.sample_time = 1e-4;
  b.model = "amb1dof_voltage";
  b.ny = ny;
  b.nu = nu;
  b.nr = nr;
  for (std::size_t k = 0; k < count; ++k) {
    b.t.push_back(0.5 + double(k) * 1e-4);
    for (std::size_t j = 0; j < ny; ++j) b.y.push_back(1e-6 * double(k + j) - 3.25);
    for (std::size_t j = 0; j < nu; ++j) b.u.push_back(0.1 * double(j) + 1.0 / double(k + 3));
    for (std::size_t j = 0; j < nr; ++j) b.r.push_back(k % 2 ? 0.05 : -0.05);
  }
  return b;
}

Decoded decode_bytes(const std::vector<std::uint8_t>& b) { return decode(b); }

TEST(RigFrame, Crc32IsTheIeeeCheckValue) {
  EXPECT_EQ(crc32(bytes_of("123456789")), 0xCBF43926u);  // the catalogued check value of CRC-32/ISO-HDLC
  EXPECT_EQ(crc32(bytes_of("")), 0u);
  EXPECT_EQ(crc32(bytes_of("The quick brown fox jumps over the lazy dog")), 0x414FA339u);
}

TEST(RigFrame, HeaderLayoutIsLittleEndian) {
  const auto b = encode(Frame{0x01020304, KeepAlive{}});
  ASSERT_EQ(b.size(), kHeaderSize);
  EXPECT_EQ(std::string(b.begin(), b.begin() + 4), "AMBR");
  EXPECT_EQ(b[4], 1);  // version 1
  EXPECT_EQ(b[5], 0);
  EXPECT_EQ(b[6], 2);   // KEEPALIVE
  EXPECT_EQ(b[8], 20);  // length
  EXPECT_EQ(b[12], 0x04);
  EXPECT_EQ(b[15], 0x01);
}

TEST(RigFrame, EveryTypeRoundTrips) {
  RigStatus status;
  status.state = RigState::fault;
  status.board_time = 12.5;
  status.sample_time = 1e-4;
  status.model = "amb1dof_voltage";
  status.y_names = {"x", "i1", "i2"};
  status.u_names = {"u1", "u2"};
  status.r_names = {"r1", "r2"};
  status.message = "amplifier 2 over temperature";
  const std::vector<Payload> payloads{Hello{"bearing-1 gateway"},
                                      KeepAlive{},
                                      status,
                                      batch(21),
                                      Excite{42, "multisine", 0.2, 1.0, 800.0},
                                      ExciteReply{42, false, "too fast"},
                                      ExciteReply{43, true, ""}};
  std::uint32_t seq = 0xFFFFFFF0u;
  for (const Payload& p : payloads) {
    const Frame f{seq++, p};
    const Decoded d = decode(encode(f));
    ASSERT_TRUE(d.frame) << d.reason;
    EXPECT_EQ(*d.frame, f);
  }
}

// 1472 bytes (no IP fragmentation on an Ethernet path); the largest batch fits, one more
// sample does not.
TEST(RigFrame, TheLargestBatchFitsOneDatagram) {
  const std::size_t n = max_batch_samples(3, 2, 2, std::string("amb1dof_voltage").size());
  EXPECT_EQ(n, 22u);  // (1472 - 20 - 26 - 15) / 64 = 22.05
  const auto b = encode(Frame{1, batch(n)});
  EXPECT_LE(b.size(), kMaxFrameSize);
  EXPECT_GT(b.size() + 64, kMaxFrameSize);
  EXPECT_THROW(encode(Frame{1, batch(n + 1)}), Error);
}

TEST(RigFrame, EncodeRefusesWhatBreaksTheBounds) {
  SampleBatch nan = batch(3);
  nan.y[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(encode(Frame{0, nan}), Error);
  SampleBatch ragged = batch(3);
  ragged.u.pop_back();
  EXPECT_THROW(encode(Frame{0, ragged}), Error);
  EXPECT_THROW(encode(Frame{0, SampleBatch{}}), Error);
  EXPECT_THROW(encode(Frame{0, Hello{std::string(kMaxText + 1, 'g')}}), Error);
  RigStatus many;
  many.y_names.assign(kMaxChannels + 1, "y");
  EXPECT_THROW(encode(Frame{0, many}), Error);
}

struct Case {
  const char* what;
  std::vector<std::uint8_t> bytes;
  Fault fault;
  const char* reason;
};

std::vector<Case> malformed_cases() {
  const auto good = encode(Frame{5, batch(10)});
  std::vector<Case> cases;
  cases.push_back({"empty", {}, Fault::short_frame, "shorter than the 20-byte header"});
  cases.push_back(
      {"short", std::vector<std::uint8_t>(good.begin(), good.begin() + 19), Fault::short_frame, "19 bytes"});
  cases.push_back({"oversize", std::vector<std::uint8_t>(kMaxFrameSize + 1, 0), Fault::oversize, "1473 bytes"});
  auto magic = good;
  magic[0] = 'X';
  reseal(magic);
  cases.push_back({"bad magic", magic, Fault::bad_magic, "not an ambid rig frame"});
  auto version = good;
  put_u16(version, 4, 2);
  reseal(version);
  cases.push_back({"wrong version", version, Fault::bad_version, "protocol version 2, this end speaks 1"});
  auto longer = good;
  longer.push_back(0);
  cases.push_back({"length field", longer, Fault::bad_length, "length field"});
  auto crc = good;
  crc[100] ^= 0x01;
  cases.push_back({"bad crc", crc, Fault::bad_crc, "CRC-32"});
  auto type = good;
  put_u16(type, 6, 99);
  reseal(type);
  cases.push_back({"unknown type", type, Fault::unknown_type, "frame type 99"});
  // Sample count 11 in a payload of 10 samples: counts inconsistent with the length.
  auto count = good;
  put_u16(count, 20 + 4 + 8 + 8 + 16 + 3, 11);
  reseal(count);
  cases.push_back(
      {"count vs length", count, Fault::bad_payload, "11 samples of 8 values need 704 bytes, the payload holds 640"});
  auto channels = good;
  channels[20 + 4 + 8 + 8 + 16] = 9;  // ny = 9 > 8
  reseal(channels);
  cases.push_back({"channel count", channels, Fault::bad_payload, "at most 8 each"});
  auto nan = good;
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(std::numeric_limits<double>::quiet_NaN());
  const std::size_t first_y = 20 + 26 + 15 + 8;  // after the first sample's time stamp
  for (int k = 0; k < 8; ++k) nan[first_y + std::size_t(k)] = std::uint8_t(bits >> (8 * k));
  reseal(nan);
  cases.push_back({"NaN", nan, Fault::bad_value, "y value is not finite"});
  auto time = good;
  const std::size_t second_t = 20 + 26 + 15 + 64;
  const std::uint64_t late = std::bit_cast<std::uint64_t>(0.5 + 3e-4);
  for (int k = 0; k < 8; ++k) time[second_t + std::size_t(k)] = std::uint8_t(late >> (8 * k));
  reseal(time);
  cases.push_back({"non-uniform times", time, Fault::bad_value, "sample 1 is not one sample time after the previous"});
  auto trailing = encode(Frame{1, Hello{"g"}});
  trailing.push_back(0);
  trailing[8] = std::uint8_t(trailing.size());
  reseal(trailing);
  cases.push_back({"trailing bytes", trailing, Fault::bad_payload, "1 bytes after the end of the payload"});
  auto cut = encode(Frame{1, Excite{1, "prbs", 0.1, 0, 0}});
  cut.resize(cut.size() - 3);
  cut[8] = std::uint8_t(cut.size());
  reseal(cut);
  cases.push_back({"truncated payload", cut, Fault::bad_payload, "payload ends inside f_max"});
  auto flag = encode(Frame{1, ExciteReply{1, true, ""}});
  flag[24] = 2;
  reseal(flag);
  cases.push_back({"bad flag", flag, Fault::bad_payload, "accepted flag 2"});
  return cases;
}

TEST(RigFrame, EveryMalformedCaseIsRejectedWithItsReason) {
  for (const Case& c : malformed_cases()) {
    const Decoded d = decode_bytes(c.bytes);
    EXPECT_FALSE(d.frame) << c.what;
    EXPECT_EQ(d.fault, c.fault) << c.what << ": " << d.reason;
    EXPECT_THAT(d.reason, HasSubstr(c.reason)) << c.what;
  }
}

// CRC-32 detects every single-bit error: no flipped bit of a valid frame is ever accepted.
TEST(RigFrame, EverySingleBitFlipIsRejected) {
  const auto good = encode(Frame{9, batch(21)});
  for (std::size_t bit = 0; bit < good.size() * 8; ++bit) {
    auto b = good;
    b[bit / 8] ^= std::uint8_t(1u << (bit % 8));
    ASSERT_FALSE(decode_bytes(b).frame) << "bit " << bit;
  }
}

// Random datagrams (seeded) never throw out of decode and are never taken for frames.
TEST(RigFrame, RandomBytesNeverDecode) {
  std::mt19937 random(2024);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<std::size_t> size(0, 1600);
  for (int k = 0; k < 5000; ++k) {
    std::vector<std::uint8_t> b(size(random));
    for (auto& v : b) v = std::uint8_t(byte(random));
    if (b.size() >= 4 && k % 2) std::copy_n("AMBR", 4, b.begin());  // get past the magic half the time
    const Decoded d = decode_bytes(b);
    EXPECT_FALSE(d.frame);
    EXPECT_FALSE(d.reason.empty());
  }
}

TEST(RigFrame, FitTextCutsLongTextsAtACharacterBoundary) {
  EXPECT_EQ(fit_text("short reason"), "short reason");
  const std::string huge = "amplitude " + std::string(400, '9') + " V above the limit";
  const std::string cut = fit_text(huge);
  EXPECT_EQ(cut.size(), kMaxText);
  EXPECT_EQ(cut.substr(0, 11), "amplitude 9");
  EXPECT_EQ(cut.substr(cut.size() - 3), "...");
  // 7 bytes: "ab" + the 2-byte "\u00b5" + "..." fits, a 3rd byte would split the next "\u00b5".
  EXPECT_EQ(fit_text("ab\u00b5\u00b5\u00b5\u00b5", 8), "ab\u00b5...");
  EXPECT_EQ(fit_text("abcdef", 2), "..");
  // The cut text is a valid frame field: a NACK quoting 1e300 encodes and decodes.
  const Frame nack{7, ExciteReply{3, false, cut}};
  const Decoded back = decode(encode(nack));
  ASSERT_TRUE(back.frame);
  EXPECT_EQ(*back.frame, nack);
}

}  // namespace rig_frame_test
}  // namespace ambid::rig
