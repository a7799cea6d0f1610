// Issue 18: an experiment CSV is read line by line into its arrays, so reading costs the
// memory of the samples (8 bytes per value), not the file's text on top (a 2 GB file used to
// take 2.1 GB). Measured as the growth of the peak resident set (getrusage) of a child process
// that only reads a generated file of 400 000 rows (~50 MB of text, 25.6 MB of samples); each
// value is checked, rows crossing the reader's chunk boundaries included.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>

#include "core/error.hpp"
#include "core/experiment_io.hpp"

namespace ambid {
namespace experiment_memory_test {

namespace fs = std::filesystem;

constexpr long kRows = 400000;
constexpr double kT = 1e-4;

// The values of row k, exactly as written (%.17g round-trips).
void row_values(long k, double (&v)[8]) {
  v[0] = double(k) * kT;
  v[1] = 1e-6 * std::sin(1e-3 * double(k));
  v[2] = 0.5 + 1e-3 * std::cos(2e-3 * double(k));
  v[3] = 0.5 - 1e-3 * std::cos(2e-3 * double(k));
  v[4] = 8.75 + 0.1 * std::sin(3e-3 * double(k));
  v[5] = 8.75 - 0.1 * std::sin(3e-3 * double(k));
  v[6] = (k / 7) % 2 ? 0.5 : -0.5;
  v[7] = -v[6];
}

class ExperimentMemory : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ambid-memory-test-" + std::to_string(std::random_device{}()));
    fs::create_directories(dir_);
    std::ofstream(dir_ / "run.json") << R"({"format": "ambid-experiment/1", "name": "large", "sample_time": 1e-4,
      "plant": {"model": "amb1dof_voltage", "parameters": {"m": 1.8, "R1": 17.5}},
      "signals": {"y": ["x", "i1", "i2"], "u": ["u1", "u2"], "r": ["r1", "r2"]},
      "operating_point": {"x": 0.0, "i1": 0.5, "i2": 0.5, "u1": 8.75, "u2": 8.75}})";
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Rows written one at a time: the test holds no copy of the text either.
  void write_csv(long rows, const std::string& extra_line = {}) const {
    std::FILE* f = std::fopen((dir_ / "run.csv").c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("t,x,i1,i2,u1,u2,r1,r2\n", f);
    double v[8];
    for (long k = 0; k < rows; ++k) {
      row_values(k, v);
      std::fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", v[0], v[1], v[2], v[3], v[4], v[5], v[6],
                   v[7]);
    }
    std::fputs(extra_line.c_str(), f);
    std::fclose(f);
  }

  fs::path dir_;
};

struct ChildReport {
  long peak_growth_kb = -1;
  long rows = -1;
  long wrong_values = -1;
};

// Reads the experiment in a child process (its peak resident set starts at the parent's
// current one) and reports how much the peak grew.
ChildReport read_in_child(const fs::path& stem) {
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) return {};
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(pipe_fds[0]);
    ChildReport r;
    rusage before{}, after{};
    ::getrusage(RUSAGE_SELF, &before);
    try {
      const Experiment e = read_experiment(stem).experiment;
      ::getrusage(RUSAGE_SELF, &after);
      r.rows = long(e.samples());
      r.wrong_values = 0;
      double v[8];
      for (long k = 0; k < r.rows; ++k) {
        row_values(k, v);
        const double got[8] = {e.t(k), e.y(k, 0), e.y(k, 1), e.y(k, 2), e.u(k, 0), e.u(k, 1), e.r(k, 0), e.r(k, 1)};
        for (int j = 0; j < 8; ++j) r.wrong_values += got[j] != v[j];
      }
    } catch (const Error&) {
      ::getrusage(RUSAGE_SELF, &after);
    }
    r.peak_growth_kb = after.ru_maxrss - before.ru_maxrss;
    (void)!::write(pipe_fds[1], &r, sizeof r);
    ::_exit(0);
  }
  ::close(pipe_fds[1]);
  ChildReport r;
  (void)!::read(pipe_fds[0], &r, sizeof r);
  ::close(pipe_fds[0]);
  ::waitpid(pid, nullptr, 0);
  return r;
}

TEST_F(ExperimentMemory, ReadingCostsTheSamplesNotTheText) {
  write_csv(kRows);
  const double text_mb = double(fs::file_size(dir_ / "run.csv")) / 1e6;
  const double samples_mb = double(kRows) * 8 * 8 / 1e6;
  ASSERT_GT(text_mb, 1.5 * samples_mb);  // the text alone would exceed the bound below
  const ChildReport r = read_in_child(dir_ / "run");
  ASSERT_EQ(r.rows, kRows);
  EXPECT_EQ(r.wrong_values, 0);
  const double growth_mb = double(r.peak_growth_kb) * 1024 / 1e6;
  // The samples, the reader's buffers (a chunk, the sidecar) and allocator slack.
  EXPECT_LT(growth_mb, samples_mb * 1.1 + 6.0) << "text " << text_mb << " MB, samples " << samples_mb << " MB";
  EXPECT_GT(growth_mb, samples_mb * 0.9);  // the measurement sees the arrays
  std::cout << "rows " << kRows << ", text " << text_mb << " MB, samples " << samples_mb << " MB, peak RSS growth "
            << growth_mb << " MB\n";
}

TEST_F(ExperimentMemory, ALineLongerThanTheBoundIsRefusedByNumber) {
  write_csv(3, std::string(2u << 20, '1') + "\n");
  try {
    read_experiment(dir_ / "run");
    FAIL() << "a 2 MB line was read";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("run.csv: line 5 is longer than 1048576 bytes"));
  }
}

TEST_F(ExperimentMemory, GarbageLinesDoNotSizeTheArrays) {
  // 3 good rows, then a million one-character lines: refused at line 5, without sizing arrays
  // for a million rows first.
  write_csv(3);
  {
    std::ofstream csv(dir_ / "run.csv", std::ios::app);
    for (int k = 0; k < 1000000; ++k) csv << "1\n";
  }
  const ChildReport r = read_in_child(dir_ / "run");
  EXPECT_EQ(r.rows, -1);  // refused
  EXPECT_GE(r.peak_growth_kb, 0);
  EXPECT_LT(r.peak_growth_kb, 8000) << "a million rows would take 64 MB";
  try {
    read_experiment(dir_ / "run");
    FAIL() << "garbage was read";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("line 5 has 1 cells, the header has 8"));
  }
}

}  // namespace experiment_memory_test
}  // namespace ambid
