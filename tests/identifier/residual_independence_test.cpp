// The residual check (residual_independence.hpp) against what is known exactly: the z of an
// alternating sequence with itself at lag 1 is -sqrt(N - 1); white residuals independent of r
// give z distributed N(0, 1) (E z^2 = 1 over many seeded records, with a coloured r too);
// an AR(1) residual and one that holds a past r are named at the right lag.
#include "identifier/time_domain/residual_independence.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace ambid::ident {
namespace residual_independence_test {

const std::vector<std::string> kE = {"x", "i1"}, kR = {"r1", "r2"};

Eigen::MatrixXd gaussian(Eigen::Index rows, Eigen::Index cols, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) m(i, j) = normal(rng);
  return m;
}

// Each sample held for `hold` samples: strongly coloured.
Eigen::MatrixXd held(const Eigen::MatrixXd& m, Eigen::Index hold) {
  Eigen::MatrixXd out(m.rows(), m.cols());
  for (Eigen::Index i = 0; i < m.rows(); ++i) out.row(i) = m.row(i - i % hold);
  return out;
}

TEST(ResidualIndependence, AlternatingResidualAtLagOneIsTheWholeRecord) {
  const Eigen::Index N = 1001;
  Eigen::MatrixXd e(N, 1), r(N, 1);
  for (Eigen::Index t = 0; t < N; ++t) e(t, 0) = t % 2 ? -1.0 : 1.0;
  std::mt19937_64 rng(3);
  r = gaussian(N, 1, rng);
  const ResidualIndependence c = residual_independence(e, {"x"}, r, {"r1"}, 1);
  // mean of e is 1 / N; corr at lag 1 is then -(1 - ~1/N^2) / (1 - ~1/N^2) ~ -1
  EXPECT_NEAR(c.whiteness_z, std::sqrt(double(N - 1)), 1e-3);
  EXPECT_EQ(c.whiteness_worst, "e_x with itself at lag 1");
  EXPECT_LT(c.z, 5.0);  // with r: independent
  EXPECT_EQ(c.correlations, 2);
}

TEST(ResidualIndependence, WhiteResidualsGiveStandardNormalZWithWhiteOrColouredExcitation) {
  std::mt19937_64 rng(41);
  for (const Eigen::Index hold : {1, 30}) {
    SCOPED_TRACE("r held for " + std::to_string(hold) + " samples");
    double sum2 = 0.0, largest = 0.0;
    for (int record = 0; record < 400; ++record) {
      const Eigen::MatrixXd e = gaussian(2000, 2, rng), r = held(gaussian(2000, 2, rng), hold);
      // One lag of one residual with one r: one |z|, N(0, 1).
      const double z = residual_independence(e.leftCols(1), {"x"}, r.leftCols(1), {"r1"}, 1).z;
      sum2 += z * z;
      const ResidualIndependence all = residual_independence(e, kE, r, kR, 20);
      largest = std::max({largest, all.z, all.whiteness_z});
    }
    // E[z^2] = 1; sd of the mean over 400 records 0.07.
    EXPECT_NEAR(sum2 / 400.0, 1.0, 0.2);
    // 400 records x 120 correlations: a z beyond 5 has probability 5.7e-7 each, 2.7 % in all.
    EXPECT_LT(largest, 5.0);
    EXPECT_GT(largest, 3.0);  // 48000 draws of N(0, 1) reach 4 or so
  }
}

TEST(ResidualIndependence, NamesTheCorrelationThatIsThere) {
  std::mt19937_64 rng(7);
  const Eigen::Index N = 10000;
  const Eigen::MatrixXd r = gaussian(N, 2, rng), noise = gaussian(N, 2, rng);
  Eigen::MatrixXd e = noise;
  for (Eigen::Index t = 3; t < N; ++t) e(t, 1) += 0.2 * r(t - 3, 1);  // e_i1 holds r2 three samples back
  ResidualIndependence c = residual_independence(e, kE, r, kR, 10);
  EXPECT_EQ(c.worst, "e_i1 with r2 at lag 3");
  // corr = 0.2 / sqrt(1.04) = 0.196: z = 0.196 sqrt(N - 3) = 19.6, give or take 1
  EXPECT_NEAR(c.z, 0.2 / std::sqrt(1.04) * std::sqrt(double(N - 3)), 3.0);
  e = noise;
  for (Eigen::Index t = 1; t < N; ++t) e(t, 0) = 0.5 * e(t - 1, 0) + noise(t, 0);  // AR(1): corr 0.5 at lag 1
  c = residual_independence(e, kE, r, kR, 10);
  EXPECT_EQ(c.whiteness_worst, "e_x with itself at lag 1");
  EXPECT_NEAR(c.whiteness_z, 0.5 * std::sqrt(double(N - 1)), 3.0);
  EXPECT_LT(c.z, 5.0);
  EXPECT_EQ(c.correlations, 2 * 3 * 10);
}

TEST(ResidualIndependence, BadInputsAreRefused) {
  const Eigen::MatrixXd e = Eigen::MatrixXd::Ones(100, 2), r = Eigen::MatrixXd::Ones(100, 2);
  EXPECT_THROW(residual_independence(e, kE, r.topRows(99), kR, 5), Error);
  EXPECT_THROW(residual_independence(e, {"x"}, r, kR, 5), Error);
  EXPECT_THROW(residual_independence(e, kE, r, kR, 0), Error);
  EXPECT_THROW(residual_independence(e, kE, r, kR, 50), Error);
  Eigen::MatrixXd bad = e;
  bad(3, 1) = std::nan("");
  EXPECT_THROW(residual_independence(bad, kE, r, kR, 5), Error);
  // Constant columns correlate with nothing: no z at all.
  EXPECT_EQ(residual_independence(e, kE, r, kR, 5).correlations, 0);
}

}  // namespace residual_independence_test
}  // namespace ambid::ident
