// Rig addresses: numeric IPv4 and a port, refused otherwise with the reason; and a datagram
// over loopback arrives whole with its sender.
#include "services/rig/udp_endpoint.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"

namespace ambid::rig {
namespace udp_endpoint_test {

using ::testing::HasSubstr;

std::string refusal(const std::string& text) {
  try {
    parse_endpoint(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "accepted";
}

TEST(UdpEndpoint, ParsesNumericAddresses) {
  const Endpoint e = parse_endpoint("127.0.0.1:19180");
  EXPECT_EQ(e.address, 0x7F000001u);
  EXPECT_EQ(e.port, 19180);
  EXPECT_TRUE(e.loopback());
  EXPECT_EQ(e.text(), "127.0.0.1:19180");
  EXPECT_FALSE(parse_endpoint("10.1.2.3:5000").loopback());
  EXPECT_EQ(parse_endpoint("127.0.0.1:0", true).port, 0);
}

TEST(UdpEndpoint, RefusesMalformedAddressesNamingWhy) {
  EXPECT_THAT(refusal("localhost:5000"), HasSubstr("'localhost' is not a numeric IPv4 address"));
  EXPECT_THAT(refusal("127.0.0.1"), HasSubstr("expected A.B.C.D:PORT"));
  EXPECT_THAT(refusal("127.0.0.1:"), HasSubstr("port '' is not a number"));
  EXPECT_THAT(refusal("127.0.0.1:5o00"), HasSubstr("port '5o00' is not a number"));
  EXPECT_THAT(refusal("127.0.0.1:70000"), HasSubstr("port 70000 outside 1..65535"));
  EXPECT_THAT(refusal("127.0.0.1:0"), HasSubstr("outside 1..65535"));
  EXPECT_THAT(refusal("256.0.0.1:5000"), HasSubstr("not a numeric IPv4 address"));
  EXPECT_THAT(refusal(":5000"), HasSubstr("not a numeric IPv4 address"));
}

TEST(UdpEndpoint, DatagramArrivesWholeWithItsSender) {
  UdpSocket a(parse_endpoint("127.0.0.1:0", true)), b(parse_endpoint("127.0.0.1:0", true));
  EXPECT_FALSE(b.receive(std::chrono::milliseconds(1)));
  std::vector<std::uint8_t> payload(3000);
  for (std::size_t k = 0; k < payload.size(); ++k) payload[k] = std::uint8_t(k * 7);
  ASSERT_TRUE(a.send_to(b.local(), payload));
  const auto d = b.receive(std::chrono::milliseconds(1000));
  ASSERT_TRUE(d);
  EXPECT_EQ(d->bytes, payload);
  EXPECT_EQ(d->from, a.local());
}

}  // namespace udp_endpoint_test
}  // namespace ambid::rig
