#include "plant_sim/sales_rotor.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace ambid::sim {
namespace sales_rotor_test {

TEST(SalesRotor, MatricesAndUnstablePole) {
  const NamedSystem s = sales_rotor();
  EXPECT_EQ(s.model, "sales_rotor");
  EXPECT_NO_THROW(s.system.validate());
  EXPECT_EQ(s.system.A(1, 0), 2.8e3);
  EXPECT_EQ(s.system.B(1, 0), 4.2);
  EXPECT_EQ(s.system.C(0, 0), 0.2e3);
  const Eigen::VectorXcd p = poles(s.system);
  ASSERT_EQ(p.size(), 2);
  const double hi = std::max(p[0].real(), p[1].real()), lo = std::min(p[0].real(), p[1].real());
  EXPECT_NEAR(hi, std::sqrt(2800.0), 1e-9);
  EXPECT_NEAR(hi, 52.9, 0.05);
  EXPECT_NEAR(lo, -std::sqrt(2800.0), 1e-9);
  EXPECT_NEAR(p[0].imag(), 0.0, 1e-12);
}

}  // namespace sales_rotor_test
}  // namespace ambid::sim
