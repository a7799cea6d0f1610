#include "plant_sim/lamstf.hpp"

#include <algorithm>
#include <complex>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

namespace ambid::sim {
namespace lamstf_test {

TEST(Lamstf, ShapeAndNames) {
  const NamedSystem s = lamstf();
  EXPECT_EQ(s.model, "lamstf");
  EXPECT_NO_THROW(s.system.validate());
  EXPECT_EQ(s.system.states(), 10);
  EXPECT_EQ(s.system.inputs(), 5);
  EXPECT_EQ(s.system.outputs(), 5);
  EXPECT_EQ(s.state_names.size(), 10u);
  EXPECT_EQ(s.input_names.size(), 5u);
  EXPECT_EQ(s.output_names.size(), 5u);
  EXPECT_TRUE(s.system.A.topLeftCorner(5, 5).isZero(0.0));
  EXPECT_TRUE(s.system.A.topRightCorner(5, 5).isIdentity(0.0));
  EXPECT_TRUE(s.system.A.bottomRightCorner(5, 5).isZero(0.0));
  EXPECT_TRUE(s.system.B.topRows(5).isZero(0.0));
  EXPECT_TRUE(s.system.C.rightCols(5).isZero(0.0));
  EXPECT_EQ(s.system.B(9, 0), 0.2767);  // sign as argued in the seed-002 note
  EXPECT_EQ(s.system.B(5, 0), 38.370);  // printed "538.370"
}

TEST(Lamstf, OpenLoopEigenvaluesMatchTable31) {
  const Eigen::VectorXcd p = poles(lamstf().system);
  // Table 3.1: +-58.78, +-j7.97, +-57.81, +-j0.96, +-9.78.
  const std::vector<std::complex<double>> table = {{58.78, 0},  {-58.78, 0}, {0, 7.97},  {0, -7.97}, {57.81, 0},
                                                   {-57.81, 0}, {0, 0.96},   {0, -0.96}, {9.78, 0},  {-9.78, 0}};
  std::vector<bool> used(static_cast<std::size_t>(p.size()), false);
  for (const auto& t : table) {
    double best = 1e300;
    Eigen::Index best_k = -1;
    for (Eigen::Index k = 0; k < p.size(); ++k) {
      const double d = std::abs(p[k] - t);
      if (!used[static_cast<std::size_t>(k)] && d < best) best = d, best_k = k;
    }
    ASSERT_GE(best_k, 0);
    used[static_cast<std::size_t>(best_k)] = true;
    // 0.1 %, or the rounding of the printed two decimals (0.96 stands for 0.9556).
    EXPECT_LE(best, std::max(1e-3 * std::abs(t), 0.005)) << "eigenvalue " << t << " nearest " << p[best_k];
    std::cout << "Table 3.1 " << t << ": model " << p[best_k] << ", relative " << best / std::abs(t) << "\n";
  }
  // A22 = 0: the oscillatory modes are undamped.
  for (Eigen::Index k = 0; k < p.size(); ++k) {
    if (std::abs(p[k].imag()) > 1e-6) {
      EXPECT_LT(std::abs(p[k].real()), 1e-6);
    }
  }
}

}  // namespace lamstf_test
}  // namespace ambid::sim
