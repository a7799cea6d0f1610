// The rig emulator as a hostile peer finds it (issue 18): a NACK quoting an absurd amplitude
// still fits its frame and the board runs on; a second local socket cannot take the session
// while the gateway holds its lease, and gets it once the lease has lapsed.
#include "services/rig/rig_emulator.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

#include "services/rig/rig_frame.hpp"

namespace ambid::rig {
namespace rig_emulator_test {

using namespace std::chrono_literals;

// An emulator on a free loopback port, served by a thread for the test's lifetime.
class RunningEmulator {
 public:
  explicit RunningEmulator(double lease) {
    EmulatorOptions o;
    o.listen = parse_endpoint("127.0.0.1:0", true);
    o.scenario.duration = 0.5;
    o.max_amplitude = 1.0;
    o.lease = lease;
    thread_ = std::thread([this, o] {
      run_emulator(
          o, [this] { return running_.load(); }, [this](const std::string& line) { log(line); });
    });
    const auto end = std::chrono::steady_clock::now() + 30s;  // the first record is simulated first
    while (std::chrono::steady_clock::now() < end && !endpoint_) std::this_thread::sleep_for(10ms);
    if (!endpoint_) ADD_FAILURE() << "the emulator did not start listening";
  }
  ~RunningEmulator() {
    running_ = false;
    thread_.join();
  }
  Endpoint endpoint() const {
    std::lock_guard lock(mutex_);
    return endpoint_.value_or(Endpoint{});
  }

 private:
  void log(const std::string& line) {
    const std::string prefix = "rig emulator listening on ";
    if (line.rfind(prefix, 0) != 0) return;
    std::lock_guard lock(mutex_);
    endpoint_ = parse_endpoint(line.substr(prefix.size(), line.find(',') - prefix.size()));
  }

  std::atomic<bool> running_{true};
  mutable std::mutex mutex_;
  std::optional<Endpoint> endpoint_;
  std::thread thread_;
};

// A gateway socket: sends frames, collects the decoded frames it receives.
struct Peer {
  UdpSocket socket{parse_endpoint("127.0.0.1:0", true)};
  std::uint32_t seq = 0;

  void send(const Endpoint& to, const Payload& p) { socket.send_to(to, encode(Frame{seq++, p})); }

  // The first frame whose payload holds T within `wait`.
  template <typename T>
  std::optional<T> await(std::chrono::milliseconds wait) {
    const auto end = std::chrono::steady_clock::now() + wait;
    while (std::chrono::steady_clock::now() < end) {
      auto d = socket.receive(20ms);
      if (!d) continue;
      const Decoded decoded = decode(d->bytes);
      if (decoded.frame)
        if (const auto* t = std::get_if<T>(&decoded.frame->payload)) return *t;
    }
    return std::nullopt;
  }
};

TEST(RigEmulator, AnAbsurdAmplitudeIsRefusedInAFrameThatFitsAndTheBoardRunsOn) {
  RunningEmulator emulator(2.0);
  Peer gateway;
  gateway.send(emulator.endpoint(), Hello{"test gateway"});
  ASSERT_TRUE(gateway.await<RigStatus>(5000ms));

  gateway.send(emulator.endpoint(), Excite{1, "prbs", 1e300, 0.0, 0.0});
  const std::optional<ExciteReply> nack = gateway.await<ExciteReply>(5000ms);
  ASSERT_TRUE(nack);
  EXPECT_EQ(nack->command, 1u);
  EXPECT_FALSE(nack->accepted);
  EXPECT_LE(nack->reason.size(), kMaxText);
  EXPECT_EQ(nack->reason.substr(0, 11), "amplitude 1");

  gateway.send(emulator.endpoint(), Excite{2, "prbs", 0.5, 0.0, 0.0});
  const std::optional<ExciteReply> ack = gateway.await<ExciteReply>(5000ms);
  ASSERT_TRUE(ack) << "the emulator stopped answering after the NACK";
  EXPECT_EQ(ack->command, 2u);
  EXPECT_TRUE(ack->accepted) << ack->reason;
}

TEST(RigEmulator, ASecondSocketCannotTakeTheSessionWhileTheLeaseHolds) {
  RunningEmulator emulator(0.6);
  Peer gateway, intruder;
  gateway.send(emulator.endpoint(), Hello{"test gateway"});
  ASSERT_TRUE(gateway.await<RigStatus>(5000ms));

  // While the gateway keeps its lease, the intruder's HELLO and EXCITE get nothing, and the
  // samples keep flowing to the gateway.
  bool intruder_answered = false, gateway_fed = false;
  for (int k = 0; k < 6; ++k) {
    gateway.send(emulator.endpoint(), KeepAlive{});
    intruder.send(emulator.endpoint(), Hello{"intruder"});
    intruder.send(emulator.endpoint(), Excite{1, "prbs", 0.9, 0.0, 0.0});
    intruder_answered = intruder_answered || intruder.await<RigStatus>(200ms).has_value();
    gateway_fed = gateway_fed || gateway.await<SampleBatch>(100ms).has_value();
  }
  EXPECT_FALSE(intruder_answered);
  EXPECT_TRUE(gateway_fed);

  // The gateway falls silent; after its lease the next HELLO holds the session.
  std::this_thread::sleep_for(1000ms);
  intruder.send(emulator.endpoint(), Hello{"new gateway"});
  EXPECT_TRUE(intruder.await<RigStatus>(2000ms));
}

}  // namespace rig_emulator_test
}  // namespace ambid::rig
