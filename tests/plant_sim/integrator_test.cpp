#include "plant_sim/integrator.hpp"

#include <cmath>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "plant_sim/amb1dof_voltage.hpp"
#include "plant_sim/lamstf.hpp"
#include "plant_sim/linear_plant.hpp"

namespace ambid::sim {
namespace integrator_test {

constexpr double kSampleTime = 1e-4;
constexpr int kSamples = 50;  // 5 ms

// The nonlinear AMB open loop at the equilibrium inputs from a small displacement x_start:
// unstable, it drifts away from the centre. Returns the deviation trajectory (one column per
// sample, after the step).
Eigen::MatrixXd open_loop(const Amb1dofVoltage& plant, int substeps, double x_start = 3e-6) {
  Eigen::VectorXd x = plant.equilibrium_state();
  x[0] = x_start;
  const Eigen::VectorXd u = plant.equilibrium_input(), w = Eigen::VectorXd::Zero(1);
  Rk4Integrator rk4(plant);
  Eigen::MatrixXd traj(4, kSamples);
  for (int k = 0; k < kSamples; ++k) {
    rk4.integrate_sample(x, u, w, kSampleTime, substeps);
    traj.col(k) = x - plant.equilibrium_state();
  }
  return traj;
}

// Largest error over the run, per state relative to that state's largest excursion.
double relative_error(const Eigen::MatrixXd& traj, const Eigen::MatrixXd& ref) {
  double e = 0.0;
  for (Eigen::Index i = 0; i < ref.rows(); ++i)
    e = std::max(e, (traj.row(i) - ref.row(i)).cwiseAbs().maxCoeff() / ref.row(i).cwiseAbs().maxCoeff());
  return e;
}

TEST(Integrator, FourthOrderConvergenceOnTheNonlinearAmb) {
  const Amb1dofVoltage plant;
  const Eigen::MatrixXd ref = open_loop(plant, 1024);
  ASSERT_GT(ref(0, kSamples - 1), 3e-5);  // it really left the linear neighbourhood
  ASSERT_LT(ref(0, kSamples - 1), 1e-4);
  std::vector<double> err;
  for (int s : {1, 2, 4, 8, 16}) {
    err.push_back(relative_error(open_loop(plant, s), ref));
    std::cout << "substeps " << s << ": relative error " << err.back() << "\n";
  }
  // Fourth order: the error falls 16-fold per halving of the step, until it reaches the
  // round-off floor (~1e-12 of the excursion: the currents sit on a 0.5 A bias).
  for (std::size_t k = 0; k + 2 < err.size(); ++k) {
    const double ratio = err[k] / err[k + 1];
    std::cout << "ratio " << ratio << "\n";
    EXPECT_GT(ratio, 14.0);
    EXPECT_LT(ratio, 18.0);
  }
  EXPECT_GT(err[3] / err[4], 12.0);
  const double at_default = relative_error(open_loop(plant, kDefaultSubsteps), ref);
  EXPECT_LT(at_default, 2e-7) << "kDefaultSubsteps = " << kDefaultSubsteps;
}

TEST(Integrator, DefaultSubstepsAccurateFarFromTheCentre) {
  // From 12 um the rotor reaches about half the gap in 5 ms, where the force law is strongly
  // nonlinear.
  const Amb1dofVoltage plant;
  const Eigen::MatrixXd ref = open_loop(plant, 1024, 12e-6);
  ASSERT_GT(ref(0, kSamples - 1), 0.4 * plant.parameters().x0);
  const double err = relative_error(open_loop(plant, kDefaultSubsteps, 12e-6), ref);
  std::cout << "half-gap run, substeps " << kDefaultSubsteps << ": relative error " << err << "\n";
  EXPECT_LT(err, 2e-7);
}

TEST(Integrator, LinearPlantMatchesExactZeroOrderHold) {
  const NamedSystem named = lamstf();
  const LinearPlant plant(named);
  const DiscreteSystem exact = c2d_zoh(named.system, 1e-3);
  Eigen::VectorXd x(10), u(5);
  x << 1e-3, -2e-3, 1e-4, 3e-4, -1e-4, 0.01, 0.0, -0.02, 0.0, 0.01;
  u << 0.1, -0.2, 0.05, 0.0, 0.3;
  const Eigen::VectorXd w = Eigen::VectorXd::Zero(5);
  const Eigen::VectorXd next = integrate_sample(plant, x, u, w, 1e-3, 8);
  const Eigen::VectorXd truth = exact.A * x + exact.B * u;
  EXPECT_LT((next - truth).norm() / truth.norm(), 1e-10);
}

// The free function goes through the model's allocation-free advance(); the workspace
// integrator through the generic right-hand side: the same RK4 scheme, to rounding.
TEST(Integrator, WorkspaceAndFreeFunctionAgree) {
  const Amb1dofVoltage plant;
  Eigen::VectorXd x = plant.equilibrium_state();
  x[0] = 2e-6;
  const Eigen::VectorXd u = plant.equilibrium_input(), w = Eigen::VectorXd::Constant(1, 1.0);
  const Eigen::VectorXd a = integrate_sample(plant, x, u, w, kSampleTime);
  Rk4Integrator rk4(plant);
  rk4.integrate_sample(x, u, w, kSampleTime);
  for (Eigen::Index i = 0; i < 4; ++i) EXPECT_NEAR(a[i], x[i], 1e-14 * std::max(1.0, std::abs(x[i])));
}

TEST(Integrator, RefusesBadArgumentsAndSurfacesTouchdown) {
  const Amb1dofVoltage plant;
  const Eigen::VectorXd x = plant.equilibrium_state(), u = plant.equilibrium_input();
  const Eigen::VectorXd w = Eigen::VectorXd::Zero(1);
  using ::testing::HasSubstr;
  EXPECT_THAT([&] { integrate_sample(plant, x, u, w, 0.0, 4); },
              ::testing::ThrowsMessage<Error>(HasSubstr("sample time must be positive")));
  EXPECT_THAT([&] { integrate_sample(plant, x, u, w, 1e-4, 0); },
              ::testing::ThrowsMessage<Error>(HasSubstr("substeps must be at least 1, got 0")));
  EXPECT_THAT([&] { integrate_sample(plant, x, Eigen::VectorXd::Zero(3), w, 1e-4, 4); },
              ::testing::ThrowsMessage<Error>(HasSubstr("input must have 2 entries, got 3")));
  // Full voltage on coil 1 only: the rotor is pulled into coil 1 within a few milliseconds.
  Eigen::VectorXd state = x;
  Rk4Integrator rk4(plant);
  EXPECT_THAT(
      [&] {
        for (int k = 0; k < 1000; ++k) rk4.integrate_sample(state, Eigen::Vector2d(100.0, 0.0), w, 1e-4);
      },
      ::testing::ThrowsMessage<Error>(HasSubstr("rotor touched the bearing")));
}

}  // namespace integrator_test
}  // namespace ambid::sim
