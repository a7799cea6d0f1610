// The trend store as the diagnostics daemon uses it: one transaction per window of the seven
// monitored parameters. Reports the write rate and the disk use per window, from which the
// README's disk use per bearing-day follows (windows per day x bytes per window), and the
// same after hourly aggregation.
#include <benchmark/benchmark.h>
#include <sqlite3.h>
#include <unistd.h>

#include <filesystem>

#include "diagnostics/trend_store.hpp"

namespace {

namespace fs = std::filesystem;
using namespace ambid::diag;

const char* const kParameters[] = {"R1", "R2", "kw1", "kw2", "kr1", "kr2", "ks"};

std::uintmax_t store_bytes(const fs::path& path) {
  std::uintmax_t bytes = 0;
  for (const char* suffix : {"", "-wal"})
    if (fs::exists(path.string() + suffix)) bytes += fs::file_size(path.string() + suffix);
  return bytes;
}

void BM_TrendStoreWindows(benchmark::State& state) {
  const fs::path path = fs::temp_directory_path() / ("ambid-trend-bench-" + std::to_string(::getpid()) + ".sqlite");
  const double window_seconds = 1.0;
  std::int64_t windows = 0;
  {
    TrendStore store(path);
    for (auto _ : state) {
      Batch batch;
      EstimateWindow w;
      w.time = double(windows++) * window_seconds;
      w.plant_id = "bearing-1";
      for (const char* p : kParameters) w.estimates.push_back({p, 17.5 + 1e-3 * double(windows % 97), 0.05});
      batch.windows.push_back(std::move(w));
      store.write(batch);
    }
  }  // closed: the WAL checkpointed into the file
  const double per_window = double(store_bytes(path)) / double(windows);
  {
    TrendStore store(path);
    RetentionPolicy hourly;
    hourly.aggregate_after = 0.0;
    store.apply_retention(hourly, double(windows) * window_seconds + 3600.0);
  }
  // The daemon reuses freed pages; VACUUM here only to measure what the aggregates occupy.
  sqlite3* db = nullptr;
  sqlite3_open(path.c_str(), &db);
  sqlite3_exec(db, "VACUUM", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  const double days = double(windows) * window_seconds / 86400.0;
  state.counters["kB_per_bearing_day_aggregated"] = double(store_bytes(path)) / days / 1e3;
  state.counters["bytes_per_window"] = per_window;
  state.counters["MB_per_bearing_day_1s_windows"] = per_window * 86400.0 / 1e6;
  state.counters["MB_per_bearing_day_0.25s_windows"] = 4.0 * per_window * 86400.0 / 1e6;
  state.counters["windows_per_s"] = benchmark::Counter(double(windows), benchmark::Counter::kIsRate);
  for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(path.string() + suffix);
}
BENCHMARK(BM_TrendStoreWindows)->Iterations(20000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
