// The identifier's rule for windows that keep failing (services/daemons/window_failures.hpp):
// the count by reason in its metric, the Health WARN that names the reason, the STALE alert
// the diagnostics engine raises for every parameter on that WARN, and their clearing.
#include "services/daemons/window_failures.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.hpp"
#include "core/no_continuous_equivalent.hpp"
#include "diagnostics/diagnostics_engine.hpp"
#include "diagnostics/identified_estimates.hpp"
#include "diagnostics/plant_families.hpp"

namespace ambid::daemons {
namespace window_failures_test {

using Change = WindowFailures::Change;
using ::testing::HasSubstr;
using ::testing::StartsWith;

const ident::WindowFailure kNoContinuous =
    ident::window_failure(NoContinuousEquivalent("d2c: discrete eigenvalue -0.93 lies on the negative real axis"));
const ident::WindowFailure kUnexciting = ident::window_failure(InsufficientData("identify: rank deficient"));

double unidentified(Metrics& metrics, const std::string& reason) {
  return metrics.counter("ambid_windows_unidentified_total", "", {{"reason", reason}}).Value();
}

bus::Health identifier_health(const WindowFailures& f) {
  bus::Health h;
  h.node = "bearing-1/identifier";
  h.role = "identifier";
  h.level = f.failing() ? bus::AlertLevel::warn : bus::AlertLevel::ok;
  h.message = f.message();
  return h;
}

TEST(WindowFailures, ReasonsOfTheErrorTypes) {
  EXPECT_EQ(kNoContinuous.reason, "no_continuous_model");
  EXPECT_EQ(kUnexciting.reason, "insufficient_data");
  EXPECT_EQ(ident::window_failure(Error("identify: unknown method 'x'")).reason, "error");
  EXPECT_THAT(kNoContinuous.message, HasSubstr("-0.93"));
}

// After 4 identified windows, 4 failures in a row (the default) start it (4 of 8 is not more
// than half); the Health message names the counts, the rule and the last reason; an identified
// window clears it once no more than half of the windows seen failed.
TEST(WindowFailures, ConsecutiveFailuresWarnAndAnIdentifiedWindowClears) {
  Metrics metrics("identifier", 0);
  WindowFailures f(WindowFailureRule{}, metrics);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(f.identified(), Change::none);
  EXPECT_EQ(f.failed(kUnexciting), Change::none);
  EXPECT_EQ(f.failed(kNoContinuous), Change::none);
  EXPECT_EQ(f.failed(kNoContinuous), Change::none);
  EXPECT_FALSE(f.failing());
  EXPECT_EQ(f.failed(kNoContinuous), Change::started);
  EXPECT_TRUE(f.failing());
  EXPECT_EQ(f.failed(kNoContinuous), Change::none);  // still failing
  EXPECT_EQ(f.skipped().at("no_continuous_model"), 4u);
  EXPECT_EQ(f.skipped().at("insufficient_data"), 1u);
  EXPECT_EQ(f.skipped().at("error"), 0u);
  EXPECT_EQ(unidentified(metrics, "no_continuous_model"), 4.0);
  EXPECT_EQ(unidentified(metrics, "insufficient_data"), 1.0);
  EXPECT_EQ(unidentified(metrics, "error"), 0.0);
  EXPECT_THAT(f.message(), StartsWith(std::string(kFailingWindows) + "5 in a row, 5 of the last 9"));
  EXPECT_THAT(f.message(), HasSubstr("last no_continuous_model: d2c: discrete eigenvalue -0.93"));
  EXPECT_LE(f.message().size(), bus::limits::text_length);
  EXPECT_TRUE(reports_failing_windows(identifier_health(f), "bearing-1"));
  EXPECT_FALSE(reports_failing_windows(identifier_health(f), "bearing-2"));

  EXPECT_EQ(f.identified(), Change::cleared);  // 5 of 10
  EXPECT_FALSE(f.failing());
  EXPECT_EQ(f.message(),
            "windows identified again; skipped so far: error 0, insufficient_data 1, no_continuous_model 4");
  EXPECT_FALSE(reports_failing_windows(identifier_health(f), "bearing-1"));
}

// Never 4 in a row but 2 of every 3 windows fail: the fraction rule starts it once 4 windows
// were seen, and it clears only when at most half of the last `recent` failed.
TEST(WindowFailures, MoreThanHalfOfTheRecentWindowsWarn) {
  Metrics metrics("identifier", 0);
  WindowFailures f(WindowFailureRule{4, 6, 0.5}, metrics);
  std::vector<Change> changes;
  for (int i = 0; i < 9; ++i) changes.push_back(i % 3 == 2 ? f.identified() : f.failed(kUnexciting));
  EXPECT_EQ(changes[2], Change::none);     // 2 of 3 failed, fewer than 4 windows seen
  EXPECT_EQ(changes[3], Change::started);  // 3 of 4
  for (int i = 4; i < 9; ++i) EXPECT_EQ(changes[std::size_t(i)], Change::none) << i;  // 4 of the last 6
  EXPECT_TRUE(f.failing());
  EXPECT_THAT(f.message(), HasSubstr("0 in a row, 4 of the last 6"));
  EXPECT_EQ(f.identified(), Change::cleared);  // 3 of the last 6
  EXPECT_EQ(unidentified(metrics, "insufficient_data"), 6.0);
}

TEST(WindowFailures, BadRulesAreNamed) {
  Metrics metrics("identifier", 0);
  EXPECT_THROW(WindowFailures(WindowFailureRule{0, 20, 0.5}, metrics), Error);
  EXPECT_THROW(WindowFailures(WindowFailureRule{4, 0, 0.5}, metrics), Error);
  try {
    WindowFailureRule{4, 20, 1.0}.validate();
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("fraction must be in [0, 1), got 1"));
  }
}

diag::EstimateWindow nominal_window(double time) {
  std::map<std::string, double> physical;
  for (const std::string& name : diag::monitored_parameters("amb1dof_voltage")) physical[name] = 17.5;
  return diag::estimate_window("amb1dof_voltage", physical, {}, time, "bearing-1", diag::Source::sim);
}

std::filesystem::path fresh_store(const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() / ("ambid-window-failures-" + name + ".sqlite");
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(path.string() + suffix);
  return path;
}

// What the diagnostics daemon does with the identifier's Health: on the failing WARN every
// monitored parameter turns STALE, naming the reason; the next identified window brings each
// back to OK ("estimates resumed").
TEST(WindowFailures, FailingWindowsMakeTheParametersStaleUntilTheNextEstimate) {
  diag::TrendStore store(fresh_store("stale"));
  diag::DiagnosticsEngine engine(store);
  for (int i = 1; i <= 3; ++i) engine.process(nominal_window(0.25 * i));
  Metrics metrics("identifier", 0);
  WindowFailures f(WindowFailureRule{}, metrics);
  for (int i = 0; i < 4; ++i) f.failed(kNoContinuous);
  const bus::Health h = identifier_health(f);
  ASSERT_TRUE(reports_failing_windows(h, "bearing-1"));

  const std::vector<diag::Alert> stale = engine.mark_stale("bearing-1", 0.75, "the identifier's " + h.message);
  ASSERT_EQ(stale.size(), diag::monitored_parameters("amb1dof_voltage").size());
  for (const diag::Alert& a : stale) {
    EXPECT_EQ(a.level, diag::Level::stale) << a.parameter;
    EXPECT_EQ(a.time, 0.75);
    EXPECT_THAT(a.message, HasSubstr("no estimate: the identifier's windows not identified: 4 in a row"));
    EXPECT_THAT(a.message, HasSubstr("no_continuous_model"));
    EXPECT_EQ(engine.level("bearing-1", a.parameter), diag::Level::stale);
  }
  EXPECT_TRUE(engine.mark_stale("bearing-1", 0.75, "again").empty());  // already STALE

  const std::vector<diag::Alert> back = engine.process(nominal_window(2.0));
  ASSERT_EQ(back.size(), stale.size());
  for (const diag::Alert& a : back) {
    EXPECT_EQ(a.level, diag::Level::ok) << a.parameter;
    EXPECT_THAT(a.message, HasSubstr("(estimates resumed)"));
  }
}

// A plant whose windows failed from the start: its monitored parameters are marked STALE too.
TEST(WindowFailures, APlantWithoutEstimatesYetGetsItsParametersMarkedStale) {
  diag::TrendStore store(fresh_store("fresh"));
  diag::DiagnosticsEngine engine(store);
  const std::vector<diag::Alert> stale = engine.mark_stale("bearing-1", 0.0, "windows not identified");
  ASSERT_EQ(stale.size(), diag::monitored_parameters("amb1dof_voltage").size());
  for (const diag::Alert& a : stale) EXPECT_EQ(a.level, diag::Level::stale);
  for (const diag::Alert& a : engine.process(nominal_window(0.25))) EXPECT_EQ(a.level, diag::Level::ok);
}

}  // namespace window_failures_test
}  // namespace ambid::daemons
