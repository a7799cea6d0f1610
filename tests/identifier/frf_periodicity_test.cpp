// The periodicity of r found from the samples alone: smallest repeating shift, whole periods
// in a record that does not end on one, a generator switched on late, periods that are not a
// whole number of samples, the tolerance, the excited lines of each reference.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.hpp"
#include "frf_test_helpers.hpp"
#include "identifier/frequency_domain/frf_periodicity.hpp"

namespace ambid::ident {
namespace frf_periodicity_test {

using test::kPi;

TEST(FrfPeriodicity, MultisineWithAPartialLastPeriodAndALateStart) {
  // Lines 3, 5, 9 of a 100-sample period; 300 leading zeros, 7 whole periods and 40 samples.
  const Eigen::VectorXd period = test::multisine_period(100, {3, 5, 9}, 4);
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(300 + 740, 1);
  for (Eigen::Index n = 0; n < 740; ++n) r(300 + n, 0) = period(n % 100);
  const Periodicity p = detect_periodicity(r);
  EXPECT_EQ(p.first_sample, 300);
  EXPECT_EQ(p.span_samples, 740);
  EXPECT_EQ(p.period_samples, 100);
  EXPECT_EQ(p.periods, 7);
  ASSERT_EQ(p.lines.size(), 1u);
  EXPECT_EQ(p.lines[0], (std::vector<Eigen::Index>{3, 5, 9}));
  EXPECT_EQ(p.all_lines, p.lines[0]);
}

TEST(FrfPeriodicity, ThePeriodIsTheSmallestShiftAndLinesArePerReference) {
  // Both channels on a 60-sample grid, lines all even: r repeats every 30 samples; on that grid
  // channel 1 holds lines 1 and 4, channel 2 lines 2 and 7.
  Eigen::MatrixXd r(600, 2);
  for (Eigen::Index n = 0; n < 600; ++n) {
    const double t = 2.0 * kPi * static_cast<double>(n) / 60.0;
    r(n, 0) = std::cos(2.0 * t + 0.3) + 0.5 * std::cos(8.0 * t);
    r(n, 1) = std::sin(4.0 * t) + std::cos(14.0 * t + 1.0);
  }
  const Periodicity p = detect_periodicity(r);
  EXPECT_EQ(p.period_samples, 30);
  EXPECT_EQ(p.periods, 20);
  EXPECT_EQ(p.lines[0], (std::vector<Eigen::Index>{1, 4}));
  EXPECT_EQ(p.lines[1], (std::vector<Eigen::Index>{2, 7}));
  EXPECT_EQ(p.all_lines, (std::vector<Eigen::Index>{1, 2, 4, 7}));
}

TEST(FrfPeriodicity, APeriodOfNonWholeSamplesRepeatsAfterAWholeMultiple) {
  // A sine of period 200.5 samples: r(n + 401) = r(n), two cycles, line 2 of 401.
  Eigen::MatrixXd r(2000, 1);
  for (Eigen::Index n = 0; n < r.rows(); ++n) r(n, 0) = std::sin(2.0 * kPi * static_cast<double>(n) / 200.5);
  const Periodicity p = detect_periodicity(r);
  EXPECT_EQ(p.period_samples, 401);
  EXPECT_EQ(p.periods, 4);
  EXPECT_EQ(p.lines[0], (std::vector<Eigen::Index>{2}));
}

TEST(FrfPeriodicity, NoiseAboveTheToleranceIsNotPeriodicBelowItIs) {
  const Eigen::VectorXd period = test::multisine_period(50, {1, 2, 3, 4, 5}, 9);
  const Eigen::MatrixXd noise = test::gaussian(1000, 1e-5, 3);
  Eigen::MatrixXd r(1000, 1);
  for (Eigen::Index n = 0; n < 1000; ++n) r(n, 0) = period(n % 50) + noise(n, 0);
  EXPECT_FALSE(detect_periodicity(r).periodic());  // default: 1e-6 of the peak
  PeriodicityOptions loose;
  loose.tolerance = 1e-3;
  const Periodicity p = detect_periodicity(r, loose);
  EXPECT_EQ(p.period_samples, 50);
  EXPECT_EQ(p.lines[0], (std::vector<Eigen::Index>{1, 2, 3, 4, 5}));
}

TEST(FrfPeriodicity, RandomSignalsAndSingleRepeatsAreNotPeriodic) {
  EXPECT_FALSE(detect_periodicity(test::gaussian(5000, 1.0, 8)).periodic());
  // One and a half periods cannot show a repetition of the whole period.
  const Eigen::VectorXd period = test::multisine_period(400, {1, 2, 3}, 2);
  Eigen::MatrixXd r(600, 1);
  for (Eigen::Index n = 0; n < 600; ++n) r(n, 0) = period(n % 400);
  EXPECT_FALSE(detect_periodicity(r).periodic());
  EXPECT_FALSE(detect_periodicity(Eigen::MatrixXd::Zero(100, 2)).periodic());
}

TEST(FrfPeriodicity, BadInputIsRefused) {
  Eigen::MatrixXd r = Eigen::MatrixXd::Ones(10, 1);
  r(3, 0) = std::nan("");
  EXPECT_THROW(detect_periodicity(r), Error);
  PeriodicityOptions o;
  o.tolerance = 0.0;
  EXPECT_THROW(detect_periodicity(Eigen::MatrixXd::Ones(10, 1), o), Error);
}

}  // namespace frf_periodicity_test
}  // namespace ambid::ident
