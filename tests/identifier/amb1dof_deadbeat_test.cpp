// Seed 000 deadbeat physical realisation of amb1dof_voltage against closed-loop data of its
// linear model (seed 000 eq. 3/4 at the contract's nominal values), simulated here sample by
// sample with the plant_sim observer/integral controller.
#include "identifier/families/amb1dof_deadbeat.hpp"

#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "plant_sim/amb1dof_parameters.hpp"
#include "plant_sim/amb1dof_physical.hpp"
#include "plant_sim/observer_controller.hpp"
#include "plant_sim/scenario.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace amb1dof_deadbeat_test {

constexpr double kT = 1e-4;

struct Case {
  sim::Amb1dofParameters truth;
  ContinuousSystem plant;  // linear truth, states x, x', i1, i2
  DiscreteSystem discrete;
  StateSpaceController controller;  // designed on the NOMINAL model
};

Case make_case(const sim::Amb1dofParameters& truth) {
  Case c;
  c.truth = truth;
  c.plant = sim::amb1dof_structure_system(sim::amb1dof_structure_parameters(truth));
  c.discrete = c2d_zoh(c.plant, kT);
  const ContinuousSystem nominal =
      sim::amb1dof_structure_system(sim::amb1dof_structure_parameters(sim::Amb1dofParameters::nominal()));
  c.controller = sim::design_observer_controller(nominal, kT, {"u1", "u2"}, {"x", "i1", "i2"},
                                                 sim::amb1dof_observer_controller_options());
  return c;
}

// Runs the linear loop and packs it as an experiment (absolute values around the contract's
// operating point).
Experiment run(const Case& c, const Eigen::MatrixXd& r, const Eigen::MatrixXd& noise_y = {},
               const Eigen::MatrixXd& noise_w = {}) {
  testing::Plant P{c.discrete.A, c.discrete.B, c.discrete.C, c.discrete.D, Eigen::MatrixXd::Zero(4, 3)};
  if (noise_y.size()) P.G = Eigen::MatrixXd::Zero(4, 3);  // measurement noise only: e enters y, not x
  testing::Controller K{c.controller.A, c.controller.B, c.controller.C, c.controller.D};
  const testing::LoopData d = testing::run_loop(P, &K, {}, r, noise_y, noise_w);
  Experiment e;
  e.name = "deadbeat test";
  e.sample_time = kT;
  e.plant.model = "amb1dof_voltage";
  e.plant.parameters = sim::Amb1dofParameters::nominal().to_map();
  e.y_names = {"x", "i1", "i2"};
  e.u_names = {"u1", "u2"};
  e.r_names = {"r1", "r2"};
  e.operating_point = {{"x", 0.0}, {"i1", 0.5}, {"i2", 0.5}, {"u1", 8.75}, {"u2", 8.75}};
  e.controller = c.controller;
  const Eigen::Index N = r.rows();
  e.t = Eigen::VectorXd::LinSpaced(N, 0.0, static_cast<double>(N - 1) * kT);
  e.y = d.y.rowwise() + Eigen::RowVector3d(0.0, 0.5, 0.5);
  e.u = d.u.rowwise() + Eigen::RowVector2d(8.75, 8.75);
  e.r = r;
  return e;
}

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

TEST(Amb1dofDeadbeat, NoiseFreeLinearModelIsExact) {
  const Case c = make_case(sim::Amb1dofParameters::nominal());
  std::mt19937_64 rng(91);
  const Eigen::MatrixXd r = testing::random_matrix(4000, 2, rng, 1.0);
  const Experiment e = run(c, r);
  const Amb1dofIdentification id = identify_amb1dof_deadbeat(e);

  const DiscreteSystem& d = id.realization.system;
  const double eA = (d.A - c.discrete.A).norm() / c.discrete.A.norm();
  const double eB = (d.B - c.discrete.B).norm() / c.discrete.B.norm();
  EXPECT_LT(eA, 1e-8);
  EXPECT_LT(eB, 1e-8);
  const auto v_true = sim::amb1dof_structure_parameters(c.truth);
  double ev = 0.0;
  for (const auto& [name, value] : v_true) {
    SCOPED_TRACE(name);
    EXPECT_LT(rel(id.parameters.at(name), value), 1e-8);
    ev = std::max(ev, rel(id.parameters.at(name), value));
  }
  EXPECT_LT((id.continuous.A - c.plant.A).norm() / c.plant.A.norm(), 1e-8);
  EXPECT_LT((id.continuous.B - c.plant.B).norm() / c.plant.B.norm(), 1e-8);
  EXPECT_LT(id.structure_deviation, 1e-8);
  // The physical map against plant_sim's (an independent implementation).
  const auto phys = sim::amb1dof_physical_from_structure(v_true, sim::Amb1dofParameters::nominal()).to_map();
  for (const auto& [name, value] : phys) {
    SCOPED_TRACE(name);
    EXPECT_LT(rel(id.physical.at(name), value), 1e-8);
  }
  EXPECT_NEAR(id.physical.at("R1"), 17.5, 17.5 * 1e-8);
  EXPECT_NEAR(id.physical.at("kw2"), 1.0, 1e-8);
  // Deadbeat gain: A + Gt [C; -F] = 0.
  const Eigen::MatrixXd CF = id.realization.cbar.leftCols(4);
  EXPECT_LT((d.A + id.realization.deadbeat_gain * CF).norm(), 1e-9);
  // Still the open-loop-unstable plant (its unstable real pole, 455 rad/s at these values).
  const double unstable = poles(c.plant).real().maxCoeff();
  EXPECT_GT(unstable, 400.0);
  EXPECT_NEAR(poles(id.continuous).real().maxCoeff(), unstable, 1e-8 * unstable);
  ::testing::Test::RecordProperty("A_error", testing::sci(eA));
  ::testing::Test::RecordProperty("v_error", testing::sci(ev));
}

// Measurement noise: the propagated one-sigma of v1..v9 against a Monte-Carlo sample of the
// same first-order covariance pushed through the exact nonlinear map (logm), and the
// estimates within a few sigma of the truth.
TEST(Amb1dofDeadbeat, UncertaintyPropagation) {
  const Case c = make_case(sim::Amb1dofParameters::nominal());
  std::mt19937_64 rng(92);
  const Eigen::Index N = 20000;
  const Eigen::MatrixXd r = testing::random_matrix(N, 2, rng, 1.0);
  Eigen::MatrixXd v(N, 3);
  v.col(0) = testing::random_matrix(N, 1, rng, 1e-9);  // 1 nm position noise
  v.col(1) = testing::random_matrix(N, 1, rng, 1e-6);  // 1 uA current noise
  v.col(2) = testing::random_matrix(N, 1, rng, 1e-6);
  const Amb1dofIdentification id = identify_amb1dof_deadbeat(run(c, r, v));
  const auto v_true = sim::amb1dof_structure_parameters(c.truth);
  for (const auto& [name, value] : v_true) {
    SCOPED_TRACE(name);
    const double sigma = id.parameter_uncertainty.at(name);
    EXPECT_GT(sigma, 0.0);
    EXPECT_LT(std::abs(id.parameters.at(name) - value), 6.0 * sigma + 1e-3 * std::abs(value));
    ::testing::Test::RecordProperty(name + "_rel_error", testing::sci(rel(id.parameters.at(name), value)));
    ::testing::Test::RecordProperty(name + "_rel_sigma", testing::sci(sigma / std::abs(value)));
  }
  // First-order propagation against the exact map (logm) applied to 400 draws from the
  // least-squares covariance of [A B]: the spread agrees within 25 % (sampling error ~7 %).
  const DiscreteSystem& d = id.realization.system;
  const Eigen::MatrixXd& S = id.realization.parameter_covariance;
  const linalg::Svd eig = linalg::svd(S);  // S is symmetric positive semi-definite: U diag(s) U'
  const Eigen::MatrixXd root = eig.U * eig.S.cwiseSqrt().asDiagonal();
  Eigen::VectorXd p0(24);
  for (Eigen::Index i = 0; i < 4; ++i) {
    p0.segment(i * 4, 4) = d.A.row(i).transpose();
    p0.segment(16 + i * 2, 2) = d.B.row(i).transpose();
  }
  const int draws = 400;
  Eigen::MatrixXd vs(draws, 9);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int k = 0; k < draws; ++k) {
    Eigen::VectorXd z(24);
    for (Eigen::Index i = 0; i < 24; ++i) z(i) = normal(rng);
    const Eigen::VectorXd pk = p0 + root * z;
    DiscreteSystem dk = d;
    for (Eigen::Index i = 0; i < 4; ++i) {
      dk.A.row(i) = pk.segment(i * 4, 4).transpose();
      dk.B.row(i) = pk.segment(16 + i * 2, 2).transpose();
    }
    const auto vk = sim::amb1dof_structure_parameters(d2c_zoh(dk));
    for (int j = 0; j < 9; ++j) vs(k, j) = vk.at("v" + std::to_string(j + 1));
  }
  for (int j = 0; j < 9; ++j) {
    const std::string name = "v" + std::to_string(j + 1);
    SCOPED_TRACE(name);
    const Eigen::VectorXd col = vs.col(j);
    const double mean = col.mean();
    const double sd = std::sqrt((col.array() - mean).square().sum() / (draws - 1));
    EXPECT_NEAR(sd / id.parameter_uncertainty.at(name), 1.0, 0.25);
  }
  // The physical uncertainty is the structure uncertainty times the nominal factor.
  EXPECT_NEAR(id.physical_uncertainty.at("R1"),
              id.parameter_uncertainty.at("v5") * sim::Amb1dofParameters::nominal().L1(), 1e-12);
}

// The observer of the controller assumes the nominal coil; with R1 20 % higher the
// observer's model is wrong and the seed-000 assumption (x_hat = x) holds only approximately:
// the change is still found (the paper: +19.77 %), other parameters barely move.
TEST(Amb1dofDeadbeat, CoilResistanceChangeIsDetected) {
  sim::Amb1dofParameters truth = sim::Amb1dofParameters::nominal();
  truth.R1 *= 1.2;
  const Case c = make_case(truth);
  std::mt19937_64 rng(93);
  const Eigen::MatrixXd r = testing::random_matrix(4000, 2, rng, 1.0);
  const Amb1dofIdentification id = identify_amb1dof_deadbeat(run(c, r));
  const auto v_true = sim::amb1dof_structure_parameters(truth);
  const auto v_nom = sim::amb1dof_structure_parameters(sim::Amb1dofParameters::nominal());
  const double change_v5 = id.parameters.at("v5") / v_nom.at("v5") - 1.0;
  ::testing::Test::RecordProperty("v5_change", testing::sci(change_v5));
  EXPECT_NEAR(change_v5, 0.2, 0.01);
  for (const auto& [name, value] : v_true) {
    ::testing::Test::RecordProperty(name + "_rel_error", testing::sci(rel(id.parameters.at(name), value)));
    if (name != "v5") {
      SCOPED_TRACE(name);
      EXPECT_LT(rel(id.parameters.at(name), value), 0.01);
    }
  }
}

// The whole offline path: the nonlinear amb1dof_voltage plant of seed 000 eq. (1) in the
// closed-loop runner (default scenario: observer/LQR/integral controller, PRBS of 0.05 V on
// both inputs, 2 s at 10 kHz), then this identification from the recorded experiment. The
// linearisation of eq. (3)/(4) is only approximate for the nonlinear plant; measured errors
// are below 1e-4.
TEST(Amb1dofDeadbeat, NonlinearPlantFromTheClosedLoopRunner) {
  const Experiment e = sim::simulate_scenario(sim::ScenarioOptions{});
  const Amb1dofIdentification id = identify_amb1dof_deadbeat(e);
  const auto v_true = sim::amb1dof_structure_parameters(sim::Amb1dofParameters::nominal());
  for (const auto& [name, value] : v_true) {
    SCOPED_TRACE(name);
    EXPECT_LT(rel(id.parameters.at(name), value), 1e-3);
    ::testing::Test::RecordProperty(name + "_rel_error", testing::sci(rel(id.parameters.at(name), value)));
  }
  EXPECT_NEAR(id.physical.at("R1"), 17.5, 17.5e-3);
  EXPECT_NEAR(id.physical.at("kw1"), 1.0, 1e-3);
  EXPECT_LT(id.structure_deviation, 1e-4);
}

TEST(Amb1dofDeadbeat, WrongControllerOrExperimentIsRefused) {
  const Case c = make_case(sim::Amb1dofParameters::nominal());
  std::mt19937_64 rng(94);
  const Experiment good = run(c, testing::random_matrix(300, 2, rng));
  {
    Experiment e = good;
    e.controller.reset();
    EXPECT_THROW(identify_amb1dof_deadbeat(e), Error);
  }
  {
    Experiment e = good;
    e.plant.model = "lamstf";
    EXPECT_THROW(identify_amb1dof_deadbeat(e), Error);
  }
  {
    Experiment e = good;
    e.controller->D(0, 0) = 0.5;  // feedthrough from u1
    try {
      identify_amb1dof_deadbeat(e);
      FAIL() << "expected Error";
    } catch (const Error& err) {
      EXPECT_NE(std::string(err.what()).find("feedthrough"), std::string::npos) << err.what();
    }
  }
  {
    Experiment e = good;
    e.controller->A(4, 0) = 0.1;  // the integrator reads the observer state: not seed-000 form
    EXPECT_THROW(identify_amb1dof_deadbeat(e), Error);
  }
  {
    Experiment e = good;
    e.plant.parameters.erase("Ls1");
    EXPECT_THROW(identify_amb1dof_deadbeat(e), Error);
  }
  {
    // No excitation at all: the loop stays at rest and nothing can be identified.
    const Experiment e = run(c, Eigen::MatrixXd::Zero(300, 2));
    EXPECT_THROW(identify_amb1dof_deadbeat(e), InsufficientData);
  }
}

}  // namespace amb1dof_deadbeat_test
}  // namespace ambid::ident
