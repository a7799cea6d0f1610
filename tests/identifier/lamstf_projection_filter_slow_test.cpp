// Seed 002 sec. 4.4 (Lee 1995, Tables 4.1/4.2): projection-filter identification of the LAMSTF
// 5-DOF magnetic suspension (plant_sim/lamstf.hpp) under full-state LQR feedback, 6000 samples
// at 10 ms, with 0.5 % and 2.5 % noise; Markov-parameter error (4.36) of the first 30 system
// Markov parameters C A^j B (j = 0..29) of the realised model, at the best ARX order.
//
// "% noise" (undefined in the dissertation) is defined here per channel as
//   rms(noise) / rms(signal):
//   measurement noise v_j on output j:  rms(v_j) = level * rms(y_j),
//   process noise w_j at plant input j: rms(w_j) = level * rms(u_j)   (x[k+1] = A x + B (u + w)),
// with rms(y_j), rms(u_j) those of the noise-free closed loop under the same excitation.
// The error of one run is the mean over j = 0..29 of ||C A^j B - Chat Ahat^j Bhat||_2 /
// ||C A^j B||_2 * 100 % (Lee's table does not say how the 30 values are combined).
// Targets: Lee's best Case 4 values, 0.6892 % (0.5 %) and 3.7469 % (2.5 %); the brief asks for
// at or below the best of all cases, 0.684 % and 3.741 %.
#include <iostream>
#include <random>

#include <gtest/gtest.h>

#include "identifier/markov.hpp"
#include "identifier/projection_filter.hpp"
#include "plant_sim/lamstf.hpp"
#include "plant_sim/lqr.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace {

constexpr double kT = 0.01;
constexpr Eigen::Index kSamples = 6000;

struct Lamstf {
  DiscreteSystem plant;
  Eigen::MatrixXd F;
};

Lamstf lamstf_setup() {
  Lamstf s;
  s.plant = c2d_zoh(sim::lamstf().system, kT);
  s.F = sim::dlqr(s.plant.A, s.plant.B, Eigen::MatrixXd::Identity(10, 10), Eigen::MatrixXd::Identity(5, 5)).K;
  return s;
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

// The best error over ARX orders 2..10 for one noise level; prints the table.
double best_over_orders(const Lamstf& s, double level, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const Eigen::MatrixXd r = testing::random_matrix(kSamples, 5, rng);
  testing::Plant P{s.plant.A, s.plant.B, s.plant.C, s.plant.D, Eigen::MatrixXd::Zero(10, 5)};
  const testing::LoopData clean = testing::run_loop(P, nullptr, s.F, r);
  const Eigen::VectorXd ry = rms(clean.y), ru = rms(clean.u);
  Eigen::MatrixXd v = testing::random_matrix(kSamples, 5, rng), w = testing::random_matrix(kSamples, 5, rng);
  v = v * (level * ry).asDiagonal();
  w = w * (level * ru).asDiagonal();
  const Eigen::MatrixXd wx = w * s.plant.B.transpose();  // process noise through B
  const testing::LoopData d = testing::run_loop(P, nullptr, s.F, r, v, wx);
  double best = 1e300;
  for (Eigen::Index q = 2; q <= 10; ++q) {
    ProjectionFilterOptions o;
    o.arx_order = q;
    o.markov_count = 25;
    o.sample_time = kT;
    o.era.order = 10;
    o.least_squares.max_condition = 1e14;
    const ProjectionFilterResult res = identify_projection_filter(d.y, d.u, d.uf, o);
    const double e = markov_error(s, res.plant);
    std::cout << "noise " << level * 100 << " %  q " << q << "  error " << e << " %\n";
    best = std::min(best, e);
  }
  return best;
}

TEST(LamstfProjectionFilter, NoiseFreeIsExact) {
  const Lamstf s = lamstf_setup();
  std::mt19937_64 rng(101);
  const Eigen::MatrixXd r = testing::random_matrix(kSamples, 5, rng);
  testing::Plant P{s.plant.A, s.plant.B, s.plant.C, s.plant.D, Eigen::MatrixXd::Zero(10, 5)};
  const testing::LoopData d = testing::run_loop(P, nullptr, s.F, r);
  ProjectionFilterOptions o;
  o.arx_order = 2;  // 5 outputs x 2 = 10 states
  o.markov_count = 25;
  o.sample_time = kT;
  o.least_squares.max_condition = 1e14;
  const ProjectionFilterResult res = identify_projection_filter(d.y, d.u, d.uf, o);
  EXPECT_EQ(res.plant.states(), 10);
  const double e = markov_error(s, res.plant);
  std::cout << "noise-free error " << e << " %\n";
  EXPECT_LT(e, 1e-6);  // percent
}

TEST(LamstfProjectionFilter, HalfPercentNoise) {
  const double best = best_over_orders(lamstf_setup(), 0.005, 102);
  ::testing::Test::RecordProperty("best_error_percent", testing::sci(best));
  EXPECT_LE(best, 0.684);
}

TEST(LamstfProjectionFilter, TwoAndAHalfPercentNoise) {
  const double best = best_over_orders(lamstf_setup(), 0.025, 103);
  ::testing::Test::RecordProperty("best_error_percent", testing::sci(best));
  EXPECT_LE(best, 3.741);
}

}  // namespace
}  // namespace ambid::ident
