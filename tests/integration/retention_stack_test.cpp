// Issue 18: the diagnostics daemon applies its trend-store retention while it runs. With
// per-window estimates kept for 20 s of plant time, 5 s aggregates and a pass every 5 s, a
// stack run of ~100 s of plant time leaves per-window estimates only for the last ~25 s and
// the older windows folded into aggregates whose counts add up to the models the daemon took
// and whose means are the nominal R1.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "diagnostics/trend_store.hpp"
#include "stack_support.hpp"

namespace ambid::testing {
namespace retention_stack_test {

using ::testing::HasSubstr;

constexpr double kDay = 86400.0;
constexpr double kKeepWindows = 20.0;  // s of plant time
constexpr double kBucket = 5.0;
constexpr double kPeriod = 5.0;

TEST(RetentionStack, TheDaemonAggregatesWindowsOlderThanItsRetention) {
  Stack stack("stack_retention", 211);
  std::ofstream(stack.dir() / "diagnostics.json")
      << R"({"store": ")" << stack.store().string()
      << R"(", "learning_windows": 40, "persist_windows": 20, "stale_timeout": 1.0, "silence": 2.0,)"
      << R"( "keep_windows_days": )" << kKeepWindows / kDay << R"(, "aggregate_bucket": )" << kBucket
      << R"(, "retention_period": )" << kPeriod << "}";
  stack.start("diagnostics", {"--metrics-port", "19211"});
  for (const char* d : {"identifier", "plant"}) stack.start(d);
  std::this_thread::sleep_for(std::chrono::seconds(12));  // ~100 s of plant time at 10x
  ASSERT_TRUE(stack.running("diagnostics")) << stack.log("diagnostics");
  stack.kill("plant");  // the store stops moving
  std::this_thread::sleep_for(std::chrono::seconds(1));
  EXPECT_THAT(stack.log("diagnostics"), HasSubstr("window estimates aggregated"));

  const diag::TrendStore store(stack.store(), diag::OpenMode::read_only);
  const auto windows = store.history("bearing-1", "R1");
  const auto aggregates = store.aggregates("bearing-1", "R1");
  ASSERT_FALSE(windows.empty()) << stack.log("diagnostics");
  ASSERT_GE(aggregates.size(), 5u) << stack.log("diagnostics");
  const double newest = windows.back().time;
  ASSERT_GT(newest, 60.0) << "the stack ran too little plant time";
  // The last pass ran less than one period before the newest model and folds whole buckets:
  // nothing older than kKeepWindows + kPeriod + kBucket (+ a window) is still stored per window.
  EXPECT_GT(windows.front().time, newest - kKeepWindows - kPeriod - kBucket - 0.5);
  // Aggregates cover the time before the per-window rows, in buckets of kBucket, with the
  // windows they hold (3 per second of plant time: 0.25 s windows after a 0.25 s settle per
  // 1 s record, ~15 per bucket) and their nominal R1 17.5 ohm.
  std::int64_t folded = 0;
  for (const diag::AggregatedEstimate& a : aggregates) {
    EXPECT_DOUBLE_EQ(a.seconds, kBucket);
    EXPECT_LE(a.start + a.seconds, windows.front().time + kBucket);
    EXPECT_GE(a.windows, 1);
    EXPECT_LE(a.windows, 16);
    EXPECT_NEAR(a.mean, 17.5, 0.05 * 17.5);
    EXPECT_LE(a.min, a.mean);
    EXPECT_GE(a.max, a.mean);
    folded += a.windows;
  }
  // Every window the daemon took went into an aggregate or is still stored: none lost. (How
  // many there are depends on whether this machine lets the identifier keep up at 10x.)
  const std::string metrics = http_get(19211, "/metrics");
  const double taken = metric(metrics, "ambid_messages_received_total{role=\"diagnostics\"}") -
                       metric(metrics, "ambid_messages_rejected_total{role=\"diagnostics\"}");
  EXPECT_EQ(double(folded + std::int64_t(windows.size())), taken) << metrics;
}

}  // namespace retention_stack_test
}  // namespace ambid::testing
