// Continuous rational fits (Sanathanan-Koerner + Ceres): exact recovery of seed 003's reduced
// beam model (eq. 7, one unstable pole), order selection, the unstable pole of the Sales rotor
// from closed-loop data (noise-free and noisy, ZOH compensated), and the realisation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include "core/error.hpp"
#include "frf_test_helpers.hpp"
#include "identifier/frequency_domain/freq_response.hpp"
#include "identifier/frequency_domain/frf_periodic.hpp"
#include "identifier/frequency_domain/rational_fit.hpp"
#include "identifier/frequency_domain/rational_fit_order.hpp"

namespace ambid::ident {
namespace rational_fit_test {

using test::kPi;
using cd = std::complex<double>;

// Seed 003 eq. 7: G_N(s) = -7.19 (s - 408.56)(s + 412.90) / ((s + 107.77)(s + 89.47)(s - 53.22)).
cd beam_eq7(cd s) { return -7.19 * (s - 408.56) * (s + 412.90) / ((s + 107.77) * (s + 89.47) * (s - 53.22)); }

Eigen::VectorXd log_grid(double f0, double f1, Eigen::Index n) {
  Eigen::VectorXd f(n);
  for (Eigen::Index i = 0; i < n; ++i)
    f(i) = f0 * std::pow(f1 / f0, static_cast<double>(i) / static_cast<double>(n - 1));
  return f;
}

// The root of `roots` nearest to `target`.
cd nearest(const Eigen::VectorXcd& roots, cd target) {
  Eigen::Index best = 0;
  (roots.array() - target).abs().minCoeff(&best);
  return roots(best);
}

TEST(RationalFit, RecoversSeed003ReducedBeamModelExactly) {
  const Eigen::VectorXd f = log_grid(0.1, 100.0, 120);  // the paper's 0.1 - 100 Hz
  Eigen::VectorXcd G(f.size());
  for (Eigen::Index k = 0; k < f.size(); ++k) G(k) = beam_eq7(cd(0.0, 2.0 * kPi * f(k)));
  RationalFitOptions o;
  o.numerator_degree = 2;
  o.denominator_degree = 3;
  const RationalFit fit = fit_rational(f, G, Eigen::VectorXd(), o);
  EXPECT_EQ(fit.weighting, FitWeighting::relative);
  EXPECT_LT(fit.misfit, 1e-20);
  const Eigen::VectorXcd p = fit.model.poles(), z = fit.model.zeros();
  for (double expected : {-107.77, -89.47, 53.22})
    EXPECT_LT(std::abs(nearest(p, expected) - expected), 1e-7 * std::abs(expected)) << expected;
  for (double expected : {408.56, -412.90})
    EXPECT_LT(std::abs(nearest(z, expected) - expected), 1e-7 * std::abs(expected)) << expected;
  EXPECT_NEAR(fit.model.gain(), -7.19, 1e-7);
  // The unstable pole was not moved to the left half plane.
  EXPECT_EQ((p.real().array() > 0.0).count(), 1);
  // Realisation: same response.
  const ContinuousSystem sys = fit.model.realization();
  for (double w : {1.0, 60.0, 600.0}) {
    EXPECT_LT(std::abs(freq_response(sys, w)(0, 0) - beam_eq7(cd(0.0, w))), 1e-9 * std::abs(beam_eq7(cd(0.0, w))));
    EXPECT_LT(std::abs(fit.model.response(w) - beam_eq7(cd(0.0, w))), 1e-9 * std::abs(beam_eq7(cd(0.0, w))));
  }
}

TEST(RationalFit, SkAloneAndCeresAgreeOnExactData) {
  const Eigen::VectorXd f = log_grid(0.1, 100.0, 60);
  Eigen::VectorXcd G(f.size());
  for (Eigen::Index k = 0; k < f.size(); ++k) G(k) = beam_eq7(cd(0.0, 2.0 * kPi * f(k)));
  RationalFitOptions o;
  o.numerator_degree = 2;
  o.denominator_degree = 3;
  o.refine = false;
  const RationalFit sk = fit_rational(f, G, Eigen::VectorXd(), o);
  EXPECT_FALSE(sk.refined);
  EXPECT_GT(sk.sk_iterations, 1);
  EXPECT_LT(std::abs(nearest(sk.model.poles(), 53.22) - 53.22), 1e-6);
}

TEST(RationalFit, OrderSelectionFindsTheOrderOfExactData) {
  const Eigen::VectorXd f = log_grid(0.1, 100.0, 120);
  Eigen::VectorXcd G(f.size());
  for (Eigen::Index k = 0; k < f.size(); ++k) G(k) = beam_eq7(cd(0.0, 2.0 * kPi * f(k)));
  OrderSearchOptions o;
  o.max_denominator_degree = 5;
  const OrderSelection sel = select_rational_order(f, G, Eigen::VectorXd(), o);
  const OrderCandidate& c = sel.candidates[sel.chosen];
  EXPECT_EQ(c.denominator_degree, 3);
  EXPECT_EQ(c.numerator_degree, 2);
  EXPECT_LT(std::abs(nearest(sel.fit.model.poles(), 53.22) - 53.22), 1e-5);
}

TEST(RationalFit, LightlyDampedBeamModelEq4) {
  // Seed 003 eq. 4 with a little damping on both the zero pair (76 rad/s) and the pole pair
  // (80 rad/s): 1690 (s^2 + 1.52 s + 76^2) / ((s + 250)(s + 70)(s - 70)(s^2 + 1.6 s + 80^2)).
  auto G0 = [](cd s) {
    return 1690.0 * (s * s + 1.52 * s + 5776.0) / ((s + 250.0) * (s + 70.0) * (s - 70.0) * (s * s + 1.6 * s + 6400.0));
  };
  const Eigen::VectorXd f = log_grid(0.1, 100.0, 300);
  Eigen::VectorXcd G(f.size());
  for (Eigen::Index k = 0; k < f.size(); ++k) G(k) = G0(cd(0.0, 2.0 * kPi * f(k)));
  RationalFitOptions o;
  o.numerator_degree = 2;
  o.denominator_degree = 5;
  const RationalFit fit = fit_rational(f, G, Eigen::VectorXd(), o);
  const Eigen::VectorXcd p = fit.model.poles();
  for (cd expected : {cd(-250.0, 0.0), cd(-70.0, 0.0), cd(70.0, 0.0), cd(-0.8, std::sqrt(6400.0 - 0.64))})
    EXPECT_LT(std::abs(nearest(p, expected) - expected), 1e-5 * std::abs(expected)) << expected;
}

// The Sales rotor loop of seed 003 eq. 8 at 10 kHz, periodic multisine of N samples per period
// on its first `count` lines (N = 1000: 10 .. 500 Hz; N = 4000: 2.5 .. 500 Hz).
PeriodicFrf sales_rotor_frf(double noise_std, Eigen::Index blocks, std::uint64_t seed, Eigen::Index N = 1000,
                            Eigen::Index count = 50) {
  const double T = 1e-4;
  std::vector<Eigen::Index> lines;
  for (Eigen::Index k = 1; k <= count; ++k) lines.push_back(k);
  const DiscreteSystem plant = c2d_zoh(test::sales_rotor_system(), T);
  const StateSpaceController controller = test::sales_pd_controller(T);
  const Eigen::MatrixXd r = test::multisine(N, lines, 2 + blocks, 1.0);
  const test::LoopData d = test::simulate_loop(plant, controller, test::sales_signals(), r, noise_std, 0.0, seed);
  PeriodicFrfOptions o;
  o.sample_time = T;
  o.period_samples = N;
  o.lines = lines;
  o.transient_periods = 2;
  return estimate_periodic_frf(r, d.u, d.y, o);
}

TEST(RationalFit, UnstablePoleOfTheSalesRotorFromNoiseFreeClosedLoopData) {
  const PeriodicFrf e = sales_rotor_frf(0.0, 2, 1);
  RationalFitOptions o;
  o.numerator_degree = 0;
  o.denominator_degree = 2;
  o.zoh_sample_time = 1e-4;  // the estimate is the sampled plant
  const RationalFit fit = fit_rational(e.plant.frequency_hz, e.plant.element(0, 0), Eigen::VectorXd(), o);
  const double unstable = std::sqrt(2800.0);  // 52.915 rad/s
  const cd p = nearest(fit.model.poles(), unstable);
  RecordProperty("unstable_pole_noise_free", std::to_string(p.real()));
  EXPECT_LT(std::abs(p - unstable), 0.01 * unstable);  // the brief: 1 %
  EXPECT_LT(std::abs(p - unstable), 1e-3 * unstable);  // in fact (aliasing of the hold neglected)
  EXPECT_LT(std::abs(nearest(fit.model.poles(), -unstable) + unstable), 1e-3 * unstable);
  EXPECT_NEAR(fit.model.gain(), 840.0, 0.840);
  // Without the ZOH compensation the half-sample delay is fitted as dynamics: worse.
  o.zoh_sample_time = 0.0;
  const RationalFit raw = fit_rational(e.plant.frequency_hz, e.plant.element(0, 0), Eigen::VectorXd(), o);
  EXPECT_GT(raw.misfit, 100.0 * fit.misfit);
}

TEST(RationalFit, UnstablePoleFromNoisyDataWithNoiseWeights) {
  const double unstable = std::sqrt(2800.0);
  int within_3_std = 0;
  const int runs = 12;
  for (int run = 0; run < runs; ++run) {
    // 2.5 Hz lines: the pole (8.4 Hz) is inside the band, not below it.
    const PeriodicFrf e = sales_rotor_frf(1e-3, 8, 40 + static_cast<std::uint64_t>(run), 4000, 200);
    RationalFitOptions o;
    o.numerator_degree = 0;
    o.denominator_degree = 2;
    o.zoh_sample_time = 1e-4;
    const RationalFit fit =
        fit_rational(e.plant.frequency_hz, e.plant.element(0, 0), e.plant.element_variance(0, 0), o);
    EXPECT_EQ(fit.weighting, FitWeighting::noise);
    EXPECT_TRUE(fit.refined);
    EXPECT_GT(fit.misfit, 0.5);  // at the noise level (about 1; 14-dof variances are noisy)
    EXPECT_LT(fit.misfit, 2.0);
    const Eigen::VectorXcd p = fit.model.poles();
    Eigen::Index at = 0;
    (p.array() - unstable).abs().minCoeff(&at);
    EXPECT_LT(std::abs(p(at) - unstable), 0.01 * unstable) << run;
    EXPECT_GT(fit.pole_std(at), 0.0);
    EXPECT_LT(fit.pole_std(at), 0.01 * unstable);
    within_3_std += std::abs(p(at) - unstable) < 3.0 * fit.pole_std(at);
  }
  EXPECT_GE(within_3_std, runs - 1);
}

TEST(RationalFit, OrderSelectionWithNoiseWeights) {
  const PeriodicFrf e = sales_rotor_frf(1e-3, 8, 5);
  OrderSearchOptions o;
  o.max_denominator_degree = 4;
  o.fit.zoh_sample_time = 1e-4;
  const OrderSelection sel =
      select_rational_order(e.plant.frequency_hz, e.plant.element(0, 0), e.plant.element_variance(0, 0), o);
  const OrderCandidate& c = sel.candidates[sel.chosen];
  EXPECT_EQ(c.denominator_degree, 2);
  EXPECT_EQ(c.numerator_degree, 0);
  EXPECT_LT(std::abs(nearest(sel.fit.model.poles(), 52.915) - 52.915), 0.01 * 52.915);
  // First order cannot explain the data.
  for (const auto& cand : sel.candidates)
    if (cand.ok && cand.denominator_degree == 1) {
      EXPECT_GT(cand.validation_misfit, 10.0);
    }
}

TEST(RationalFit, RefusesBadInput) {
  const Eigen::VectorXd f = log_grid(1.0, 10.0, 4);
  const Eigen::VectorXcd G = Eigen::VectorXcd::Ones(4);
  RationalFitOptions o;
  o.numerator_degree = 2;
  o.denominator_degree = 3;
  EXPECT_THROW(fit_rational(f, G, Eigen::VectorXd(), o), InsufficientData);  // 6 parameters, 4 lines
  o.numerator_degree = 4;
  EXPECT_THROW(fit_rational(f, G, Eigen::VectorXd(), o), Error);  // improper
  o.numerator_degree = 0;
  o.denominator_degree = 1;
  o.weighting = FitWeighting::noise;
  EXPECT_THROW(fit_rational(f, G, Eigen::VectorXd(), o), Error);  // no variances
  Eigen::VectorXd bad = f;
  bad(2) = bad(1);
  o.weighting = FitWeighting::relative;
  EXPECT_THROW(fit_rational(bad, G, Eigen::VectorXd(), o), Error);
}

}  // namespace rational_fit_test
}  // namespace ambid::ident
