#include "diagnostics/trend_store.hpp"

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <set>

#include "core/error.hpp"
#include "diagnostics/synthetic_estimates.hpp"

namespace ambid::diag {
namespace trend_store_test {

using testing::fresh_store_path;

EstimateWindow window(double time, const std::string& plant, std::vector<ParameterEstimate> estimates) {
  EstimateWindow w;
  w.time = time;
  w.plant_id = plant;
  w.source = Source::rig;
  w.estimates = std::move(estimates);
  return w;
}

Alert alert(double time, const std::string& plant, Level level) {
  Alert a;
  a.time = time;
  a.plant_id = plant;
  a.level = level;
  a.fault = "coil_resistance";
  a.channel = 1;
  a.parameter = "R1";
  a.value = 21.0;
  a.baseline = 17.5;
  a.message = "coil 1 resistance 20 % above baseline (step)";
  return a;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

void raw_exec(const std::filesystem::path& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
  sqlite3_close(db);
}

TEST(TrendStore, RoundTrip) {
  TrendStore store(fresh_store_path("roundtrip"));
  Batch batch;
  batch.windows.push_back(window(1.0, "bearing-A", {{"R1", 17.5, 0.05}, {"kw1", 1.0, 0.002}}));
  batch.windows.push_back(window(2.0, "bearing-A", {{"R1", 17.6, 0.06}, {"kw1", 1.01, 0.002}}));
  batch.windows.push_back(window(1.5, "bearing-B", {{"R1", 18.0, 0.05}}));
  batch.alerts.push_back(alert(2.0, "bearing-A", Level::error));
  Alert no_channel = alert(2.0, "bearing-A", Level::warn);
  no_channel.channel.reset();
  no_channel.baseline.reset();
  batch.alerts.push_back(no_channel);
  Baseline learned = learn_baseline(std::vector<double>{1, 2, 3, 4, 5}, std::vector<double>{.1, .1, .1, .1, .1});
  batch.baselines.push_back({"bearing-A", "R1", learned, 2.0});
  store.write(batch);

  const std::vector<StoredEstimate> r1 = store.history("bearing-A", "R1");
  ASSERT_EQ(r1.size(), 2u);
  EXPECT_DOUBLE_EQ(r1[0].time, 1.0);
  EXPECT_DOUBLE_EQ(r1[1].value, 17.6);
  EXPECT_DOUBLE_EQ(r1[1].sigma, 0.06);
  EXPECT_EQ(r1[1].source, Source::rig);
  EXPECT_EQ(r1[1].plant_id, "bearing-A");
  EXPECT_EQ(r1[1].parameter, "R1");
  EXPECT_EQ(store.history("bearing-A", "R1", 1.5, 3.0).size(), 1u);
  EXPECT_EQ(store.history("bearing-B", "R1").size(), 1u);
  EXPECT_TRUE(store.history("bearing-C", "R1").empty());

  const std::vector<Alert> alerts = store.latest_alerts(10);
  ASSERT_EQ(alerts.size(), 2u);
  EXPECT_EQ(alerts[0], no_channel);  // same time: the later write first
  EXPECT_EQ(alerts[1], batch.alerts[0]);

  const std::optional<Baseline> b = store.baseline("bearing-A", "R1");
  ASSERT_TRUE(b);
  EXPECT_DOUBLE_EQ(b->mean, 3.0);
  EXPECT_DOUBLE_EQ(b->extra_spread, learned.extra_spread);
  EXPECT_DOUBLE_EQ(b->mean_sigma, learned.mean_sigma);
  EXPECT_DOUBLE_EQ(b->reported_sigma, 0.1);
  EXPECT_EQ(b->windows, 5u);
  EXPECT_EQ(b->origin, BaselineOrigin::learned);
  EXPECT_FALSE(store.baseline("bearing-A", "kw1"));

  // A newer baseline replaces the old one.
  store.write({{}, {}, {{"bearing-A", "R1", given_baseline(17.5, 0.01), 3.0}}});
  EXPECT_EQ(store.baseline("bearing-A", "R1")->origin, BaselineOrigin::given);
  EXPECT_DOUBLE_EQ(store.baseline("bearing-A", "R1")->extra_spread, 0.01);
  EXPECT_EQ(store.integrity_check(), "ok");
}

// Another bearing under a plant id: its baselines go, other plants' and the history stay.
TEST(TrendStore, ForgetBaselinesOfOnePlant) {
  TrendStore store(fresh_store_path("forget"));
  store.write({{{1.0, "bearing-A", Source::sim, {{"R1", 17.5, 0.1}}}},
               {},
               {{"bearing-A", "R1", given_baseline(17.5, 0.01), 1.0},
                {"bearing-A", "R2", given_baseline(17.5, 0.01), 1.0},
                {"bearing-B", "R1", given_baseline(18.0, 0.01), 1.0}}});
  EXPECT_EQ(store.forget_baselines("bearing-A"), 2u);
  EXPECT_FALSE(store.baseline("bearing-A", "R1"));
  EXPECT_FALSE(store.baseline("bearing-A", "R2"));
  EXPECT_DOUBLE_EQ(store.baseline("bearing-B", "R1")->mean, 18.0);
  EXPECT_EQ(store.history("bearing-A", "R1").size(), 1u);
  EXPECT_EQ(store.forget_baselines("bearing-A"), 0u);
}

TEST(TrendStore, LatestAlertsNewestFirstAndPerPlant) {
  TrendStore store(fresh_store_path("alerts"));
  Batch batch;
  for (int i = 0; i < 10; ++i) batch.alerts.push_back(alert(i, i % 2 ? "bearing-B" : "bearing-A", Level::warn));
  store.write(batch);
  const std::vector<Alert> latest = store.latest_alerts(3);
  ASSERT_EQ(latest.size(), 3u);
  EXPECT_DOUBLE_EQ(latest[0].time, 9.0);
  EXPECT_DOUBLE_EQ(latest[2].time, 7.0);
  const std::vector<Alert> of_a = store.latest_alerts(100, "bearing-A");
  ASSERT_EQ(of_a.size(), 5u);
  for (const Alert& a : of_a) EXPECT_EQ(a.plant_id, "bearing-A");
  EXPECT_DOUBLE_EQ(of_a[0].time, 8.0);
}

TEST(TrendStore, RetentionRemovesExactlyTheOldRows) {
  TrendStore store(fresh_store_path("retention"));
  Batch batch;
  for (int t = 0; t < 100; ++t)
    for (const char* plant : {"bearing-A", "bearing-B"})
      batch.windows.push_back(window(t, plant, {{"R1", 17.5 + t, 0.05}, {"kw1", 1.0, 0.002}}));
  for (int t = 0; t < 100; t += 10) batch.alerts.push_back(alert(t, "bearing-A", Level::warn));
  store.write(batch);

  RetentionPolicy by_age;
  by_age.max_age = 30.0;
  const RetentionReport aged = store.apply_retention(by_age, 99.0);  // keeps t >= 69
  EXPECT_EQ(aged.estimates_removed, 4 * 69);
  EXPECT_EQ(aged.alerts_removed, 7);  // t = 0 ... 60
  for (const char* plant : {"bearing-A", "bearing-B"}) {
    const std::vector<StoredEstimate> h = store.history(plant, "R1");
    ASSERT_EQ(h.size(), 31u);
    EXPECT_DOUBLE_EQ(h.front().time, 69.0);
    EXPECT_DOUBLE_EQ(h.front().value, 17.5 + 69);
    EXPECT_DOUBLE_EQ(h.back().time, 99.0);
  }
  const std::vector<Alert> alerts = store.latest_alerts(100);
  ASSERT_EQ(alerts.size(), 3u);
  EXPECT_DOUBLE_EQ(alerts.back().time, 70.0);

  RetentionPolicy by_rows;
  by_rows.max_rows_per_series = 10;
  EXPECT_EQ(store.apply_retention(by_rows, 99.0).estimates_removed, 4 * 21);
  for (const char* plant : {"bearing-A", "bearing-B"})
    for (const char* parameter : {"R1", "kw1"}) {
      const std::vector<StoredEstimate> h = store.history(plant, parameter);
      ASSERT_EQ(h.size(), 10u);
      EXPECT_DOUBLE_EQ(h.front().time, 90.0);
    }
  EXPECT_EQ(store.apply_retention(by_rows, 99.0).estimates_removed, 0);
  EXPECT_EQ(store.apply_retention(RetentionPolicy{}, 1e9).estimates_removed, 0);
  RetentionPolicy negative;
  negative.max_age = -1.0;
  EXPECT_THROW(store.apply_retention(negative, 99.0), Error);
}

// Per-window estimates older than aggregate_after become hourly buckets whose mean, scatter,
// mean sigma and extremes equal those computed here from the same values; a second pass that
// cuts into a stored bucket merges into it; max_age removes old buckets too.
TEST(TrendStore, RetentionAggregatesOldEstimatesIntoBuckets) {
  TrendStore store(fresh_store_path("aggregate"));
  Batch batch;
  std::vector<double> first_hour;
  for (int k = 0; k < 3 * 3600; k += 10) {  // 3 h of windows every 10 s
    const double value = 17.5 + 0.05 * std::sin(0.37 * k) + (k >= 3600 ? 1.0 : 0.0);
    if (k < 3600) first_hour.push_back(value);
    batch.windows.push_back(window(k, "bearing-A", {{"R1", value, 0.04 + 1e-6 * k}}));
  }
  store.write(batch);
  RetentionPolicy policy;
  policy.aggregate_after = 3600.0;
  const RetentionReport r = store.apply_retention(policy, 3 * 3600.0 + 100.0);  // cut at 2 h
  EXPECT_EQ(r.estimates_aggregated, 720);
  EXPECT_EQ(store.history("bearing-A", "R1").size(), 360u);  // the last hour stays per window
  const std::vector<AggregatedEstimate> a = store.aggregates("bearing-A", "R1");
  ASSERT_EQ(a.size(), 2u);
  double mean = 0.0, square = 0.0;
  for (double v : first_hour) mean += v / double(first_hour.size());
  for (double v : first_hour) square += (v - mean) * (v - mean) / double(first_hour.size() - 1);
  EXPECT_DOUBLE_EQ(a[0].start, 0.0);
  EXPECT_DOUBLE_EQ(a[0].seconds, 3600.0);
  EXPECT_EQ(a[0].windows, 360);
  EXPECT_NEAR(a[0].mean, mean, 1e-12);
  EXPECT_NEAR(a[0].spread, std::sqrt(square), 1e-9);
  EXPECT_NEAR(a[0].mean_sigma, 0.04 + 1e-6 * 1795.0, 1e-12);  // sigma at the mean window time
  EXPECT_DOUBLE_EQ(a[0].min, *std::min_element(first_hour.begin(), first_hour.end()));
  EXPECT_NEAR(a[1].mean, mean + 1.0, 1e-3);
  EXPECT_EQ(a[1].source, Source::rig);

  // Late windows of an aggregated hour merge into its bucket.
  Batch late;
  late.windows.push_back(window(3599.5, "bearing-A", {{"R1", 100.0, 0.04}}));
  store.write(late);
  EXPECT_EQ(store.apply_retention(policy, 3 * 3600.0 + 100.0).estimates_aggregated, 1);
  const std::vector<AggregatedEstimate> merged = store.aggregates("bearing-A", "R1");
  ASSERT_EQ(merged.size(), 2u);
  EXPECT_EQ(merged[0].windows, 361);
  EXPECT_DOUBLE_EQ(merged[0].max, 100.0);
  EXPECT_NEAR(merged[0].mean, (mean * 360.0 + 100.0) / 361.0, 1e-12);

  RetentionPolicy expire;
  expire.max_age = 1.9 * 3600.0;  // removes what ended before 4060 s: the first hour
  EXPECT_EQ(store.apply_retention(expire, 3 * 3600.0 + 100.0).aggregates_removed, 1);
  EXPECT_EQ(store.aggregates("bearing-A", "R1").size(), 1u);

  RetentionPolicy bad;
  bad.bucket = 0.0;
  EXPECT_THROW(store.apply_retention(bad, 1.0), Error);
}

// A store of schema 1 (before the aggregates) opens with its rows and gains the new table.
TEST(TrendStore, MigratesASchemaOneStoreKeepingItsRows) {
  const auto path = fresh_store_path("migrate");
  {
    TrendStore store(path);
    Batch batch;
    batch.windows.push_back(window(1.0, "bearing-A", {{"R1", 17.5, 0.05}}));
    store.write(batch);
  }
  raw_exec(path, "DROP TABLE estimate_aggregates; PRAGMA user_version = 1");
  TrendStore store(path);
  ASSERT_EQ(store.history("bearing-A", "R1").size(), 1u);
  RetentionPolicy policy;
  policy.aggregate_after = 0.0;
  policy.bucket = 10.0;
  EXPECT_EQ(store.apply_retention(policy, 20.0).estimates_aggregated, 1);
  EXPECT_EQ(store.aggregates("bearing-A", "R1").size(), 1u);
}

TEST(TrendStore, WalModeAndSchemaVersion) {
  const auto path = fresh_store_path("schema");
  { TrendStore store(path); }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* stmt = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "PRAGMA journal_mode", -1, &stmt, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_step(stmt), SQLITE_ROW);
  EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(stmt, 0)), "wal");
  sqlite3_finalize(stmt);
  ASSERT_EQ(sqlite3_prepare_v2(db, "PRAGMA user_version", -1, &stmt, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_step(stmt), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int(stmt, 0), kSchemaVersion);
  sqlite3_finalize(stmt);
  sqlite3_close(db);

  raw_exec(path, "PRAGMA user_version = 3");
  const std::string message = error_of([&] { TrendStore store(path); });
  EXPECT_NE(message.find("schema version 3 is newer than this program's 2"), std::string::npos) << message;
}

TEST(TrendStore, ErrorsNameTheOperationAndSqlitesMessage) {
  const auto missing = fresh_store_path("missing");
  std::string message = error_of([&] { TrendStore store(missing, OpenMode::read_only); });
  EXPECT_NE(message.find(missing.string() + ": open: unable to open database file"), std::string::npos) << message;

  const auto junk = fresh_store_path("junk");
  std::ofstream(junk) << std::string(4096, 'x');
  message = error_of([&] { TrendStore store(junk); });
  EXPECT_NE(message.find("file is not a database"), std::string::npos) << message;

  const auto path = fresh_store_path("read_only");
  { TrendStore store(path); }
  TrendStore reader(path, OpenMode::read_only);
  Batch batch;
  batch.windows.push_back(window(1.0, "bearing-A", {{"R1", 17.5, 0.05}}));
  message = error_of([&] { reader.write(batch); });
  EXPECT_NE(message.find(": insert estimate: attempt to write a readonly database (code 8)"), std::string::npos)
      << message;

  TrendStore store(path);
  batch.windows.push_back(window(2.0, "bearing-A", {{"R1", 17.5, -0.05}}));
  message = error_of([&] { store.write(batch); });
  EXPECT_NE(message.find("R1 sigma must be non-negative"), std::string::npos) << message;
  EXPECT_TRUE(store.history("bearing-A", "R1").empty());  // nothing of the refused batch
}

// A writer process appends batches of 10 windows while this process reads: every read sees
// whole batches only.
TEST(TrendStore, ConcurrentReaderSeesWholeBatches) {
  const auto path = fresh_store_path("concurrent");
  constexpr int kBatches = 200, kWindows = 10;
  int ready[2];
  ASSERT_EQ(pipe(ready), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    close(ready[0]);
    try {
      TrendStore store(path);
      const char byte = 1;
      if (write(ready[1], &byte, 1) != 1) _exit(3);
      for (int b = 0; b < kBatches; ++b) {
        Batch batch;
        for (int j = 0; j < kWindows; ++j)
          batch.windows.push_back(
              window(b * kWindows + j, "bearing-A", {{"R1", 17.5, 0.05}, {"R2", 17.5, 0.05}, {"kw1", 1.0, 0.002}}));
        batch.alerts.push_back(alert(b, "bearing-A", Level::warn));
        store.write(batch);
      }
      _exit(0);
    } catch (...) {
      _exit(2);
    }
  }
  close(ready[1]);
  char byte = 0;
  ASSERT_EQ(read(ready[0], &byte, 1), 1);
  close(ready[0]);
  TrendStore reader(path, OpenMode::read_only);
  std::set<std::size_t> seen;
  int status = 0;
  for (;;) {
    const bool done = waitpid(child, &status, WNOHANG) == child;
    const std::size_t n = reader.history("bearing-A", "R2").size();
    ASSERT_EQ(n % kWindows, 0u) << "a reader saw part of a batch";
    ASSERT_TRUE(seen.empty() || n >= *seen.rbegin());
    seen.insert(n);
    const std::size_t alerts = reader.latest_alerts(1000).size();
    ASSERT_GE(alerts * kWindows, n);  // this read is later, so at least as many batches
    if (done) break;
  }
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(reader.history("bearing-A", "R2").size(), std::size_t{kBatches * kWindows});
  EXPECT_GE(seen.size(), 3u) << "the reader should have seen the store grow";
}

}  // namespace trend_store_test
}  // namespace ambid::diag
