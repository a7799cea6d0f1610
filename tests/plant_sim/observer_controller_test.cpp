#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "plant_sim/amb1dof_voltage.hpp"
#include "plant_sim/observer_controller.hpp"

namespace ambid::sim {
namespace observer_controller_test {

constexpr double kT = 1e-4;
const std::vector<std::string> kInputs = {"u1", "u2"};
const std::vector<std::string> kOutputs = {"x", "i1", "i2"};

ContinuousSystem amb_model(const std::string& parameter = "", double factor = 1.0) {
  Amb1dofParameters p = Amb1dofParameters::nominal();
  if (!parameter.empty()) p.set(parameter, p.get(parameter) * factor);
  return Amb1dofVoltage(p).linearize();
}

StateSpaceController nominal_design() {
  return design_observer_controller(amb_model(), kT, kInputs, kOutputs, amb1dof_observer_controller_options());
}

TEST(ObserverController, ContractShape) {
  const StateSpaceController c = nominal_design();
  EXPECT_EQ(c.inputs, (std::vector<std::string>{"u1", "u2", "x", "i1", "i2"}));
  EXPECT_EQ(c.outputs, kInputs);
  EXPECT_EQ(c.sample_time, kT);
  EXPECT_EQ(c.states(), 5);  // 4 observer states + 1 integrator
  EXPECT_NO_THROW(c.validate(kInputs));
  EXPECT_TRUE(c.D.leftCols(2).isZero(0.0));
}

TEST(ObserverController, NominalLoopIsStableAndWellDamped) {
  const StateSpaceController c = nominal_design();
  const DiscreteSystem cl = linear_closed_loop(c2d_zoh(amb_model(), kT), kInputs, kOutputs, c);
  ASSERT_EQ(cl.states(), 9);
  const double radius = spectral_radius(cl);
  EXPECT_LT(radius, 0.995);
  const Eigen::VectorXcd z = linalg::eigenvalues(cl.A);
  double slowest_complex = 1e300;
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    const std::complex<double> s = std::log(z(i)) / kT;
    const double damping = -s.real() / std::abs(s);
    EXPECT_GE(damping, 0.45) << "pole s = " << s;
    if (std::abs(s.imag()) > 1.0) slowest_complex = std::min(slowest_complex, std::abs(s));
  }
  EXPECT_GT(slowest_complex, 400.0);  // control bandwidth of the position loop, rad/s
  EXPECT_LT(slowest_complex, 700.0);
}

TEST(ObserverController, RobustToTwentyPercentCoilAndAmplifierChanges) {
  const StateSpaceController c = nominal_design();
  for (const std::string parameter : {"R1", "R2", "kw1", "kw2"}) {
    for (const double factor : {0.8, 1.2}) {
      const DiscreteSystem plant = c2d_zoh(amb_model(parameter, factor), kT);
      const double radius = spectral_radius(linear_closed_loop(plant, kInputs, kOutputs, c));
      EXPECT_LT(radius, 0.995) << parameter << " x " << factor;
    }
  }
}

// The contract form must reproduce seed 000 eq. 39, 42, 43 sample for sample:
//   xh[k+1] = A xh + B u + L (y - C xh),  e[k+1] = e[k] - E y[k+1],  uf = -F xh + Fe e.
TEST(ObserverController, ContractFormReproducesThePaperLaw) {
  const StateSpaceController c = nominal_design();
  const DiscreteSystem d = c2d_zoh(amb_model(), kT);
  const Eigen::MatrixXd F = -c.C.leftCols(4), Fe = c.C.rightCols(1);
  const Eigen::MatrixXd L = c.B.topRightCorner(4, 3);
  const Eigen::MatrixXd E = Eigen::RowVector3d(1, 0, 0);
  EXPECT_LT((c.A.topLeftCorner(4, 4) - (d.A - L * d.C)).norm(), 1e-12);
  EXPECT_LT((c.B.topLeftCorner(4, 2) - d.B).norm(), 1e-15);

  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  const int steps = 200;
  Eigen::MatrixXd u(2, steps), y(3, steps);
  for (int k = 0; k < steps; ++k) {
    u.col(k) << noise(rng), noise(rng);
    y.col(k) << 1e-5 * noise(rng), 0.01 * noise(rng), 0.01 * noise(rng);
  }
  // Paper, with e[-1] = 0 so e[0] = -E y[0].
  Eigen::VectorXd xh = Eigen::VectorXd::Zero(4), e = -E * y.col(0);
  // Contract.
  Eigen::VectorXd xc = Eigen::VectorXd::Zero(5);
  for (int k = 0; k < steps; ++k) {
    const Eigen::VectorXd paper = -F * xh + Fe * e;
    Eigen::VectorXd v(5);
    v << u.col(k), y.col(k);
    const Eigen::VectorXd contract = c.C * xc + c.D * v;
    ASSERT_LT((paper - contract).norm(), 1e-9 * std::max(1.0, paper.norm())) << "k = " << k;
    xc = (c.A * xc + c.B * v).eval();
    xh = (d.A * xh + d.B * u.col(k) + L * (y.col(k) - d.C * xh)).eval();
    if (k + 1 < steps) e = (e - E * y.col(k + 1)).eval();
  }
}

TEST(ObserverController, IntegralActionRemovesStaticPositionError) {
  const StateSpaceController c = nominal_design();
  const DiscreteSystem cl = linear_closed_loop(c2d_zoh(amb_model("R1", 1.2), kT), kInputs, kOutputs, c);
  // Static gain from a constant input offset r to [y; u]: the x row must vanish.
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(cl.states(), cl.states());
  const Eigen::MatrixXd dc = cl.C * linalg::lu_solve(Eigen::MatrixXd(I - cl.A), cl.B).x + cl.D;
  EXPECT_LT(dc.row(0).norm(), 1e-12);
  EXPECT_GT(dc.row(1).norm(), 1e-3);  // the currents do move
}

TEST(ObserverController, LinearClosedLoopMatchesStepByStepSimulation) {
  const StateSpaceController c = nominal_design();
  const DiscreteSystem plant = c2d_zoh(amb_model("kw2", 0.8), kT);
  const DiscreteSystem cl = linear_closed_loop(plant, kInputs, kOutputs, c);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 0.1);
  const int steps = 300;
  Eigen::MatrixXd r(steps, 2);
  for (int k = 0; k < steps; ++k) r.row(k) << noise(rng), noise(rng);
  const Eigen::MatrixXd yu = simulate(cl, r);
  Eigen::VectorXd xp = Eigen::VectorXd::Zero(4), xc = Eigen::VectorXd::Zero(5);
  for (int k = 0; k < steps; ++k) {
    const Eigen::VectorXd y = plant.C * xp;
    Eigen::VectorXd v(5);
    v << Eigen::VectorXd::Zero(2), y;
    const Eigen::VectorXd u = c.C * xc + c.D * v + r.row(k).transpose();  // D u-columns are 0
    v.head(2) = u;
    ASSERT_LT((yu.row(k).head(3).transpose() - y).norm(), 1e-12 + 1e-9 * y.norm()) << k;
    ASSERT_LT((yu.row(k).tail(2).transpose() - u).norm(), 1e-9 * (1.0 + u.norm())) << k;
    xp = (plant.A * xp + plant.B * u).eval();
    xc = (c.A * xc + c.B * v).eval();
  }
}

TEST(ObserverController, RejectsBadOptions) {
  ObserverControllerOptions o = amb1dof_observer_controller_options();
  o.integral_outputs = {"y"};
  EXPECT_THROW(design_observer_controller(amb_model(), kT, kInputs, kOutputs, o), Error);
  o = amb1dof_observer_controller_options();
  o.Q = Eigen::MatrixXd::Identity(3, 3);
  EXPECT_THROW(design_observer_controller(amb_model(), kT, kInputs, kOutputs, o), Error);
  o = amb1dof_observer_controller_options();
  o.observer_pole_radius = 0.0;
  EXPECT_THROW(design_observer_controller(amb_model(), kT, kInputs, kOutputs, o), Error);
  EXPECT_THROW(design_observer_controller(amb_model(), kT, {"u1"}, kOutputs, amb1dof_observer_controller_options()),
               Error);
}

}  // namespace observer_controller_test
}  // namespace ambid::sim
