#include "plant_sim/linear_plant.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "plant_sim/sales_rotor.hpp"

namespace ambid::sim {
namespace linear_plant_test {

using ::testing::HasSubstr;

TEST(LinearPlant, DefaultDisturbanceEntersLikeTheInput) {
  const LinearPlant plant(sales_rotor());
  EXPECT_EQ(plant.model(), "sales_rotor");
  EXPECT_EQ(plant.disturbance_names(), std::vector<std::string>{"w_u"});
  EXPECT_EQ(plant.disturbance_matrix(), plant.system().B);
  EXPECT_EQ(plant.equilibrium_state(), Eigen::Vector2d::Zero());
  EXPECT_EQ(plant.equilibrium_input(), Eigen::VectorXd::Zero(1));
  const Eigen::Vector2d x(1e-3, 0.2);
  const Eigen::VectorXd u = Eigen::VectorXd::Constant(1, 0.5), w = Eigen::VectorXd::Constant(1, -0.1);
  const Eigen::VectorXd dx = plant.derivative(x, u, w);
  EXPECT_DOUBLE_EQ(dx[0], 0.2);
  EXPECT_DOUBLE_EQ(dx[1], 2.8e3 * 1e-3 + 4.2 * (0.5 - 0.1));
  EXPECT_DOUBLE_EQ(plant.output(x)[0], 0.2);
}

TEST(LinearPlant, GivenDisturbanceMatrix) {
  const LinearPlant plant(sales_rotor(), Eigen::Vector2d(0.0, 2.0), {"F"});
  const Eigen::VectorXd dx =
      plant.derivative(Eigen::Vector2d::Zero(), Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, 3.0));
  EXPECT_EQ(dx, Eigen::Vector2d(0.0, 6.0));
}

TEST(LinearPlant, RefusesInconsistentInput) {
  NamedSystem s = sales_rotor();
  s.system.D(0, 0) = 1.0;
  EXPECT_THAT([&] { LinearPlant{s}; }, ::testing::ThrowsMessage<Error>(HasSubstr("D must be zero")));
  s = sales_rotor();
  s.state_names = {"x"};
  EXPECT_THAT([&] { LinearPlant{s}; },
              ::testing::ThrowsMessage<Error>(HasSubstr("2 states need as many names, got 1")));
  s = sales_rotor();
  s.state_names = {"x", "x"};
  EXPECT_THAT([&] { LinearPlant{s}; }, ::testing::ThrowsMessage<Error>(HasSubstr("duplicate name 'x'")));
  EXPECT_THAT([&] { LinearPlant(sales_rotor(), Eigen::Vector3d::Zero(), {"F"}); },
              ::testing::ThrowsMessage<Error>(HasSubstr("2 rows")));
  EXPECT_THROW(LinearPlant(sales_rotor(), Eigen::Vector2d::Zero(), {"F", "G"}), Error);
  const LinearPlant plant(sales_rotor());
  EXPECT_THROW(plant.derivative(Eigen::Vector3d::Zero(), Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1)), Error);
}

}  // namespace linear_plant_test
}  // namespace ambid::sim
