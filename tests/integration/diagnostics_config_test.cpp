// The diagnostics daemon's confirm_windows (alert_policy.hpp, "Confirmation"): below 1 it is
// refused at start with the key's name, before the daemon joins the bus (domain 73).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "cli_run.hpp"

namespace ambid::testing {
namespace diagnostics_config_test {

TEST(DiagnosticsConfig, RefusesConfirmingOverNoWindowAtStart) {
  const auto dir = cli_test::fresh_dir("diagnostics_confirm_windows");
  std::ofstream(dir / "diagnostics.json")
      << R"({"store": ")" << (dir / "trend.sqlite").string() << R"(", "confirm_windows": 0})";
  const cli_test::CommandResult r = cli_test::run_ambid("daemon diagnostics --dds cyclone --domain 73 --config " +
                                                        (dir / "diagnostics.json").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("confirm_windows must be at least 1, got 0"));
}

}  // namespace diagnostics_config_test
}  // namespace ambid::testing
