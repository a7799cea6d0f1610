// Welch (Hann, 50 % overlap) closed-loop FRFs with random and chirp excitation: the indirect
// estimate S_yr S_ur^-1 is unbiased under feedback, the direct S_yu S_uu^-1 is biased towards
// 1/K when the noise fed back into u is comparable to the excitation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>

#include "core/error.hpp"
#include "frf_test_helpers.hpp"
#include "identifier/frequency_domain/freq_response.hpp"
#include "identifier/frf_types.hpp"
#include "identifier/frf_welch.hpp"

namespace ambid::ident {
namespace frf_welch_test {

using test::kPi;

constexpr double kT = 1e-4;

using test::gaussian;

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

struct Loop {
  DiscreteSystem plant = c2d_zoh(test::sales_rotor_system(), kT);
  StateSpaceController controller = test::sales_pd_controller(kT);
  std::complex<double> G(double f) const { return freq_response(plant, 2.0 * kPi * f)(0, 0); }
  std::complex<double> K(double f) const { return freq_response(controller, 2.0 * kPi * f)(0, 0); }
};

// The loop driven by unit Gaussian r over 41 segments of 2000 samples (seed 3), noise-free.
struct RandomRun {
  Eigen::MatrixXd r;
  test::LoopData d;
};
RandomRun random_run(const Loop& loop) {
  RandomRun run;
  run.r = gaussian(2000 * 41, 1.0, 3);
  run.d = test::simulate_loop(loop.plant, loop.controller, test::sales_signals(), run.r);
  return run;
}

// Welch with 2000-sample (0.2 s, 5 Hz) segments to 1 kHz.
WelchFrfOptions welch_to_1khz() {
  WelchFrfOptions o;
  o.sample_time = kT;
  o.segment_samples = 2000;
  o.f_max = 1000.0;
  return o;
}

TEST(FrfWelch, NoiseFreeRandomExcitation) {
  const Loop loop;
  const RandomRun run = random_run(loop);
  WelchFrfOptions o = welch_to_1khz();
  o.first_sample = 2000;
  const WelchFrf e = estimate_welch_frf(run.r, run.d.u, run.d.y, o);
  EXPECT_EQ(e.segments, 79);
  // Welch (1967): variance ratio 1 + 2 (1 - 1/M) rho^2 with the overlap correlation
  // rho = sum_{n<L/2} w(n) w(n + L/2) / sum w^2 = (L/16) / (3L/8) = 1/6 for Hann at 50 %
  // (Harris 1978: 16.7 %).
  EXPECT_NEAR(e.effective_segments, 79.0 / (1.0 + 2.0 * (78.0 / 79.0) / 36.0), 1e-9);
  std::vector<double> err;
  double worst_above_100 = 0.0;
  for (Eigen::Index l = 0; l < e.plant.lines(); ++l) {
    const double f = e.plant.frequency_hz(l);
    err.push_back(std::abs(e.plant.value[static_cast<std::size_t>(l)](0, 0) / loop.G(f) - 1.0));
    if (f >= 100.0) worst_above_100 = std::max(worst_above_100, err.back());
    // Noise-free: coherence below 1 only from the leakage of each segment's transient, which
    // matters at the lowest lines (closed-loop time constant ~10 ms against 0.2 s segments).
    EXPECT_GT(e.output_coherence(l, 0), f >= 100.0 ? 0.99 : 0.85) << f;
    EXPECT_GT(e.input_coherence(l, 0), f >= 100.0 ? 0.99 : 0.85) << f;
  }
  // Leakage of the windowed segments is the only error left; the reported variance accounts
  // for it (the residual y - G u is treated as noise).
  EXPECT_LT(median(err), 3e-3);
  EXPECT_LT(*std::max_element(err.begin(), err.end()), 0.15);  // at the lowest lines
  EXPECT_LT(worst_above_100, 0.02);
  int within = 0;
  for (Eigen::Index l = 0; l < e.plant.lines(); ++l)
    within += err[static_cast<std::size_t>(l)] * std::abs(loop.G(e.plant.frequency_hz(l))) <=
              3.0 * std::sqrt(e.plant.variance[static_cast<std::size_t>(l)](0, 0));
  EXPECT_GE(within, static_cast<int>(0.95 * static_cast<double>(e.plant.lines())));
}

// Samples where a controller clamp acted are not exogenous: every segment holding one is
// skipped, so whatever the record holds there leaves the estimate as it is without those
// segments. 1000 samples of y from 30500 on are replaced by garbage and masked: with 2000-sample
// segments at hop 1000 the segments starting at 29000, 30000 and 31000 hold them (3 of 81).
TEST(FrfWelch, SegmentsHoldingALeftOutSampleAreSkipped) {
  const Loop loop;
  const auto [r, d] = random_run(loop);
  WelchFrfOptions o = welch_to_1khz();
  o.left_out.assign(std::size_t(r.rows()), false);
  std::fill(o.left_out.begin() + 30500, o.left_out.begin() + 31500, true);
  Eigen::MatrixXd y_bad = d.y;
  y_bad.middleRows(30500, 1000) = gaussian(1000, 50.0 * d.y.cwiseAbs().maxCoeff(), 9);
  const WelchFrf clean = estimate_welch_frf(r, d.u, d.y, o);
  const WelchFrf masked = estimate_welch_frf(r, d.u, y_bad, o);
  EXPECT_EQ(masked.segments, 78);
  EXPECT_EQ(masked.skipped_segments, 3);
  // The kept segments: 0..28 and 32..80 (29 and 49 consecutive ones): 1 + (2/78) (28 + 48) rho^2.
  EXPECT_NEAR(masked.effective_segments, 78.0 / (1.0 + 2.0 / 78.0 * 76.0 / 36.0), 1e-9);
  double worst_change = 0.0, worst_unmasked = 0.0;
  WelchFrfOptions unmasked_options = o;
  unmasked_options.left_out.clear();
  const WelchFrf unmasked = estimate_welch_frf(r, d.u, y_bad, unmasked_options);
  for (Eigen::Index l = 0; l < masked.plant.lines(); ++l) {
    const auto li = static_cast<std::size_t>(l);
    worst_change = std::max(worst_change, std::abs(masked.plant.value[li](0, 0) / clean.plant.value[li](0, 0) - 1.0));
    worst_unmasked =
        std::max(worst_unmasked, std::abs(unmasked.plant.value[li](0, 0) / clean.plant.value[li](0, 0) - 1.0));
  }
  RecordProperty("garbage_unmasked_worst_relative_change", test::scientific(worst_unmasked));
  EXPECT_LT(worst_change, 1e-12);  // the garbage is in no averaged segment
  EXPECT_GT(worst_unmasked, 0.1);  // and would matter if it were

  o.left_out.assign(std::size_t(r.rows()), true);
  EXPECT_THROW(estimate_welch_frf(r, d.u, d.y, o), InsufficientData);
  o.left_out.resize(10);
  EXPECT_THROW(estimate_welch_frf(r, d.u, d.y, o), Error);
}

TEST(FrfWelch, DirectEstimateIsBiasedUnderFeedbackWithNoise) {
  const Loop loop;
  const double sr = 1.0, sv = 0.03;
  const Eigen::Index L = 2000, M = 400;
  const Eigen::MatrixXd r = gaussian(L / 2 * (M + 1) + L, sr, 11);
  const test::LoopData d = test::simulate_loop(loop.plant, loop.controller, test::sales_signals(), r, sv, 0.0, 12);
  WelchFrfOptions o;
  o.sample_time = kT;
  o.segment_samples = L;
  o.first_sample = L;
  o.f_min = 5.0;
  o.f_max = 50.0;  // above, the loop attenuates r so much that the coherence falls below 0.1
  const WelchFrf e = estimate_welch_frf(r, d.u, d.y, o);
  ASSERT_EQ(e.plant.lines(), 10);
  std::vector<double> err_indirect, err_direct, err_direct_vs_theory;
  int covered = 0, direct_outside = 0;
  const double factor = confidence_radius_factor(0.95, 0.0);
  for (Eigen::Index l = 0; l < e.plant.lines(); ++l) {
    const auto li = static_cast<std::size_t>(l);
    const double f = e.plant.frequency_hz(l);
    const std::complex<double> G = loop.G(f), K = loop.K(f);
    // Closed loop y = S (G r + v), u = S (r + K v): the direct estimate converges to
    // (G sr^2 + conj(K) sv^2) / (sr^2 + |K|^2 sv^2), a mix of G and 1/K.
    const std::complex<double> biased = (G * sr * sr + std::conj(K) * sv * sv) / (sr * sr + std::norm(K) * sv * sv);
    err_indirect.push_back(std::abs(e.plant.value[li](0, 0) / G - 1.0));
    err_direct.push_back(std::abs(e.plant_direct.value[li](0, 0) / G - 1.0));
    err_direct_vs_theory.push_back(std::abs(e.plant_direct.value[li](0, 0) / biased - 1.0));
    covered += std::norm(e.plant.value[li](0, 0) - G) <= factor * e.plant.variance[li](0, 0);
    // The direct estimate's error is far outside the indirect estimate's noise disc.
    direct_outside += std::abs(e.plant_direct.value[li](0, 0) - G) > 3.0 * std::sqrt(e.plant.variance[li](0, 0));
  }
  RecordProperty("median_error_indirect", std::to_string(median(err_indirect)));
  RecordProperty("median_error_direct", std::to_string(median(err_direct)));
  EXPECT_LT(median(err_indirect), 0.15);
  EXPECT_GT(median(err_direct), 0.3);  // visibly biased (0.48 .. 1.06 here)
  EXPECT_EQ(direct_outside, 10);
  EXPECT_LT(median(err_direct_vs_theory), 0.05);  // and biased the way the theory says
  EXPECT_GE(covered, 8);                          // 95 % discs, 10 lines
}

TEST(FrfWelch, ChirpExcitation) {
  const Loop loop;
  const Eigen::Index n = 2000 * 60;
  const double D = static_cast<double>(n) * kT, f0 = 1.0, f1 = 1200.0;
  Eigen::MatrixXd r(n, 1);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * kT;
    r(k, 0) = std::sin(2.0 * kPi * (f0 * t + (f1 - f0) * t * t / (2.0 * D)));
  }
  const test::LoopData d = test::simulate_loop(loop.plant, loop.controller, test::sales_signals(), r);
  WelchFrfOptions o = welch_to_1khz();
  o.f_min = 20.0;
  const WelchFrf e = estimate_welch_frf(r, d.u, d.y, o);
  std::vector<double> err;
  for (Eigen::Index l = 0; l < e.plant.lines(); ++l)
    err.push_back(std::abs(e.plant.value[static_cast<std::size_t>(l)](0, 0) / loop.G(e.plant.frequency_hz(l)) - 1.0));
  EXPECT_LT(median(err), 0.01);
  EXPECT_LT(*std::max_element(err.begin(), err.end()), 0.1);
}

TEST(FrfWelch, RefusesBadInput) {
  const Eigen::MatrixXd r = gaussian(1000, 1.0, 1);
  WelchFrfOptions o;
  o.sample_time = kT;
  o.segment_samples = 2000;
  EXPECT_THROW(estimate_welch_frf(r, r, r, o), InsufficientData);
  o.segment_samples = 100;
  o.overlap = 1.0;
  EXPECT_THROW(estimate_welch_frf(r, r, r, o), Error);
  o.overlap = 0.5;
  EXPECT_THROW(estimate_welch_frf(r, r, Eigen::MatrixXd(r.topRows(10)), o), Error);
}

}  // namespace frf_welch_test
}  // namespace ambid::ident
