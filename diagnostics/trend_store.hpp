#pragma once
// The trend store: one SQLite file per deployment holding every identified physical parameter
// (time, plant, source, parameter, value, sigma), the baselines and the alerts raised.
//
// Durability: the file is in WAL mode with synchronous=FULL. In WAL mode, NORMAL already
// keeps the file consistent through a crash of the process, but after a power loss or an OS
// crash it may lose the last transactions that were reported committed (the WAL is synced only
// at checkpoints). FULL syncs the WAL at every commit, so a commit that returned is on disk:
// "nothing lost on crash" holds for power loss too. Its price, one fsync per commit, is small
// because writes come in batches (one transaction per write(), a window of estimates every
// second or slower in the daemon, thousands of windows per transaction offline).
//
// Concurrency: one writer (the daemon or `ambid diagnose`) and any number of readers in other
// processes (open read_only). WAL lets readers see the last committed state while the writer
// writes; a reader never sees part of a batch. Waits for a lock up to 5 s (busy timeout)
// before failing. One TrendStore object must be used by one thread at a time.
//
// Schema versioned with PRAGMA user_version (kSchemaVersion); opening a newer file, or a
// read_only open of an older or empty one, is refused.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "diagnostics/alert.hpp"
#include "diagnostics/estimate.hpp"
#include "diagnostics/monitor/baseline.hpp"

namespace ambid::diag {

inline constexpr int kSchemaVersion = 2;  // 2: estimate_aggregates

struct StoredEstimate {
  double time = 0.0;
  std::string plant_id;
  Source source = Source::sim;
  std::string parameter;
  double value = 0.0;
  double sigma = 0.0;
};

struct BaselineRecord {
  std::string plant_id;
  std::string parameter;
  Baseline baseline;
  double time = 0.0;  // when it was learned or given
};

// What one write() stores atomically.
struct Batch {
  std::vector<EstimateWindow> windows;
  std::vector<Alert> alerts;
  std::vector<BaselineRecord> baselines;  // replace any baseline of the same plant and parameter
};

// Per-window estimates older than now - aggregate_after are folded into one row per plant,
// parameter, source and bucket of `bucket` seconds (count, sums for the mean and scatter, mean
// sigma, extremes) and removed. Rows (estimates, aggregates and alerts) older than now - max_age
// are removed; of each (plant, parameter) series only the newest max_rows_per_series estimates
// are kept. An empty limit keeps all.
struct RetentionPolicy {
  std::optional<double> aggregate_after;  // seconds
  double bucket = 3600.0;                 // seconds
  std::optional<double> max_age;          // seconds
  std::optional<std::int64_t> max_rows_per_series;
  // aggregate_after and max_age >= 0 and finite, bucket > 0 and finite, max_rows_per_series >= 0.
  void validate() const;
};

struct RetentionReport {
  std::int64_t estimates_aggregated = 0;  // per-window rows folded into buckets
  std::int64_t estimates_removed = 0;     // per-window rows removed without aggregation
  std::int64_t aggregates_removed = 0;
  std::int64_t alerts_removed = 0;
};

// The estimates of one bucket of time [start, start + seconds).
struct AggregatedEstimate {
  double start = 0.0, seconds = 0.0;
  std::string plant_id;
  Source source = Source::sim;
  std::string parameter;
  std::int64_t windows = 0;
  double mean = 0.0;
  double spread = 0.0;      // standard deviation of the window values
  double mean_sigma = 0.0;  // the windows' reported sigma, averaged
  double min = 0.0, max = 0.0;
};

enum class OpenMode { read_write, read_only };

class TrendStore {
 public:
  // read_write creates the file and its schema when absent.
  explicit TrendStore(const std::filesystem::path& file, OpenMode mode = OpenMode::read_write);
  ~TrendStore();
  TrendStore(const TrendStore&) = delete;
  TrendStore& operator=(const TrendStore&) = delete;

  // Stores the whole batch in one transaction, or nothing (Error on invalid input or sqlite
  // failure).
  void write(const Batch& batch);

  // Estimates of one parameter of one plant with from <= time <= to, oldest first.
  std::vector<StoredEstimate> history(const std::string& plant_id, const std::string& parameter,
                                      double from = -std::numeric_limits<double>::infinity(),
                                      double to = std::numeric_limits<double>::infinity()) const;
  // The newest `limit` alerts, newest first; of one plant when plant_id is given.
  // Aggregated buckets of one parameter of one plant starting in [from, to], oldest first.
  std::vector<AggregatedEstimate> aggregates(const std::string& plant_id, const std::string& parameter,
                                             double from = -std::numeric_limits<double>::infinity(),
                                             double to = std::numeric_limits<double>::infinity()) const;
  std::vector<Alert> latest_alerts(std::size_t limit, const std::optional<std::string>& plant_id = {}) const;
  std::optional<Baseline> baseline(const std::string& plant_id, const std::string& parameter) const;
  // Removes every baseline of the plant (another bearing under the same plant id: they are
  // learned again); returns how many. History and alerts stay.
  std::size_t forget_baselines(const std::string& plant_id);

  // Applies the policy in one transaction.
  RetentionReport apply_retention(const RetentionPolicy& policy, double now);

  // PRAGMA integrity_check: "ok", or the first problem sqlite found.
  std::string integrity_check() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ambid::diag
