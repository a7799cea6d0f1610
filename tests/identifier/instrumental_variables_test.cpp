// Instrumental variables against a known errors-in-variables problem: the regressor is a
// noisy measurement of a signal driven by an excitation r, the target is the true signal
// times theta plus noise. Least squares is biased towards zero by the regressor noise
// (attenuation factor var(s) / (var(s) + var(noise)) = 0.5 here); IV with r as instrument
// is consistent.
#include "identifier/time_domain/instrumental_variables.hpp"

#include <random>

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace ambid::ident {
namespace instrumental_variables_test {

struct Problem {
  Eigen::MatrixXd phi, z, instruments;
};

Problem errors_in_variables(Eigen::Index rows, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Problem p{Eigen::MatrixXd(rows, 2), Eigen::MatrixXd(rows, 1), Eigen::MatrixXd(rows, 3)};
  double previous_r = 0.0;
  for (Eigen::Index k = 0; k < rows; ++k) {
    const double r = normal(rng);
    const double s = r + previous_r;                 // the true regressor, variance 2
    p.phi(k, 0) = s + std::sqrt(2.0) * normal(rng);  // measured with noise of variance 2
    p.phi(k, 1) = 1.0;
    p.z(k, 0) = 3.0 * s - 0.5 + 0.1 * normal(rng);
    p.instruments.row(k) << r, previous_r, 1.0;
    previous_r = r;
  }
  return p;
}

TEST(InstrumentalVariables, ConsistentWhereLeastSquaresIsBiased) {
  std::mt19937_64 rng(11);
  const Problem p = errors_in_variables(200000, rng);
  LeastSquaresAccumulator ls(2, 1, {"s", "1"});
  ls.add(p.phi, p.z);
  EXPECT_NEAR(ls.solve().theta(0, 0), 1.5, 0.02);  // attenuated by 0.5
  const LeastSquaresSolution iv = solve_instrumental_variables(p.phi, p.z, p.instruments, {"s", "1"});
  const Eigen::MatrixXd sd = iv.standard_deviations();
  EXPECT_NEAR(iv.theta(0, 0), 3.0, 4.0 * sd(0, 0));
  EXPECT_NEAR(iv.theta(1, 0), -0.5, 4.0 * sd(1, 0));
  EXPECT_LT(sd(0, 0), 0.02);
  // Residual variance of the original equations: 0.1^2 + 3^2 * 2 (the regressor noise).
  EXPECT_NEAR(iv.residual_covariance(0, 0), 0.01 + 18.0, 0.3);
}

TEST(InstrumentalVariables, UncertaintyMatchesTheSpreadOverSeeds) {
  std::vector<double> estimates;
  double predicted = 0.0;
  for (int seed = 0; seed < 40; ++seed) {
    std::mt19937_64 rng(100 + seed);
    const Problem p = errors_in_variables(5000, rng);
    const LeastSquaresSolution iv = solve_instrumental_variables(p.phi, p.z, p.instruments, {"s", "1"});
    estimates.push_back(iv.theta(0, 0));
    predicted += iv.standard_deviations()(0, 0) / 40.0;
  }
  double mean = 0.0, var = 0.0;
  for (double e : estimates) mean += e / 40.0;
  for (double e : estimates) var += (e - mean) * (e - mean) / 39.0;
  EXPECT_NEAR(std::sqrt(var) / predicted, 1.0, 0.35);
  EXPECT_NEAR(mean, 3.0, 3.0 * predicted / std::sqrt(40.0) + 0.01);
}

TEST(InstrumentalVariables, BadInputIsRefused) {
  std::mt19937_64 rng(12);
  const Problem p = errors_in_variables(100, rng);
  EXPECT_THROW(solve_instrumental_variables(p.phi, p.z, p.instruments.leftCols(1), {"s", "1"}), InsufficientData);
  EXPECT_THROW(solve_instrumental_variables(p.phi, p.z.topRows(50), p.instruments, {"s", "1"}), Error);
  EXPECT_THROW(solve_instrumental_variables(p.phi, p.z, p.instruments, {"s"}), Error);
  // Instruments that carry nothing of the regressor: the projected problem is rank deficient.
  Eigen::MatrixXd useless = p.instruments;
  useless.col(0).setZero();
  useless.col(1).setZero();
  EXPECT_THROW(solve_instrumental_variables(p.phi, p.z, useless, {"s", "1"}), InsufficientData);
}

}  // namespace instrumental_variables_test
}  // namespace ambid::ident
