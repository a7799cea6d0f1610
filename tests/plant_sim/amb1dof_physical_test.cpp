#include "plant_sim/amb1dof_physical.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "plant_sim/amb1dof_voltage.hpp"

namespace ambid::sim {
namespace amb1dof_physical_test {

using ::testing::HasSubstr;

TEST(Amb1dofPhysical, RecoversThePhysicalParameters) {
  auto truth = Amb1dofParameters::nominal();
  truth.R1 = 21.0;
  truth.kw2 = 0.9;
  const auto v = amb1dof_structure_parameters(truth);
  const auto phys = amb1dof_physical_from_structure(v, Amb1dofParameters::nominal());
  EXPECT_NEAR(phys.R1, 21.0, 1e-12);
  EXPECT_NEAR(phys.R2, 17.5, 1e-12);
  EXPECT_NEAR(phys.kw1, 1.0, 1e-14);
  EXPECT_NEAR(phys.kw2, 0.9, 1e-14);
  EXPECT_NEAR(phys.kr1, 490.0, 1e-9);
  EXPECT_NEAR(phys.kr2, 490.0, 1e-9);
  EXPECT_NEAR(phys.kr1_emf, 490.0, 1e-9);
  EXPECT_NEAR(phys.kr2_emf, 490.0, 1e-9);
  EXPECT_NEAR(phys.ks, 1.4e6, 1e-6);
  const auto map = phys.to_map();
  EXPECT_EQ(map.size(), 9u);
  EXPECT_EQ(map.at("R1"), phys.R1);
  EXPECT_EQ(map.at("kr2_emf"), phys.kr2_emf);
}

TEST(Amb1dofPhysical, SystemAndParametersRoundTrip) {
  const Amb1dofVoltage plant;
  const auto v = plant.structure_parameters();
  const ContinuousSystem sys = amb1dof_structure_system(v);
  EXPECT_NO_THROW(sys.validate());
  EXPECT_EQ(amb1dof_structure_parameters(sys), v);
}

TEST(Amb1dofPhysical, BadInputIsNamed) {
  auto v = Amb1dofVoltage().structure_parameters();
  EXPECT_THAT([&] { amb1dof_physical_from_structure(v, 0.429, 0.0, 1.8); },
              ::testing::ThrowsMessage<Error>(HasSubstr("inductance L2 must be positive")));
  EXPECT_THAT([&] { amb1dof_physical_from_structure(v, 0.429, 0.429, -1.0); },
              ::testing::ThrowsMessage<Error>(HasSubstr("mass m")));
  v.erase("v7");
  EXPECT_THAT([&] { amb1dof_structure_system(v); }, ::testing::ThrowsMessage<Error>(HasSubstr("'v7' is missing")));
  ContinuousSystem small;
  small.A = Eigen::MatrixXd::Zero(2, 2);
  small.B = Eigen::MatrixXd::Zero(2, 1);
  EXPECT_THAT([&] { amb1dof_structure_parameters(small); }, ::testing::ThrowsMessage<Error>(HasSubstr("A 2x2")));
}

}  // namespace amb1dof_physical_test
}  // namespace ambid::sim
