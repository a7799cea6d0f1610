// The progress line of the long offline commands (services/cli/progress.hpp) as a user sees
// it: `ambid frf` and `ambid audit` draw "COMMAND: STAGE k/n, ... elapsed" on stderr when it
// is a terminal (a pseudo-terminal from util-linux `script` here), and say nothing of it under
// --quiet or when stderr is a pipe.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_run.hpp"

namespace ambid {
namespace progress_cli_test {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;
using cli_test::CommandResult;
using cli_test::fresh_dir;
using cli_test::run_ambid;
using cli_test::run_command;

// `ambid ARGS` with stdout and stderr on a pseudo-terminal; the exit status is ambid's.
CommandResult run_ambid_on_terminal(const std::string& args) {
  return run_command("script -qec '" + std::string(AMBID_BINARY) + " " + args + "' /dev/null");
}

TEST(ProgressCli, FrfDrawsItsStagesOnATerminalOnly) {
  const fs::path dir = fresh_dir("progress_frf");
  ASSERT_EQ(run_ambid("sim --excitation multisine --duration 2 --seed 3 --out " + (dir / "ms").string()).status, 0);
  const std::string args = "frf " + (dir / "ms.json").string() + " --no-fit --out " + (dir / "frf").string();
  CommandResult r = run_ambid_on_terminal(args);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("ambid frf: read " + (dir / "ms.json").string() + " 0/4, "));
  EXPECT_THAT(r.output, HasSubstr("ambid frf: FRF estimate 1/4, "));
  EXPECT_THAT(r.output, HasSubstr("ambid frf: plots 2/4, "));
  EXPECT_THAT(r.output, HasSubstr(" elapsed"));
  r = run_ambid_on_terminal(args + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("wrote"));
  EXPECT_THAT(r.output, Not(HasSubstr("ambid frf: read")));
  EXPECT_THAT(r.output, Not(HasSubstr("elapsed")));
  r = run_ambid(args);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, Not(HasSubstr("elapsed")));
  EXPECT_THAT(r.output, Not(HasSubstr("\r")));
}

TEST(ProgressCli, AuditDrawsItsCandidatesOnATerminalOnly) {
  const fs::path dir = fresh_dir("progress_audit");
  ASSERT_EQ(run_ambid("sim --duration 0.5 --amplitude 0.3 --position-noise 2e-9 --current-noise 2e-5 --seed 21 --out " +
                      (dir / "run").string())
                .status,
            0);
  const std::string args = "audit " + (dir / "run.json").string() + " --out " + (dir / "audit").string();
  CommandResult r = run_ambid_on_terminal(args);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("ambid audit: screen the effect catalogue 0/"));
  EXPECT_THAT(r.output, HasSubstr("ambid audit: fit the best candidates 0/5, "));
  r = run_ambid_on_terminal(args + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("ambid audit:"));  // the verdict
  EXPECT_THAT(r.output, Not(HasSubstr("elapsed")));
}

}  // namespace progress_cli_test
}  // namespace ambid
