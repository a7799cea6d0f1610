// What the audit reads of a rounded record from the record itself: a DAC's step
// (audit_quantisation.hpp), on signals built here with a known step.
#include <cmath>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "diagnostics/audit/audit_quantisation.hpp"

namespace ambid::diag {
namespace audit_rounding_test {

Eigen::VectorXd uniform(Eigen::Index n, double lo, double hi, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> d(lo, hi);
  Eigen::VectorXd v(n);
  for (double& x : v) x = d(rng);
  return v;
}

Eigen::VectorXd rounded(const Eigen::VectorXd& v, double step) { return (v / step).array().round().matrix() * step; }

// A first-order coil (a = exp(-R Ts / L), 830 rad/s at 3.25 ms) driven by the command rounded
// to 0.35 V, its current logged at 0.01 mA: the screen reads the step, and the middle of the
// steps that round every logged command alike is 0.35 itself (the DAC's edges lie midway
// between the 0.01 V the command is logged at: the bounds about the top edge are symmetric).
TEST(AuditRounding, TheDacStepIsReadFromTheCurrent) {
  const Eigen::Index n = 3000;
  const Eigen::VectorXd command = rounded(uniform(n, 3.0, 5.0, 5), 0.01);
  const double a = std::exp(-830.0 * 3.25e-3), b = (1.0 - a) / 210.0;
  Eigen::VectorXd current(n);
  current(0) = 0.019;
  for (Eigen::Index k = 0; k + 1 < n; ++k)
    current(k + 1) = a * current(k) + b * std::nearbyint(command(k) / 0.35) * 0.35;
  const Eigen::VectorXd logged = rounded(current, 1e-5);
  const DacScreen s = screen_dac_step(command, logged, 0.02, 2.0);
  EXPECT_NEAR(s.step, 0.35, 1e-9);
  EXPECT_LT(s.residual, 0.01 * s.unrounded);

  // Without a DAC no step explains the current much better than the command itself.
  for (Eigen::Index k = 0; k + 1 < n; ++k) current(k + 1) = a * current(k) + b * command(k);
  const DacScreen none = screen_dac_step(command, rounded(current, 1e-5), 0.02, 2.0);
  EXPECT_GT(none.residual, 0.5 * none.unrounded);

  EXPECT_THAT([&] { screen_dac_step(command, logged.head(10), 0.02, 2.0); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("same length")));
  EXPECT_THAT([&] { screen_dac_step(command, logged, 0.0, 2.0); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("0 < smallest < largest")));
}

}  // namespace audit_rounding_test
}  // namespace ambid::diag
