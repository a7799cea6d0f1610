#include "diagnostics/trend_store.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string_view>

#include "core/error.hpp"
#include "diagnostics/monitor/sqlite.hpp"

namespace ambid::diag {
namespace {

// migrations[v] takes the schema from version v to v + 1.
constexpr std::string_view kMigrations[] = {
    R"sql(
CREATE TABLE estimates (
  id        INTEGER PRIMARY KEY,
  time      REAL NOT NULL,
  plant_id  TEXT NOT NULL,
  source    TEXT NOT NULL CHECK (source IN ('sim', 'replay', 'rig')),
  parameter TEXT NOT NULL,
  value     REAL NOT NULL,
  sigma     REAL NOT NULL CHECK (sigma >= 0)
);
CREATE INDEX estimates_series ON estimates (plant_id, parameter, time);
CREATE INDEX estimates_time ON estimates (time);
CREATE TABLE alerts (
  id        INTEGER PRIMARY KEY,
  time      REAL NOT NULL,
  plant_id  TEXT NOT NULL,
  level     TEXT NOT NULL CHECK (level IN ('OK', 'WARN', 'ERROR', 'STALE')),
  fault     TEXT NOT NULL,
  channel   INTEGER,
  parameter TEXT NOT NULL,
  value     REAL NOT NULL,
  baseline  REAL,
  message   TEXT NOT NULL
);
CREATE INDEX alerts_time ON alerts (time);
CREATE INDEX alerts_plant_time ON alerts (plant_id, time);
CREATE TABLE baselines (
  plant_id       TEXT NOT NULL,
  parameter      TEXT NOT NULL,
  mean           REAL NOT NULL,
  extra_spread   REAL NOT NULL,
  mean_sigma     REAL NOT NULL,
  reported_sigma REAL NOT NULL,
  windows        INTEGER NOT NULL,
  origin         TEXT NOT NULL CHECK (origin IN ('learned', 'given')),
  time           REAL NOT NULL,
  PRIMARY KEY (plant_id, parameter)
);
)sql",
    R"sql(
CREATE TABLE estimate_aggregates (
  plant_id         TEXT NOT NULL,
  parameter        TEXT NOT NULL,
  source           TEXT NOT NULL CHECK (source IN ('sim', 'replay', 'rig')),
  bucket_start     REAL NOT NULL,
  bucket_seconds   REAL NOT NULL CHECK (bucket_seconds > 0),
  windows          INTEGER NOT NULL CHECK (windows > 0),
  value_sum        REAL NOT NULL,
  value_square_sum REAL NOT NULL,
  sigma_sum        REAL NOT NULL,
  value_min        REAL NOT NULL,
  value_max        REAL NOT NULL,
  PRIMARY KEY (plant_id, parameter, source, bucket_start)
);
)sql",
};
static_assert(std::size(kMigrations) == kSchemaVersion);

constexpr int kBusyTimeoutMs = 5000;

void migrate(sqlite::Connection& db) {
  sqlite::Transaction tx(db, "schema migration");
  const std::int64_t version = db.query_int("PRAGMA user_version", "read schema version");
  if (version > kSchemaVersion)
    throw Error("trend store " + db.path() + ": schema version " + std::to_string(version) +
                " is newer than this program's " + std::to_string(kSchemaVersion));
  for (std::int64_t v = version; v < kSchemaVersion; ++v)
    db.exec(kMigrations[v], "migrate schema to version " + std::to_string(v + 1));
  if (version != kSchemaVersion)
    db.exec("PRAGMA user_version = " + std::to_string(kSchemaVersion), "write schema version");
  tx.commit();
}

void require_finite(double x, const std::string& what) {
  if (!std::isfinite(x)) throw Error("trend store: " + what + " is not finite");
}

void validate(const Batch& batch) {
  for (const EstimateWindow& w : batch.windows) w.validate();
  for (const Alert& a : batch.alerts) {
    if (a.plant_id.empty() || a.fault.empty() || a.parameter.empty())
      throw Error("trend store: alert at t=" + std::to_string(a.time) + " lacks a plant id, fault or parameter");
    require_finite(a.time, "alert time");
    require_finite(a.value, "alert value of " + a.parameter);
    if (a.baseline) require_finite(*a.baseline, "alert baseline of " + a.parameter);
  }
  for (const BaselineRecord& b : batch.baselines) {
    if (b.plant_id.empty() || b.parameter.empty()) throw Error("trend store: baseline lacks a plant id or parameter");
    require_finite(b.time, "baseline time of " + b.parameter);
    b.baseline.validate();
  }
}

Alert read_alert(const sqlite::Statement::Run& row) {
  Alert a;
  a.time = row.column_double(0);
  a.plant_id = row.column_text(1);
  a.level = parse_level(row.column_text(2));
  a.fault = row.column_text(3);
  if (!row.column_is_null(4)) a.channel = static_cast<int>(row.column_int(4));
  a.parameter = row.column_text(5);
  a.value = row.column_double(6);
  if (!row.column_is_null(7)) a.baseline = row.column_double(7);
  a.message = row.column_text(8);
  return a;
}

// Opens the connection and brings it to the current schema before any statement is prepared.
struct Connected {
  Connected(const std::string& path, OpenMode mode) : db(path, mode == OpenMode::read_only) {
    db.set_busy_timeout(kBusyTimeoutMs);
    if (mode == OpenMode::read_write) {
      const std::string journal = db.query_text("PRAGMA journal_mode = WAL", "set WAL journal mode");
      if (journal != "wal")
        throw Error("trend store " + path + ": set WAL journal mode: sqlite kept journal mode '" + journal + "'");
      db.exec("PRAGMA synchronous = FULL", "set synchronous FULL");
      migrate(db);
    } else {
      const std::int64_t version = db.query_int("PRAGMA user_version", "read schema version");
      if (version != kSchemaVersion)
        throw Error("trend store " + path + ": schema version " + std::to_string(version) + ", expected " +
                    std::to_string(kSchemaVersion) + " (a read-only open does not migrate)");
    }
  }
  sqlite::Connection db;
};

constexpr std::string_view kAlertColumns = "time, plant_id, level, fault, channel, parameter, value, baseline, message";

std::string select_alerts(std::string_view where) {
  return "SELECT " + std::string(kAlertColumns) + " FROM alerts " + std::string(where) +
         " ORDER BY time DESC, id DESC LIMIT ?";
}

}  // namespace

void RetentionPolicy::validate() const {
  if (max_age && (!(*max_age >= 0.0) || !std::isfinite(*max_age)))
    throw Error("retention: max_age must be non-negative and finite, got " + std::to_string(*max_age));
  if (aggregate_after && (!(*aggregate_after >= 0.0) || !std::isfinite(*aggregate_after)))
    throw Error("retention: aggregate_after must be non-negative and finite, got " + std::to_string(*aggregate_after));
  if (!(bucket > 0.0) || !std::isfinite(bucket))
    throw Error("retention: bucket must be positive and finite, got " + std::to_string(bucket));
  if (max_rows_per_series && *max_rows_per_series < 0)
    throw Error("retention: max_rows_per_series must be non-negative, got " + std::to_string(*max_rows_per_series));
}

struct TrendStore::Impl {
  Impl(const std::string& path, OpenMode mode) : connected(path, mode) {}

  Connected connected;
  sqlite::Connection& db = connected.db;
  sqlite::Statement insert_estimate{
      db, "INSERT INTO estimates (time, plant_id, source, parameter, value, sigma) VALUES (?, ?, ?, ?, ?, ?)",
      "insert estimate"};
  sqlite::Statement insert_alert{
      db, "INSERT INTO alerts (" + std::string(kAlertColumns) + ") VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)", "insert alert"};
  sqlite::Statement replace_baseline{
      db,
      "INSERT OR REPLACE INTO baselines (plant_id, parameter, mean, extra_spread, mean_sigma, reported_sigma, "
      "windows, origin, time) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)",
      "store baseline"};
  sqlite::Statement select_history{db,
                                   "SELECT time, plant_id, source, parameter, value, sigma FROM estimates "
                                   "WHERE plant_id = ? AND parameter = ? AND time >= ? AND time <= ? ORDER BY time, id",
                                   "read history"};
  sqlite::Statement select_alerts_all{db, select_alerts(""), "read alerts"};
  sqlite::Statement select_alerts_plant{db, select_alerts("WHERE plant_id = ?"), "read alerts of a plant"};
  sqlite::Statement select_baseline{
      db,
      "SELECT mean, extra_spread, mean_sigma, reported_sigma, windows, origin FROM baselines "
      "WHERE plant_id = ? AND parameter = ?",
      "read baseline"};
  sqlite::Statement delete_baselines{db, "DELETE FROM baselines WHERE plant_id = ?", "remove baselines"};
  sqlite::Statement delete_old_estimates{db, "DELETE FROM estimates WHERE time < ?", "remove old estimates"};
  // Buckets are whole multiples of the bucket length; a bucket already stored (a run of
  // retention that cut through it) is merged, not replaced.
  sqlite::Statement fold_estimates{
      db,
      "INSERT INTO estimate_aggregates (plant_id, parameter, source, bucket_start, bucket_seconds, windows, "
      "value_sum, value_square_sum, sigma_sum, value_min, value_max) "
      "SELECT plant_id, parameter, source, bucket * ?1, ?1, COUNT(*), SUM(value), SUM(value * value), SUM(sigma), "
      "MIN(value), MAX(value) FROM (SELECT *, CAST(time / ?1 AS INTEGER) - (time < 0 AND time / ?1 <> "
      "CAST(time / ?1 AS INTEGER)) AS bucket FROM estimates WHERE time < ?2) "
      "GROUP BY plant_id, parameter, source, bucket "
      "ON CONFLICT (plant_id, parameter, source, bucket_start) DO UPDATE SET windows = windows + excluded.windows, "
      "value_sum = value_sum + excluded.value_sum, value_square_sum = value_square_sum + excluded.value_square_sum, "
      "sigma_sum = sigma_sum + excluded.sigma_sum, value_min = MIN(value_min, excluded.value_min), "
      "value_max = MAX(value_max, excluded.value_max)",
      "aggregate old estimates"};
  sqlite::Statement delete_old_aggregates{
      db, "DELETE FROM estimate_aggregates WHERE bucket_start + bucket_seconds <= ?", "remove old aggregates"};
  sqlite::Statement select_aggregates{
      db,
      "SELECT bucket_start, bucket_seconds, plant_id, source, parameter, windows, value_sum, value_square_sum, "
      "sigma_sum, value_min, value_max FROM estimate_aggregates WHERE plant_id = ? AND parameter = ? AND "
      "bucket_start >= ? AND bucket_start <= ? ORDER BY bucket_start, source",
      "read aggregates"};
  sqlite::Statement delete_old_alerts{db, "DELETE FROM alerts WHERE time < ?", "remove old alerts"};
  sqlite::Statement delete_excess_estimates{
      db,
      "DELETE FROM estimates WHERE id IN (SELECT id FROM (SELECT id, ROW_NUMBER() OVER (PARTITION BY plant_id, "
      "parameter ORDER BY time DESC, id DESC) AS newer FROM estimates) WHERE newer > ?)",
      "remove excess estimates"};
};

TrendStore::TrendStore(const std::filesystem::path& file, OpenMode mode)
    : impl_(std::make_unique<Impl>(file.string(), mode)) {}

TrendStore::~TrendStore() = default;

void TrendStore::write(const Batch& batch) {
  validate(batch);
  sqlite::Transaction tx(impl_->db, "write batch");
  for (const EstimateWindow& w : batch.windows) {
    for (const ParameterEstimate& e : w.estimates) {
      auto run = impl_->insert_estimate.run();
      run.bind(1, w.time).bind(2, w.plant_id).bind(3, to_string(w.source)).bind(4, e.parameter);
      run.bind(5, e.value).bind(6, e.sigma).execute();
    }
  }
  for (const Alert& a : batch.alerts) {
    auto run = impl_->insert_alert.run();
    run.bind(1, a.time).bind(2, a.plant_id).bind(3, to_string(a.level)).bind(4, a.fault);
    run.bind(5, a.channel ? std::optional<std::int64_t>(*a.channel) : std::nullopt);
    run.bind(6, a.parameter).bind(7, a.value).bind(8, a.baseline).bind(9, a.message).execute();
  }
  for (const BaselineRecord& r : batch.baselines) {
    const Baseline& b = r.baseline;
    auto run = impl_->replace_baseline.run();
    run.bind(1, r.plant_id).bind(2, r.parameter).bind(3, b.mean).bind(4, b.extra_spread).bind(5, b.mean_sigma);
    run.bind(6, b.reported_sigma).bind(7, static_cast<std::int64_t>(b.windows)).bind(8, to_string(b.origin));
    run.bind(9, r.time).execute();
  }
  tx.commit();
}

std::vector<StoredEstimate> TrendStore::history(const std::string& plant_id, const std::string& parameter, double from,
                                                double to) const {
  auto run = impl_->select_history.run();
  run.bind(1, plant_id).bind(2, parameter).bind(3, from).bind(4, to);
  std::vector<StoredEstimate> rows;
  while (run.step())
    rows.push_back({run.column_double(0), run.column_text(1), parse_source(run.column_text(2)), run.column_text(3),
                    run.column_double(4), run.column_double(5)});
  return rows;
}

std::vector<AggregatedEstimate> TrendStore::aggregates(const std::string& plant_id, const std::string& parameter,
                                                       double from, double to) const {
  auto run = impl_->select_aggregates.run();
  run.bind(1, plant_id).bind(2, parameter).bind(3, from).bind(4, to);
  std::vector<AggregatedEstimate> rows;
  while (run.step()) {
    AggregatedEstimate a;
    a.start = run.column_double(0);
    a.seconds = run.column_double(1);
    a.plant_id = run.column_text(2);
    a.source = parse_source(run.column_text(3));
    a.parameter = run.column_text(4);
    a.windows = run.column_int(5);
    const double n = double(a.windows);
    a.mean = run.column_double(6) / n;
    a.spread = std::sqrt(std::max(0.0, run.column_double(7) / n - a.mean * a.mean) * n / std::max(1.0, n - 1.0));
    a.mean_sigma = run.column_double(8) / n;
    a.min = run.column_double(9);
    a.max = run.column_double(10);
    rows.push_back(std::move(a));
  }
  return rows;
}

std::vector<Alert> TrendStore::latest_alerts(std::size_t limit, const std::optional<std::string>& plant_id) const {
  sqlite::Statement& statement = plant_id ? impl_->select_alerts_plant : impl_->select_alerts_all;
  auto run = statement.run();
  int index = 1;
  if (plant_id) run.bind(index++, *plant_id);
  run.bind(index, static_cast<std::int64_t>(limit));
  std::vector<Alert> alerts;
  while (run.step()) alerts.push_back(read_alert(run));
  return alerts;
}

std::optional<Baseline> TrendStore::baseline(const std::string& plant_id, const std::string& parameter) const {
  auto run = impl_->select_baseline.run();
  run.bind(1, plant_id).bind(2, parameter);
  if (!run.step()) return std::nullopt;
  Baseline b;
  b.mean = run.column_double(0);
  b.extra_spread = run.column_double(1);
  b.mean_sigma = run.column_double(2);
  b.reported_sigma = run.column_double(3);
  b.windows = static_cast<std::size_t>(run.column_int(4));
  b.origin = parse_baseline_origin(run.column_text(5));
  b.validate();
  return b;
}

std::size_t TrendStore::forget_baselines(const std::string& plant_id) {
  impl_->delete_baselines.run().bind(1, plant_id).execute();
  return std::size_t(impl_->db.changes());
}

RetentionReport TrendStore::apply_retention(const RetentionPolicy& policy, double now) {
  policy.validate();
  require_finite(now, "retention time");
  RetentionReport report;
  sqlite::Transaction tx(impl_->db, "apply retention");
  if (policy.max_age) {
    const double oldest = now - *policy.max_age;
    impl_->delete_old_estimates.run().bind(1, oldest).execute();
    report.estimates_removed += impl_->db.changes();
    impl_->delete_old_aggregates.run().bind(1, oldest).execute();
    report.aggregates_removed += impl_->db.changes();
    impl_->delete_old_alerts.run().bind(1, oldest).execute();
    report.alerts_removed += impl_->db.changes();
  }
  if (policy.aggregate_after) {
    // Whole buckets only: the cut is rounded down to a bucket boundary.
    const double cut = std::floor((now - *policy.aggregate_after) / policy.bucket) * policy.bucket;
    impl_->fold_estimates.run().bind(1, policy.bucket).bind(2, cut).execute();
    impl_->delete_old_estimates.run().bind(1, cut).execute();
    report.estimates_aggregated += impl_->db.changes();
  }
  if (policy.max_rows_per_series) {
    impl_->delete_excess_estimates.run().bind(1, *policy.max_rows_per_series).execute();
    report.estimates_removed += impl_->db.changes();
  }
  tx.commit();
  return report;
}

std::string TrendStore::integrity_check() const {
  return impl_->db.query_text("PRAGMA integrity_check", "integrity check");
}

}  // namespace ambid::diag
