#include "diagnostics/monitor/change_detection.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.hpp"

namespace ambid::diag {
namespace change_detection_test {

// Windows until a two-sided CUSUM started at S = 0 alarms on N(mean, 1) data.
double mean_cusum_run_length(double k, double h, double mean, int runs, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> z(mean, 1.0);
  CusumConfig config;
  config.k = k;
  config.h = h;
  config.clear_level = 0.5 * h;
  double total = 0.0;
  for (int r = 0; r < runs; ++r) {
    Cusum cusum(config);
    int n = 0;
    do {
      cusum.update(z(rng));
      ++n;
    } while (!cusum.alarmed());
    total += n;
  }
  return total / runs;
}

// Windows until |T| of the slope test first exceeds the threshold (counting evaluated windows).
double mean_slope_run_length(std::size_t window, double threshold, int runs, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> z;
  SlopeConfig config;
  config.window = window;
  config.threshold = threshold;
  config.clear_threshold = 0.5 * threshold;
  double total = 0.0;
  for (int r = 0; r < runs; ++r) {
    SlopeTest test(config);
    int n = 0, t = 0;
    do {
      test.update(t++, z(rng), 1.0);
      if (test.ready()) ++n;
    } while (!test.alarmed());
    total += n;
  }
  return total / runs;
}

TEST(CusumFormula, KnownValues) {
  // Siegmund's approximation against the exact one-sided values of the literature
  // (k = 0.5, h = 4: ARL0 = 336, ARL(1) = 8.38; h = 5: ARL0 = 930).
  EXPECT_NEAR(cusum_arl(0.5, 4.0, 0.0), 336.0, 0.01 * 336.0);
  EXPECT_NEAR(cusum_arl(0.5, 4.0, 1.0), 8.38, 0.01 * 8.38);
  EXPECT_NEAR(cusum_arl(0.5, 5.0, 0.0), 930.0, 0.01 * 930.0);
  EXPECT_NEAR(two_sided_cusum_arl(0.5, 4.0, 0.0), 0.5 * cusum_arl(0.5, 4.0, 0.0), 1e-9);
  EXPECT_NEAR(two_sided_cusum_arl(0.5, 12.0, 0.0), 5.2e5, 0.01 * 5.2e5);  // the default
  EXPECT_NEAR(cusum_arl(0.5, 4.0, 0.5), 5.166 * 5.166, 1e-9);             // Delta = 0
}

TEST(CusumFormula, FalseAlarmRunLengthMatchesSimulation) {
  for (double h : {4.0, 6.0}) {
    const double formula = two_sided_cusum_arl(0.5, h, 0.0);  // 169, 1286
    const double simulated = mean_cusum_run_length(0.5, h, 0.0, 3000, 11);
    // 3000 runs: standard error about 1.8 % of the mean.
    EXPECT_NEAR(simulated, formula, 0.06 * formula) << "h = " << h;
  }
}

TEST(CusumFormula, DetectionDelayMatchesSimulation) {
  for (double shift : {1.0, 2.0, 4.0}) {
    const double formula = two_sided_cusum_arl(0.5, 8.0, shift);  // 16.3, 5.9, 2.6
    const double simulated = mean_cusum_run_length(0.5, 8.0, shift, 4000, 12);
    EXPECT_NEAR(simulated, formula, 0.06 * formula + 0.15) << "shift = " << shift;
  }
}

TEST(SlopeFormula, FalseAlarmRunLengthMatchesSimulation) {
  struct Case {
    std::size_t window;
    double threshold;
  };
  for (const Case c : {Case{20, 2.5}, Case{50, 2.5}, Case{10, 3.0}}) {
    const double formula = slope_test_arl0(c.window, c.threshold);  // 171, 321, 472
    const double simulated = mean_slope_run_length(c.window, c.threshold, 2000, 13);
    // run lengths are close to geometric: standard error about 2.2 % of the mean.
    EXPECT_NEAR(simulated, formula, 0.08 * formula) << "window " << c.window << ", threshold " << c.threshold;
  }
  EXPECT_GT(slope_test_arl0(50, 5.0), 3e6);  // the default
}

TEST(SlopeFormula, ExpectedStatisticOfARamp) {
  const std::size_t window = 50;
  const double rate = 0.05;
  // Fully on the ramp: r sqrt(W (W^2 - 1) / 12).
  EXPECT_NEAR(slope_test_expected_statistic(window, rate, 80), rate * std::sqrt(50.0 * 2499.0 / 12.0), 1e-9);
  EXPECT_NEAR(slope_test_expected_statistic(window, rate, 0), 0.0, 1e-12);
  // Part-way onto the ramp, against the mean over noisy runs.
  for (std::size_t on_ramp : {10u, 25u}) {
    std::mt19937_64 rng(14);
    std::normal_distribution<double> noise;
    SlopeConfig config;
    config.window = window;
    double sum = 0.0;
    const int runs = 2000;
    for (int r = 0; r < runs; ++r) {
      SlopeTest test(config);
      for (std::size_t i = 0; i < 100; ++i) {
        const std::size_t ramp_start = 100 - on_ramp;
        const double truth = i >= ramp_start ? rate * static_cast<double>(i - ramp_start + 1) : 0.0;
        test.update(static_cast<double>(i), truth + noise(rng), 1.0);
      }
      sum += test.statistic();
    }
    EXPECT_NEAR(sum / runs, slope_test_expected_statistic(window, rate, on_ramp), 0.07) << on_ramp;  // 3.2 se
  }
}

TEST(Cusum, RaisesOnAStepAndClearsWithHysteresis) {
  CusumConfig config;  // k 0.5, h 12, clear below 6 for 5 windows
  Cusum cusum(config);
  for (int i = 0; i < 20; ++i) cusum.update(0.0);
  EXPECT_FALSE(cusum.alarmed());
  cusum.update(3.0);  // S+ = 2.5 ...
  for (int i = 0; i < 3; ++i) cusum.update(3.0);
  EXPECT_FALSE(cusum.alarmed());  // 10.0
  cusum.update(3.0);              // 12.5 > h
  ASSERT_TRUE(cusum.alarmed());
  EXPECT_EQ(cusum.direction(), 1);
  EXPECT_EQ(cusum.alarm_windows(), 1u);
  EXPECT_DOUBLE_EQ(cusum.upper(), 12.0);  // capped at h
  // Back to the baseline: S+ falls by k per window, 11.5 ... 5.5 (< 6 after 13 windows),
  // then 5 clean windows: cleared in window 17.
  for (int i = 1; i <= 16; ++i) {
    cusum.update(0.0);
    ASSERT_TRUE(cusum.alarmed()) << i;
  }
  cusum.update(0.0);
  EXPECT_FALSE(cusum.alarmed());
  EXPECT_DOUBLE_EQ(cusum.upper(), 0.0);
}

TEST(Cusum, RaisesOnADecrease) {
  Cusum cusum(CusumConfig{});
  for (int i = 0; i < 4; ++i) cusum.update(-3.5);  // S- = 3 a window
  EXPECT_FALSE(cusum.alarmed());
  EXPECT_DOUBLE_EQ(cusum.lower(), 12.0);  // not above h yet
  cusum.update(-3.5);
  ASSERT_TRUE(cusum.alarmed());
  EXPECT_EQ(cusum.direction(), -1);
  EXPECT_DOUBLE_EQ(cusum.lower(), 12.0);
  EXPECT_DOUBLE_EQ(cusum.upper(), 0.0);
}

TEST(Cusum, DoesNotFlapAroundTheThreshold) {
  Cusum cusum(CusumConfig{});
  for (int i = 0; i < 5; ++i) cusum.update(3.0);
  ASSERT_TRUE(cusum.alarmed());
  // A value hovering where the statistic would cross h again and again: stays raised.
  for (int i = 0; i < 200; ++i) {
    cusum.update(i % 2 ? 1.5 : -0.5);
    ASSERT_TRUE(cusum.alarmed()) << i;
  }
}

TEST(Cusum, RaisedReferenceValue) {
  Cusum cusum(CusumConfig{});
  for (int i = 0; i < 100; ++i) cusum.update(0.9, 0.5);  // k 1.0 > z
  EXPECT_FALSE(cusum.alarmed());
  EXPECT_DOUBLE_EQ(cusum.upper(), 0.0);
  EXPECT_THROW(cusum.update(0.0, -0.1), Error);
}

TEST(SlopeTest, FitsALine) {
  SlopeConfig config;
  config.window = 5;
  SlopeTest test(config);
  for (int i = 0; i < 5; ++i) test.update(1e9 + 10.0 * i, 3.0 + 0.2 * i, 0.01);
  ASSERT_TRUE(test.ready());
  EXPECT_NEAR(test.slope(), 0.02, 1e-9);
  EXPECT_NEAR(test.level(), 3.8, 1e-6);
  EXPECT_NEAR(test.change_over_window(), 0.8, 1e-6);
  // slope / sd(slope): sd = sigma / sqrt(sum (t - mean t)^2) = 0.01 / sqrt(1000)
  EXPECT_NEAR(test.statistic(), 0.02 / (0.01 / std::sqrt(1000.0)), 1e-3);
  EXPECT_TRUE(test.alarmed());
  EXPECT_THROW(test.update(1e9 + 40.0, 3.0, 0.01), Error);  // time going back
}

TEST(Config, Validation) {
  CusumConfig c;
  c.clear_level = c.h;
  EXPECT_THROW(c.validate(), Error);
  SlopeConfig s;
  s.window = 2;
  EXPECT_THROW(s.validate(), Error);
  EXPECT_THROW(Cusum(CusumConfig{.k = -1.0}), Error);
}

}  // namespace change_detection_test
}  // namespace ambid::diag
