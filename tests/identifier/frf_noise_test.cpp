// Periodic FRF estimation with noise in the loop (measurement noise on y, fed back by the
// controller): the error falls as blocks of periods are averaged, and the reported variance
// gives confidence discs that cover the true response at about their stated confidence.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "frf_test_helpers.hpp"
#include "identifier/frequency_domain/freq_response.hpp"
#include "identifier/frequency_domain/frf_periodic.hpp"
#include "identifier/frf_types.hpp"

namespace ambid::ident {
namespace frf_noise_test {

using test::kPi;

constexpr double kT = 1e-4;
constexpr Eigen::Index kN = 1000;  // lines every 10 Hz

struct NoisyLoop {
  DiscreteSystem plant = c2d_zoh(test::sales_rotor_system(), kT);
  StateSpaceController controller = test::sales_pd_controller(kT);
  std::vector<Eigen::Index> lines;
  NoisyLoop() {
    for (Eigen::Index k = 1; k <= 50; ++k) lines.push_back(k);  // 10 .. 500 Hz
  }
  PeriodicFrf run(Eigen::Index blocks, double noise_std, std::uint64_t seed) const {
    const Eigen::MatrixXd r = test::multisine(kN, lines, 2 + blocks, 1.0);
    const test::LoopData d = test::simulate_loop(plant, controller, test::sales_signals(), r, noise_std, 0.0, seed);
    PeriodicFrfOptions o;
    o.sample_time = kT;
    o.period_samples = kN;
    o.lines = lines;
    o.transient_periods = 2;
    return estimate_periodic_frf(r, d.u, d.y, o);
  }
  std::complex<double> G(double f) const { return freq_response(plant, 2.0 * kPi * f)(0, 0); }
  // T_yr = G / (1 - K G), T_ur = 1 / (1 - K G) (r added to the controller output).
  std::complex<double> S(double f) const {
    const double w = 2.0 * kPi * f;
    return 1.0 / (1.0 - freq_response(controller, w)(0, 0) * G(f));
  }
};

double rms_relative_error(const NoisyLoop& loop, const PeriodicFrf& e) {
  double s = 0.0;
  for (Eigen::Index l = 0; l < e.plant.lines(); ++l)
    s += std::norm(e.plant.value[static_cast<std::size_t>(l)](0, 0) / loop.G(e.plant.frequency_hz(l)) - 1.0);
  return std::sqrt(s / static_cast<double>(e.plant.lines()));
}

// The reported noise std relative to |G|, rms over the lines.
double rms_relative_std(const NoisyLoop& loop, const PeriodicFrf& e) {
  double s = 0.0;
  for (Eigen::Index l = 0; l < e.plant.lines(); ++l)
    s += e.plant.variance[static_cast<std::size_t>(l)](0, 0) / std::norm(loop.G(e.plant.frequency_hz(l)));
  return std::sqrt(s / static_cast<double>(e.plant.lines()));
}

TEST(FrfNoise, ErrorFallsAsBlocksAreAveraged) {
  const NoisyLoop loop;
  // Same noise level, 2, 8 and 32 blocks, three seeds each: the rms error should fall like
  // 1/sqrt(blocks), i.e. by 2 per factor 4.
  double e2 = 0.0, e8 = 0.0, e32 = 0.0, s8 = 0.0, s32 = 0.0;  // s: the reported std
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const PeriodicFrf p2 = loop.run(2, 1e-3, seed), p8 = loop.run(8, 1e-3, seed + 10),
                      p32 = loop.run(32, 1e-3, seed + 20);
    e2 += rms_relative_error(loop, p2);
    e8 += rms_relative_error(loop, p8);
    e32 += rms_relative_error(loop, p32);
    s8 += rms_relative_std(loop, p8);
    s32 += rms_relative_std(loop, p32);
  }
  EXPECT_GT(e2, 1e-3);  // noise is visible
  EXPECT_NEAR(e8 / e2, 0.5, 0.15);
  EXPECT_NEAR(e32 / e8, 0.5, 0.15);
  EXPECT_NEAR(e32 / e2, 0.25, 0.08);
  // The reported std (rms over lines: the root of the mean sample variance, unbiased) falls
  // by 2 from 8 to 32 blocks and matches the actual error there. Not from 2 blocks: with 2
  // blocks the rms error is ~130 % of |G| at this noise level, where the linearised variance of
  // the ratio T_yr / T_ur no longer describes it (measured: reported std 8/2 ratio 0.61,
  // actual error / reported std 1.35 at 2 blocks against 0.92 and 1.12 at 8 and 32).
  EXPECT_NEAR(s32 / s8, 0.5, 0.05);
  EXPECT_NEAR(e8 / s8, 1.0, 0.2);
  EXPECT_NEAR(e32 / s32, 1.0, 0.2);
  RecordProperty("error_over_reported_std_8_blocks", std::to_string(e8 / s8));
  RecordProperty("error_over_reported_std_32_blocks", std::to_string(e32 / s32));
  RecordProperty("error_ratio_8_to_2_blocks", std::to_string(e8 / e2));
  RecordProperty("error_ratio_32_to_8_blocks", std::to_string(e32 / e8));
  RecordProperty("reported_std_ratio_32_to_8_blocks", std::to_string(s32 / s8));
}

TEST(FrfNoise, ConfidenceDiscsCoverTheTruth) {
  const NoisyLoop loop;
  const double confidence = 0.95;
  int covered_g = 0, covered_yr = 0, covered_ur = 0, total = 0;
  double variance_ratio = 0.0;  // mean |error|^2 / reported variance of G
  for (std::uint64_t seed = 100; seed < 120; ++seed) {
    const PeriodicFrf e = loop.run(8, 1e-3, seed);
    ASSERT_TRUE(e.plant.has_variance());
    ASSERT_DOUBLE_EQ(e.plant.variance_dof, 14.0);
    const double factor = confidence_radius_factor(confidence, e.plant.variance_dof);
    for (Eigen::Index l = 0; l < e.plant.lines(); ++l) {
      const auto li = static_cast<std::size_t>(l);
      const double f = e.plant.frequency_hz(l);
      const std::complex<double> G0 = loop.G(f), S0 = loop.S(f);
      covered_g += std::norm(e.plant.value[li](0, 0) - G0) <= factor * e.plant.variance[li](0, 0);
      covered_yr += std::norm(e.output_from_reference.value[li](0, 0) - G0 * S0) <=
                    factor * e.output_from_reference.variance[li](0, 0);
      covered_ur +=
          std::norm(e.input_from_reference.value[li](0, 0) - S0) <= factor * e.input_from_reference.variance[li](0, 0);
      variance_ratio += std::norm(e.plant.value[li](0, 0) - G0) / e.plant.variance[li](0, 0);
      ++total;
    }
  }
  const double cg = static_cast<double>(covered_g) / total, cyr = static_cast<double>(covered_yr) / total,
               cur = static_cast<double>(covered_ur) / total;
  EXPECT_GE(cg, 0.90);
  EXPECT_LE(cg, 0.99);
  EXPECT_GE(cyr, 0.90);
  EXPECT_LE(cyr, 0.99);
  EXPECT_GE(cur, 0.90);
  EXPECT_LE(cur, 0.99);
  // E[|e|^2 / s^2] = E[F(2, 14)] = 14 / 12 for a calibrated variance.
  EXPECT_NEAR(variance_ratio / total, 14.0 / 12.0, 0.2);
  RecordProperty("coverage_G", std::to_string(cg));
  RecordProperty("coverage_Tyr", std::to_string(cyr));
  RecordProperty("coverage_Tur", std::to_string(cur));
}

TEST(FrfNoise, LineNoiseVarianceMatchesTheSimulatedNoise) {
  // The y phasor noise of one period: the measured y = S (G r + v) carries S v (the noise fed
  // back through the loop), so var = |S|^2 4 sigma^2 / N for white v of std sigma.
  const NoisyLoop loop;
  const double sigma = 1e-3;
  const PeriodicFrf e = loop.run(32, sigma, 7);
  ASSERT_EQ(e.output_noise_variance.rows(), 50);
  for (Eigen::Index l = 0; l < 50; l += 5) {
    const double S2 = std::norm(loop.S(e.plant.frequency_hz(l)));
    EXPECT_NEAR(e.output_noise_variance(l, 0) / (4.0 * sigma * sigma / kN * S2), 1.0, 0.6) << l;
  }
}

}  // namespace frf_noise_test
}  // namespace ambid::ident
