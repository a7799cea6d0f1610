#include "plant_sim/linearize.hpp"

#include <cmath>
#include <iostream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "plant_sim/amb1dof_voltage.hpp"
#include "plant_sim/lamstf.hpp"
#include "plant_sim/linear_plant.hpp"

namespace ambid::sim {
namespace linearize_test {

// Largest relative error over the entries where `exact` is non-zero; entries where it is zero
// must be tiny against the largest entry of their row of `exact`.
struct Comparison {
  double relative = 0.0;    // max |num - exact| / |exact| over non-zero entries
  double zero_ratio = 0.0;  // max |num| / max|row of exact| over zero entries
};

Comparison compare(const Eigen::MatrixXd& num, const Eigen::MatrixXd& exact) {
  Comparison c;
  for (Eigen::Index i = 0; i < exact.rows(); ++i) {
    const double row = exact.row(i).cwiseAbs().maxCoeff();
    for (Eigen::Index j = 0; j < exact.cols(); ++j) {
      if (exact(i, j) != 0.0)
        c.relative = std::max(c.relative, std::abs(num(i, j) - exact(i, j)) / std::abs(exact(i, j)));
      else
        c.zero_ratio = std::max(c.zero_ratio, std::abs(num(i, j)) / (row > 0 ? row : 1.0));
    }
  }
  return c;
}

void expect_numerical_matches_analytic(const Amb1dofVoltage& plant) {
  const ContinuousSystem exact = plant.linearize();
  const ContinuousSystem num =
      linearize(plant, {.state_scale = plant.state_scale(), .input_scale = plant.input_scale()});
  const Comparison a = compare(num.A, exact.A), b = compare(num.B, exact.B), c = compare(num.C, exact.C);
  std::cout << "numerical vs analytic: A rel " << a.relative << " zero " << a.zero_ratio << "; B rel " << b.relative
            << " zero " << b.zero_ratio << "; C rel " << c.relative << " zero " << c.zero_ratio << "\n";
  EXPECT_LT(a.relative, 1e-6);
  EXPECT_LT(b.relative, 1e-6);
  EXPECT_LT(c.relative, 1e-12);
  EXPECT_LT(a.zero_ratio, 1e-9);
  EXPECT_LT(b.zero_ratio, 1e-9);
  EXPECT_LT(c.zero_ratio, 1e-12);
  EXPECT_TRUE(num.D.isZero(0.0));
}

TEST(Linearize, NumericalAgreesWithAnalyticAtNominal) { expect_numerical_matches_analytic(Amb1dofVoltage()); }

TEST(Linearize, NumericalAgreesWithAnalyticWhenPerturbed) {
  auto p = Amb1dofParameters::nominal();
  p.R1 *= 1.2;
  p.kw1 *= 1.2;
  p.Ls2 = 0.1;
  expect_numerical_matches_analytic(Amb1dofVoltage(p));
}

TEST(Linearize, LinearPlantGivesItsOwnMatrices) {
  const NamedSystem named = lamstf();
  const ContinuousSystem num = linearize(LinearPlant(named));
  EXPECT_TRUE(num.A.isApprox(named.system.A, 1e-9));
  EXPECT_TRUE(num.B.isApprox(named.system.B, 1e-9));
  EXPECT_TRUE(num.C.isApprox(named.system.C, 1e-9));
}

TEST(Linearize, RefusesBadOptions) {
  const Amb1dofVoltage plant;
  LinearizeOptions wrong_size;
  wrong_size.state_scale = Eigen::VectorXd::Ones(3);
  EXPECT_THAT([&] { linearize(plant, wrong_size); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("state scale must have 4 entries, got 3")));
  LinearizeOptions negative;
  negative.input_scale = Eigen::Vector2d(1.0, -1.0);
  EXPECT_THAT([&] { linearize(plant, negative); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("input scale 1 must be positive")));
  LinearizeOptions no_step;
  no_step.relative_step = 0.0;
  EXPECT_THROW(linearize(plant, no_step), Error);
}

}  // namespace linearize_test
}  // namespace ambid::sim
