// `ambid alerts --follow` across a reconnect of the alerts' writer (issue 18): a restarted
// diagnostics daemon publishes its current alerts again, and each must be printed once.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <thread>

#include "services/bus/make_bus.hpp"
#include "stack_support.hpp"

namespace ambid::testing {
namespace alerts_follow_test {

using namespace std::chrono_literals;

bus::Alert alert(const std::string& parameter, bus::AlertLevel level, double time) {
  bus::Alert a;
  a.plant_id = "bearing-1";
  a.fault = "coil_resistance";
  a.channel = 1;
  a.time = time;
  a.level = level;
  a.parameter = parameter;
  a.value = 21.0;
  a.baseline = 17.5;
  a.message = "coil 1 resistance +20 %";
  return a;
}

std::size_t occurrences(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST(AlertsFollow, EachAlertIsPrintedOnceAcrossAWriterReconnect) {
  Stack stack("alerts_follow", 186);
  auto follow =
      std::async(std::launch::async, [&] { return stack.ambid("alerts --follow --until WARN:done --timeout 30"); });
  {
    auto b = bus::make_bus("cyclone", 186);
    auto writer = b->writer<bus::Alert>();
    writer->write(alert("R1", bus::AlertLevel::error, 12.5));
    std::this_thread::sleep_for(3s);       // the follower has printed it
  }                                        // the daemon goes away ...
  auto b = bus::make_bus("fastdds", 186);  // ... and comes back, with its current alerts
  auto writer = b->writer<bus::Alert>();
  writer->write(alert("R1", bus::AlertLevel::error, 12.5));
  writer->write(alert("R2", bus::AlertLevel::warn, 13.0));
  std::this_thread::sleep_for(2s);
  writer->write(alert("done", bus::AlertLevel::warn, 14.0));
  const CommandResult r = follow.get();
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(occurrences(r.output, "ERROR  bearing-1  R1"), 1u) << r.output;
  EXPECT_EQ(occurrences(r.output, "WARN   bearing-1  R2"), 1u) << r.output;
}

}  // namespace alerts_follow_test
}  // namespace ambid::testing
