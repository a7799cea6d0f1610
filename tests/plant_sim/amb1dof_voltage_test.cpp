#include "plant_sim/amb1dof_voltage.hpp"

#include <cmath>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "plant_sim/amb1dof_physical.hpp"

namespace ambid::sim {
namespace amb1dof_voltage_test {

using ::testing::HasSubstr;

// v1..v9 from the formulas of seed 000 eq. (3)/(4), written out independently of the library.
std::map<std::string, double> expected_v(const Amb1dofParameters& p) {
  const double ks1 = p.K1 * p.i0 * p.i0 / (2 * std::pow(p.x0, 3));
  const double ks2 = p.K2 * p.i0 * p.i0 / (2 * std::pow(p.x0, 3));
  const double kr1 = p.K1 * p.i0 / (2 * p.x0 * p.x0);
  const double kr2 = p.K2 * p.i0 / (2 * p.x0 * p.x0);
  const double L1 = p.Ls1 + p.K1 / (2 * p.x0);
  const double L2 = p.Ls2 + p.K2 / (2 * p.x0);
  return {{"v1", (ks1 + ks2) / p.m}, {"v2", kr1 / p.m}, {"v3", kr2 / p.m},  {"v4", kr1 / L1},  {"v5", p.R1 / L1},
          {"v6", kr2 / L2},          {"v7", p.R2 / L2}, {"v8", p.kw1 / L1}, {"v9", p.kw2 / L2}};
}

TEST(Amb1dofParameters, NominalValuesOfTheContract) {
  const auto p = Amb1dofParameters::nominal();
  EXPECT_EQ(p.m, 1.8);
  EXPECT_EQ(p.x0, 3.5e-4);
  EXPECT_EQ(p.i0, 0.5);
  EXPECT_EQ(p.R1, 17.5);
  EXPECT_EQ(p.R2, 17.5);
  EXPECT_EQ(p.Ls1, 0.086);
  EXPECT_EQ(p.Ls2, 0.086);
  EXPECT_EQ(p.K1, 2.401e-4);
  EXPECT_EQ(p.K2, 2.401e-4);
  EXPECT_EQ(p.kw1, 1.0);
  EXPECT_EQ(p.kw2, 1.0);
  EXPECT_NEAR(p.L1(), 0.429, 1e-15);
  EXPECT_NO_THROW(p.validate());
}

TEST(Amb1dofParameters, MapRoundTripAndNames) {
  auto p = Amb1dofParameters::nominal();
  p.R1 = 21.0;
  const auto map = p.to_map();
  EXPECT_EQ(map.size(), 11u);
  EXPECT_EQ(map.at("R1"), 21.0);
  auto extra = map;
  extra["tau"] = 4e-4;  // unknown keys are ignored, as in the contract
  const auto q = Amb1dofParameters::from_map(extra);
  EXPECT_EQ(q.to_map(), map);
  p.set("kw2", 1.1);
  EXPECT_EQ(p.kw2, 1.1);
  EXPECT_EQ(p.get("kw2"), 1.1);
  EXPECT_EQ(Amb1dofParameters::names().size(), 11u);
}

TEST(Amb1dofParameters, BadInputIsNamed) {
  auto map = Amb1dofParameters::nominal().to_map();
  map.erase("Ls2");
  try {
    Amb1dofParameters::from_map(map);
    FAIL() << "missing key accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("'Ls2' is missing"));
  }

  auto p = Amb1dofParameters::nominal();
  try {
    p.set("R3", 1.0);
    FAIL() << "unknown name accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("'R3'"));
    EXPECT_THAT(e.what(), HasSubstr("m, x0, i0, R1, R2, Ls1, Ls2, K1, K2, kw1, kw2"));
  }
  EXPECT_THROW(p.get("mass"), Error);

  p.set("m", 0.0);
  try {
    p.validate();
    FAIL() << "zero mass accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("'m' must be positive"));
  }
  EXPECT_THROW(Amb1dofVoltage{p}, Error);

  p = Amb1dofParameters::nominal();
  p.x0 = -1e-4;
  EXPECT_THAT([&] { p.validate(); },
              ::testing::ThrowsMessage<Error>(HasSubstr("'x0' must be positive and finite, got -0.0001")));
  p = Amb1dofParameters::nominal();
  p.R2 = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT([&] { p.validate(); }, ::testing::ThrowsMessage<Error>(HasSubstr("'R2'")));
}

TEST(Amb1dofVoltage, NamesAndEquilibrium) {
  const Amb1dofVoltage plant;
  EXPECT_EQ(plant.model(), "amb1dof_voltage");
  EXPECT_EQ(plant.state_names(), (std::vector<std::string>{"x", "x_dot", "i1", "i2"}));
  EXPECT_EQ(plant.input_names(), (std::vector<std::string>{"u1", "u2"}));
  EXPECT_EQ(plant.output_names(), (std::vector<std::string>{"x", "i1", "i2"}));
  EXPECT_EQ(plant.disturbance_names(), (std::vector<std::string>{"Fz"}));
  const Eigen::VectorXd x = plant.equilibrium_state();
  const Eigen::VectorXd u = plant.equilibrium_input();
  EXPECT_EQ(x, Eigen::Vector4d(0, 0, 0.5, 0.5));
  EXPECT_DOUBLE_EQ(u[0], 8.75);
  EXPECT_DOUBLE_EQ(u[1], 8.75);
  // The operating point is a rest point of the nominal model.
  const Eigen::VectorXd dx = plant.derivative(x, u, Eigen::VectorXd::Zero(1));
  EXPECT_LT(dx.cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(plant.output(x), Eigen::Vector3d(0, 0.5, 0.5));

  auto p = Amb1dofParameters::nominal();
  p.R1 = 21.0;
  p.kw2 = 1.25;
  const Amb1dofVoltage changed(p);
  EXPECT_DOUBLE_EQ(changed.equilibrium_input()[0], 21.0 * 0.5 / 1.0);
  EXPECT_DOUBLE_EQ(changed.equilibrium_input()[1], 17.5 * 0.5 / 1.25);
}

TEST(Amb1dofVoltage, RightHandSideIsEquationOne) {
  auto p = Amb1dofParameters::nominal();
  p.K2 = 2.2e-4;
  p.Ls1 = 0.09;
  const Amb1dofVoltage plant(p);
  const double x = 4e-5, v = 0.03, i1 = 0.6, i2 = 0.45, u1 = 9.0, u2 = 7.5, Fz = 2.0;
  const Eigen::VectorXd dx =
      plant.derivative(Eigen::Vector4d(x, v, i1, i2), Eigen::Vector2d(u1, u2), Eigen::VectorXd::Constant(1, Fz));
  const double g1 = p.x0 - x, g2 = p.x0 + x;
  EXPECT_DOUBLE_EQ(dx[0], v);
  EXPECT_NEAR(dx[1], (p.K1 / 4 * std::pow(i1 / g1, 2) - p.K2 / 4 * std::pow(i2 / g2, 2) + Fz) / p.m,
              1e-12 * std::abs(dx[1]));
  // Check the voltage equations as written: kw u = R i + Ls i' + K/2 d/dt(i/g).
  const double d1 = (dx[2] * g1 + i1 * v) / (g1 * g1);  // d/dt(i1/(x0 - x))
  const double d2 = (dx[3] * g2 - i2 * v) / (g2 * g2);  // d/dt(i2/(x0 + x))
  EXPECT_NEAR(p.kw1 * u1, p.R1 * i1 + p.Ls1 * dx[2] + p.K1 / 2 * d1, 1e-12 * u1);
  EXPECT_NEAR(p.kw2 * u2, p.R2 * i2 + p.Ls2 * dx[3] + p.K2 / 2 * d2, 1e-12 * u2);
  // Coil 1 pulls toward +x: more current in coil 1 accelerates the rotor toward +x.
  const Eigen::Vector4d more_i1 = plant.derivative(Eigen::Vector4d(0, 0, 0.6, 0.5), Eigen::Vector2d(0, 0), 0.0);
  EXPECT_GT(more_i1[1], 0.0);
}

TEST(Amb1dofVoltage, RefusesTouchdownAndBadSizes) {
  const Amb1dofVoltage plant;
  const Eigen::VectorXd u = plant.equilibrium_input(), w = Eigen::VectorXd::Zero(1);
  for (double x : {3.5e-4, -3.5e-4, 1e-3}) {
    EXPECT_THAT([&] { plant.derivative(Eigen::Vector4d(x, 0, 0.5, 0.5).eval(), u, w); },
                ::testing::ThrowsMessage<Error>(HasSubstr("rotor touched the bearing")));
  }
  EXPECT_THAT([&] { plant.derivative(Eigen::VectorXd::Zero(3), u, w); },
              ::testing::ThrowsMessage<Error>(HasSubstr("state (x, x_dot, i1, i2) must have 4 entries, got 3")));
  EXPECT_THROW(plant.derivative(plant.equilibrium_state(), Eigen::VectorXd::Zero(1), w), Error);
  EXPECT_THROW(plant.derivative(plant.equilibrium_state(), u, Eigen::VectorXd::Zero(0)), Error);
  EXPECT_THROW(plant.derivative(Eigen::Vector4d(std::nan(""), 0, 0.5, 0.5).eval(), u, w), Error);
}

TEST(Amb1dofVoltage, StructureParametersAreExact) {
  const Amb1dofVoltage plant;
  const auto v = plant.structure_parameters();
  const auto e = expected_v(Amb1dofParameters::nominal());
  ASSERT_EQ(v.size(), 9u);
  for (const auto& [key, value] : e) EXPECT_NEAR(v.at(key), value, 1e-9 * std::abs(value)) << key;
  // The contract's numbers at their printed precision.
  EXPECT_NEAR(v.at("v1"), 777777.8, 0.05);
  EXPECT_NEAR(v.at("v2"), 272.222, 0.0005);
  EXPECT_NEAR(v.at("v3"), 272.222, 0.0005);
  EXPECT_NEAR(v.at("v4"), 1142.191, 0.0005);
  EXPECT_NEAR(v.at("v6"), 1142.191, 0.0005);
  EXPECT_NEAR(v.at("v5"), 40.7925, 0.00005);
  EXPECT_NEAR(v.at("v7"), 40.7925, 0.00005);
  EXPECT_NEAR(v.at("v8"), 2.33100, 0.000005);
  EXPECT_NEAR(v.at("v9"), 2.33100, 0.000005);
}

TEST(Amb1dofVoltage, AnalyticLinearisationHasTheSignsOfEquationThree) {
  const Amb1dofVoltage plant;
  const ContinuousSystem sys = plant.linearize();
  const auto v = expected_v(plant.parameters());
  Eigen::Matrix4d A;
  A << 0, 1, 0, 0, v.at("v1"), 0, v.at("v2"), -v.at("v3"), 0, -v.at("v4"), -v.at("v5"), 0, 0, v.at("v6"), 0,
      -v.at("v7");
  Eigen::Matrix<double, 4, 2> B;
  B << 0, 0, 0, 0, v.at("v8"), 0, 0, v.at("v9");
  Eigen::Matrix<double, 3, 4> C;
  C << 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1;
  EXPECT_LT((sys.A - A).cwiseAbs().maxCoeff(), 1e-9 * v.at("v1"));
  EXPECT_TRUE(sys.B.isApprox(B, 1e-12));
  EXPECT_EQ(sys.C, C);
  EXPECT_TRUE(sys.D.isZero(0.0));
  EXPECT_EQ(plant.disturbance_matrix(), Eigen::Vector4d(0, 1 / 1.8, 0, 0));
  // Exactly one unstable pole (the negative stiffness).
  const Eigen::VectorXcd p = poles(sys);
  int unstable = 0;
  for (Eigen::Index k = 0; k < p.size(); ++k) unstable += p[k].real() > 0 ? 1 : 0;
  EXPECT_EQ(unstable, 1);
}

TEST(Amb1dofVoltage, PerturbedCoilAndAmplifierMoveV5AndV8ByExactlyTwentyPercent) {
  const auto nominal = Amb1dofVoltage().structure_parameters();
  auto p = Amb1dofParameters::nominal();
  p.set("R1", 1.2 * p.R1);
  p.set("kw1", 1.2 * p.kw1);
  const auto v = Amb1dofVoltage(p).structure_parameters();
  EXPECT_NEAR(v.at("v5") / nominal.at("v5"), 1.2, 1e-14);
  EXPECT_NEAR(v.at("v8") / nominal.at("v8"), 1.2, 1e-14);
  for (const char* key : {"v1", "v2", "v3", "v4", "v6", "v7", "v9"})
    EXPECT_NEAR(v.at(key), nominal.at(key), 1e-14 * nominal.at(key)) << key;
}

}  // namespace amb1dof_voltage_test
}  // namespace ambid::sim
