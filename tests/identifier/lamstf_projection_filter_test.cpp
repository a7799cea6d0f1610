// Seed 002 sec. 4.4 (Lee 1995, Tables 4.1/4.2): projection-filter identification of the LAMSTF
// 5-DOF magnetic suspension (plant_sim/lamstf.hpp) under LQR state feedback, 6000 samples at
// 10 ms, with 0.5 % and 2.5 % process and measurement noise; Markov-parameter error (4.36) of
// the first 30 system Markov parameters C A^j B (j = 0..29) of the realised model (ERA, 10
// states, 25 Markov parameters as Lee), at the best ARX order q = 2..12.
//
// "% noise" (undefined in the dissertation) is defined here per channel as
// rms(noise) / rms(signal), with the signals of the noise-free closed loop under the same
// excitation r ~ N(0, 1) on the five coil currents:
//   measurement noise v_j on output j:  rms(v_j) = level * rms(y_j),
//   process noise w_j at plant input j: rms(w_j) = level * rms(u_j)   (x[k+1] = A x + B (u + w)).
// The error of one run is the mean over j = 0..29 of ||C A^j B - Chat Ahat^j Bhat||_2 /
// ||C A^j B||_2 * 100 % (Lee's table does not say how the 30 values are combined).
// Targets: at or below the best values of Lee's tables, 0.684 % (0.5 %) and 3.741 % (2.5 %).
//
// Controller (Lee's LQR weights are not given): LQR with Q = I, R = I on the model scaled by
// 1/0.85, so every closed-loop pole lies inside |z| < 0.85 (Lee sec. 2.5: place the closed-loop
// poles in a chosen, well-damped band to make identification easy), fed by the state estimate
// of the steady-state Kalman predictor for these noise covariances (the contract form of an
// observer-based controller; Lee's rig, too, had only position sensors). Two findings behind
// this set-up, measured with this code:
//   - Plain LQR (Q = I, R = I) leaves closed-loop poles at |z| = 0.997: y is then dominated by
//     slow drift, 0.5 % of its rms swamps the fast dynamics, the Kalman predictor has
//     |z| = 0.985 (q ~ 300 needed) and the error is ~60-70 % at any q <= 12.
//   - Feeding back the TRUE, noise-free state makes u a noise-free measurement of F x; the best
//     linear predictor of y then uses it, the recursion (4.25) misreads those coefficients and
//     the error is a bias: ~4 % at 2.5 % noise that does not shrink with more data (4.1 % at
//     6000, 4.5 % at 96000 samples). Lee's derivation assumes u_f = -F x only "for the moment".
#include <iostream>
#include <random>

#include <gtest/gtest.h>

#include "identifier/families/physical_coordinates.hpp"
#include "identifier/time_domain/markov.hpp"
#include "identifier/time_domain/projection_filter.hpp"
#include "plant_sim/lamstf.hpp"
#include "plant_sim/lqr.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace lamstf_projection_filter_test {

constexpr double kT = 0.01;
constexpr Eigen::Index kSamples = 6000;

struct Lamstf {
  DiscreteSystem plant;
  Eigen::MatrixXd F;
};

Lamstf lamstf_setup() {
  Lamstf s;
  s.plant = c2d_zoh(sim::lamstf().system, kT);
  const double radius = 0.85;
  s.F = sim::dlqr(s.plant.A / radius, s.plant.B / radius, Eigen::MatrixXd::Identity(10, 10),
                  Eigen::MatrixXd::Identity(5, 5))
            .K;
  return s;
}

// Observer-based state feedback uf = -F xhat, xhat from the Kalman predictor for process
// covariance W (states) and measurement covariance V; contract form reading [u; y].
testing::Controller observer_controller(const Lamstf& s, const Eigen::MatrixXd& W, const Eigen::MatrixXd& V) {
  // A tiny regularisation keeps (A, W^1/2) stabilisable for the singular W = B S B'.
  const Eigen::MatrixXd L = sim::predictor_gain(s.plant.A, s.plant.C, W + 1e-12 * Eigen::MatrixXd::Identity(10, 10),
                                                V + 1e-12 * Eigen::MatrixXd::Identity(5, 5))
                                .L;
  testing::Controller K;
  K.A = s.plant.A - L * s.plant.C;
  K.B.resize(10, 10);
  K.B << s.plant.B, L;
  K.C = -s.F;
  K.D = Eigen::MatrixXd::Zero(5, 10);
  return K;
}

Eigen::VectorXd rms(const Eigen::MatrixXd& x) { return (x.colwise().squaredNorm() / double(x.rows())).cwiseSqrt(); }

// Mean (4.36) error over the first 30 Markov parameters, percent.
double markov_error(const Lamstf& s, const DiscreteSystem& id) {
  const MarkovSequence truth = markov_parameters(s.plant, 30);
  const MarkovSequence est = markov_parameters(id, 30);
  const std::vector<double> e = markov_errors_percent(truth, est, 1, 30);
  double mean = 0.0;
  for (const double v : e) mean += v / 30.0;
  return mean;
}

// The best error over ARX orders 2..12 for one noise level; prints the table.
double best_over_orders(const Lamstf& s, double level, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const Eigen::MatrixXd r = testing::random_matrix(kSamples, 5, rng);
  testing::Plant P{s.plant.A, s.plant.B, s.plant.C, s.plant.D, Eigen::MatrixXd::Zero(10, 5)};
  const testing::LoopData clean = testing::run_loop(P, nullptr, s.F, r);
  const Eigen::VectorXd ry = rms(clean.y), ru = rms(clean.u);
  const Eigen::MatrixXd v = testing::random_matrix(kSamples, 5, rng) * (level * ry).asDiagonal();
  const Eigen::MatrixXd w = testing::random_matrix(kSamples, 5, rng) * (level * ru).asDiagonal();
  const Eigen::MatrixXd W = s.plant.B * (level * ru).cwiseAbs2().asDiagonal() * s.plant.B.transpose();
  const Eigen::MatrixXd V = (level * ry).cwiseAbs2().asDiagonal();
  const testing::Controller K = observer_controller(s, W, V);
  const testing::LoopData d = testing::run_loop(P, &K, {}, r, v, w * s.plant.B.transpose());
  double best = 1e300;
  Eigen::Index best_q = 0;
  for (Eigen::Index q = 2; q <= 12; ++q) {
    ProjectionFilterOptions o;
    o.arx_order = q;
    o.markov_count = 25;
    o.sample_time = kT;
    o.era.order = 10;
    const ProjectionFilterResult res = identify_projection_filter(d.y, d.u, d.uf, o);
    const double e = markov_error(s, res.plant);
    std::cout << "noise " << level * 100 << " %  seed " << seed << "  q " << q << "  error " << e << " %\n";
    if (e < best) {
      best = e;
      best_q = q;
    }
  }
  std::cout << "noise " << level * 100 << " %  seed " << seed << "  best q " << best_q << "  error " << best << " %\n";
  return best;
}

TEST(LamstfProjectionFilter, NoiseFreeIsExact) {
  const Lamstf s = lamstf_setup();
  std::mt19937_64 rng(101);
  const Eigen::MatrixXd r = testing::random_matrix(kSamples, 5, rng);
  testing::Plant P{s.plant.A, s.plant.B, s.plant.C, s.plant.D, Eigen::MatrixXd::Zero(10, 5)};
  const testing::Controller K =
      observer_controller(s, s.plant.B * s.plant.B.transpose(), Eigen::MatrixXd::Identity(5, 5));
  const testing::LoopData d = testing::run_loop(P, &K, {}, r);
  ProjectionFilterOptions o;
  o.arx_order = 2;  // 5 outputs x 2 = 10 states
  o.markov_count = 25;
  o.sample_time = kT;
  const ProjectionFilterResult res = identify_projection_filter(d.y, d.u, d.uf, o);
  EXPECT_EQ(res.suggested_order, 10);
  EXPECT_EQ(res.plant.states(), 10);
  const double e = markov_error(s, res.plant);
  std::cout << "noise-free error " << e << " %\n";
  EXPECT_LT(e, 1e-6);  // percent, i.e. 1e-8 relative
  ::testing::Test::RecordProperty("error_percent", testing::sci(e));
  // Lee (2.35)-(2.43): back to the analytical model's second-order coordinates through the
  // sensor calibration C1 (positions q = C1^-1 y): A21, A22 = 0 and B2 of sec. 5.2.
  const ContinuousSystem truth = sim::lamstf().system;
  const SecondOrderForm f = second_order_form(res.plant, truth.C.leftCols(5));
  const Eigen::MatrixXd A21 = truth.A.bottomLeftCorner(5, 5), B2 = truth.B.bottomRows(5);
  const double e21 = (f.stiffness - A21).norm() / A21.norm();
  const double e22 = f.damping.norm() / A21.norm();
  const double eb2 = (f.input - B2).norm() / B2.norm();
  EXPECT_LT(e21, 1e-8);
  EXPECT_LT(e22, 1e-8);
  EXPECT_LT(eb2, 1e-8);
  ::testing::Test::RecordProperty("A21_error", testing::sci(e21));
  ::testing::Test::RecordProperty("B2_error", testing::sci(eb2));
}

TEST(LamstfProjectionFilter, HalfPercentNoise) {
  const Lamstf s = lamstf_setup();
  for (const std::uint64_t seed : {102u, 202u, 302u}) {
    const double best = best_over_orders(s, 0.005, seed);
    ::testing::Test::RecordProperty("best_error_percent_seed_" + std::to_string(seed), testing::sci(best));
    EXPECT_LE(best, 0.684) << "seed " << seed;
  }
}

TEST(LamstfProjectionFilter, TwoAndAHalfPercentNoise) {
  const Lamstf s = lamstf_setup();
  for (const std::uint64_t seed : {103u, 203u, 303u}) {
    const double best = best_over_orders(s, 0.025, seed);
    ::testing::Test::RecordProperty("best_error_percent_seed_" + std::to_string(seed), testing::sci(best));
    EXPECT_LE(best, 3.741) << "seed " << seed;
  }
}

}  // namespace lamstf_projection_filter_test
}  // namespace ambid::ident
