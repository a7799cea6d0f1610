// A writer killed with SIGKILL in the middle of writing: on reopening, every transaction that
// committed is there in full, nothing of the one in flight, and the file is consistent.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <random>
#include <string>
#include <thread>

#include "diagnostics/synthetic_estimates.hpp"
#include "diagnostics/trend_store.hpp"

namespace ambid::diag {
namespace trend_store_crash_test {

constexpr int kWindows = 200;  // per batch: 200 windows x 7 parameters + 1 alert, one transaction

double value_of(std::size_t parameter, double time) {
  return testing::nominal_parameters()[parameter].second * (1.0 + 1e-6 * time);
}

Batch make_batch(std::int64_t b) {
  Batch batch;
  for (int j = 0; j < kWindows; ++j) {
    EstimateWindow w;
    w.time = static_cast<double>(b * kWindows + j);
    w.plant_id = "bearing-A";
    w.source = Source::rig;
    for (std::size_t p = 0; p < testing::nominal_parameters().size(); ++p)
      w.estimates.push_back({testing::nominal_parameters()[p].first, value_of(p, w.time), 0.01});
    batch.windows.push_back(std::move(w));
  }
  Alert a;
  a.time = static_cast<double>(b);
  a.plant_id = "bearing-A";
  a.level = Level::warn;
  a.fault = "coil_resistance";
  a.channel = 1;
  a.parameter = "R1";
  a.value = 17.6;
  a.baseline = 17.5;
  a.message = "batch " + std::to_string(b);
  batch.alerts.push_back(a);
  return batch;
}

// Writes batches first, first + 1, ... forever, reporting each commit on `report`.
[[noreturn]] void writer(const std::filesystem::path& path, std::int64_t first, int report) {
  try {
    TrendStore store(path);
    for (std::int64_t b = first;; ++b) {
      store.write(make_batch(b));
      if (write(report, &b, sizeof b) != sizeof b) _exit(3);
    }
  } catch (...) {
    _exit(2);
  }
}

// Batches in the store, after checking that they are complete and exactly as written.
std::int64_t check_store(const std::filesystem::path& path) {
  TrendStore store(path);
  EXPECT_EQ(store.integrity_check(), "ok");
  std::size_t rows = 0;
  for (std::size_t p = 0; p < testing::nominal_parameters().size(); ++p) {
    const std::vector<StoredEstimate> h = store.history("bearing-A", testing::nominal_parameters()[p].first);
    if (p == 0) rows = h.size();
    EXPECT_EQ(h.size(), rows) << "parameters differ in count";
    for (std::size_t i = 0; i < h.size(); ++i) {
      if (h[i].time != static_cast<double>(i) || h[i].value != value_of(p, h[i].time)) {
        ADD_FAILURE() << "row " << i << " of " << testing::nominal_parameters()[p].first << " is wrong";
        break;
      }
    }
  }
  EXPECT_EQ(rows % kWindows, 0u) << "a partial batch";
  const auto batches = static_cast<std::int64_t>(rows / kWindows);
  EXPECT_EQ(store.latest_alerts(100000).size(), static_cast<std::size_t>(batches));
  return batches;
}

TEST(TrendStoreCrash, KilledWriterLosesNoCommittedBatch) {
  const auto path = testing::fresh_store_path("crash");
  std::mt19937_64 rng(41);
  std::uniform_int_distribution<int> delay_us(0, 30000);
  std::int64_t batches = 0;
  for (int round = 0; round < 6; ++round) {
    int report[2];
    ASSERT_EQ(pipe(report), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      close(report[0]);
      writer(path, batches, report[1]);
    }
    close(report[1]);
    // Let it commit a few batches, then kill it at a random moment (a batch takes several ms
    // to write, most of it inside the transaction).
    std::int64_t last = -1;
    for (int seen = 0; seen < 3; ++seen) ASSERT_EQ(read(report[0], &last, sizeof last), sizeof last);
    std::this_thread::sleep_for(std::chrono::microseconds(delay_us(rng)));
    ASSERT_EQ(kill(child, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "the writer ended on its own";
    while (read(report[0], &last, sizeof last) == sizeof last) {
    }
    close(report[0]);

    const std::int64_t stored = check_store(path);
    // Every reported commit is there; at most the batch in flight committed unreported.
    EXPECT_GE(stored, last + 1) << "round " << round;
    EXPECT_LE(stored, last + 2) << "round " << round;
    batches = stored;
  }
  EXPECT_GE(batches, 18);
}

}  // namespace trend_store_crash_test
}  // namespace ambid::diag
