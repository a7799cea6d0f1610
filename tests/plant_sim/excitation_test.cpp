#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <complex>
#include <numbers>
#include <set>
#include <vector>

#include "core/error.hpp"
#include "plant_sim/excitation.hpp"

namespace ambid::sim {
namespace excitation_test {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Direct DFT of x (independent of the generator's FFT): X[k] = sum_n x[n] exp(-2 pi i k n / N).
std::vector<std::complex<double>> dft(const Eigen::VectorXd& x) {
  const Eigen::Index N = x.size();
  std::vector<std::complex<double>> X(static_cast<std::size_t>(N));
  for (Eigen::Index k = 0; k < N; ++k) {
    std::complex<double> sum = 0.0;
    for (Eigen::Index n = 0; n < N; ++n)
      sum += x(n) * std::polar(1.0, -kTwoPi * static_cast<double>((k * n) % N) / static_cast<double>(N));
    X[static_cast<std::size_t>(k)] = sum;
  }
  return X;
}

TEST(Prbs, MaximalPeriodAndBalanceForEveryRegisterLength) {
  for (int n = 2; n <= 18; ++n) {
    PrbsOptions o;
    o.register_length = n;
    o.amplitude = 0.5;
    o.seed = static_cast<std::uint64_t>(n);
    const Eigen::Index P = (Eigen::Index{1} << n) - 1;
    const Excitation e = prbs(o, 2 * P, 1e-4);
    const Eigen::VectorXd s = e.samples.col(0);
    // Periodic with period P ...
    EXPECT_TRUE(s.head(P) == s.tail(P)) << "n = " << n;
    // ... and no shorter period dividing it (P is prime or its divisors are checked).
    for (Eigen::Index d = 1; d < P; ++d) {
      if (P % d != 0) continue;
      EXPECT_GT((s.head(P - d) - s.segment(d, P - d)).cwiseAbs().maxCoeff(), 0.0) << "n = " << n << " has period " << d;
    }
    // Balance: 2^(n-1) ones, 2^(n-1) - 1 minus ones per period.
    EXPECT_DOUBLE_EQ(s.head(P).sum(), 0.5) << "n = " << n;
    EXPECT_EQ(e.description.json()["period_samples"], P);
  }
}

TEST(Prbs, AutocorrelationIsTwoValued) {
  PrbsOptions o;
  o.register_length = 7;
  const Eigen::Index P = 127;
  const Eigen::VectorXd s = prbs(o, P, 1e-4).samples.col(0);
  for (Eigen::Index lag = 0; lag < P; ++lag) {
    double r = 0.0;
    for (Eigen::Index k = 0; k < P; ++k) r += s(k) * s((k + lag) % P);
    EXPECT_DOUBLE_EQ(r, lag == 0 ? double(P) : -1.0) << "lag " << lag;
  }
}

TEST(Prbs, ClockDividerSeedAndChannels) {
  PrbsOptions o;
  o.register_length = 9;
  o.clock_divider = 3;
  o.channels = 3;
  o.seed = 11;
  const Excitation a = prbs(o, 3000, 1e-4), b = prbs(o, 3000, 1e-4);
  EXPECT_EQ(a.samples, b.samples);  // bit-identical for the same seed
  EXPECT_EQ(a.description.json()["period_samples"], 511 * 3);
  for (Eigen::Index k = 0; k + 3 <= 3000; k += 3)
    for (int j = 0; j < 3; ++j) {
      EXPECT_EQ(a.samples(k, j), a.samples(k + 1, j));
      EXPECT_EQ(a.samples(k, j), a.samples(k + 2, j));
    }
  // Channels are shifts of one m-sequence spaced by a third of the period.
  const auto shifts = a.description.json()["channel_shifts"];
  EXPECT_EQ((shifts[1].get<std::uint64_t>() + 511 - shifts[0].get<std::uint64_t>()) % 511, 170U);
  for (Eigen::Index k = 0; k < 3 * (511 - 170); ++k) EXPECT_EQ(a.samples(k, 1), a.samples(k + 3 * 170, 0));
  o.seed = 12;
  EXPECT_NE(prbs(o, 3000, 1e-4).samples, a.samples);
}

TEST(RandomSignal, IndependentReproducibleChannels) {
  RandomOptions o;
  o.kind = NoiseKind::gaussian;
  o.amplitude = 2.0;
  o.channels = 2;
  o.seed = 99;
  const Excitation a = random_signal(o, 20000, 1e-4);
  EXPECT_EQ(a.samples, random_signal(o, 20000, 1e-4).samples);
  const Eigen::VectorXd x = a.samples.col(0), y = a.samples.col(1);
  const double sx = std::sqrt(x.squaredNorm() / 20000), sy = std::sqrt(y.squaredNorm() / 20000);
  EXPECT_NEAR(sx, 2.0, 0.05);
  EXPECT_NEAR(sy, 2.0, 0.05);
  EXPECT_LT(std::abs(x.dot(y)) / (20000 * sx * sy), 0.03);
  o.kind = NoiseKind::binary;
  const Excitation b = random_signal(o, 1000, 1e-4);
  EXPECT_TRUE((b.samples.array().abs() == 2.0).all());
  o.seed = 100;
  EXPECT_NE(random_signal(o, 1000, 1e-4).samples, b.samples);
}

TEST(Multisine, EnergyExactlyOnTheRequestedLinesAndRmsNormalised) {
  MultisineOptions o;
  o.period_samples = 1000;
  o.periods = 2;
  o.f_min = 95.0;  // T = 1e-4: lines every 10 Hz -> k = 10..30
  o.f_max = 300.0;
  o.level = 0.3;
  o.seed = 5;
  const Excitation e = multisine(o, 1e-4);
  ASSERT_EQ(e.samples.rows(), 2000);
  const Eigen::VectorXd first = e.samples.col(0).head(1000);
  EXPECT_EQ((first - e.samples.col(0).tail(1000)).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_NEAR(std::sqrt(first.squaredNorm() / 1000), 0.3, 1e-12);
  EXPECT_NEAR(e.description.json()["rms"].get<double>(), 0.3, 1e-12);

  std::set<Eigen::Index> expected;
  for (Eigen::Index k = 10; k <= 30; ++k) expected.insert(k);
  const auto lines = e.description.json()["lines"].get<std::vector<Eigen::Index>>();
  EXPECT_EQ(std::set<Eigen::Index>(lines.begin(), lines.end()), expected);
  EXPECT_DOUBLE_EQ(e.description.json()["frequencies"][0].get<double>(), 100.0);

  const auto X = dft(first);
  const double flat = 0.3 / std::sqrt(21 / 2.0);  // equal amplitude on 21 lines
  for (Eigen::Index k = 0; k <= 500; ++k) {
    const double magnitude = std::abs(X[static_cast<std::size_t>(k)]);
    if (expected.count(k))
      EXPECT_NEAR(magnitude, 500.0 * flat, 1e-9) << "line " << k;
    else
      EXPECT_LT(magnitude, 1e-9) << "line " << k;
  }
}

TEST(Multisine, GivenSpectrumPeakNormalisationAndSeeds) {
  MultisineOptions o;
  o.period_samples = 512;
  o.f_min = 1.0;
  o.f_max = 2000.0;
  o.normalisation = Normalisation::peak;
  o.level = 1.5;
  o.amplitude_spectrum = [](double f) { return 1.0 / f; };
  o.seed = 1;
  const double T = 1e-4;
  const Excitation a = multisine(o, T);
  EXPECT_NEAR(a.samples.cwiseAbs().maxCoeff(), 1.5, 1e-12);
  const auto X = dft(a.samples.col(0));
  const auto lines = a.description.json()["lines"].get<std::vector<Eigen::Index>>();
  const auto amplitudes = a.description.json()["line_amplitudes"].get<std::vector<double>>();
  const double line_spacing = 1.0 / (512 * T);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const double f = static_cast<double>(lines[i]) * line_spacing;
    EXPECT_NEAR(std::abs(X[static_cast<std::size_t>(lines[i])]), 256.0 * amplitudes[i], 1e-9);
    EXPECT_NEAR(amplitudes[i] * f, amplitudes[0] * line_spacing * double(lines[0]), 1e-9);
  }
  EXPECT_EQ(multisine(o, T).samples, a.samples);
  o.seed = 2;
  EXPECT_NE(multisine(o, T).samples, a.samples);
}

TEST(Multisine, HadamardPatternSeparatesChannels) {
  MultisineOptions o;
  o.period_samples = 200;
  o.f_min = 50.0;
  o.f_max = 500.0;
  o.channels = 3;  // order 4
  o.periods = 8;
  o.pattern = ChannelPattern::hadamard;
  o.seed = 3;
  const double T = 1e-3;
  const Excitation e = multisine(o, T);
  const Eigen::MatrixXd H = hadamard(4);
  EXPECT_TRUE((H * H.transpose()).isApprox(4.0 * Eigen::MatrixXd::Identity(4, 4)));
  const Eigen::VectorXd s = e.samples.col(0).head(200);  // H(0, 0) = 1
  for (int p = 0; p < 8; ++p)
    for (int j = 0; j < 3; ++j) EXPECT_TRUE(e.samples.block(200 * p, j, 200, 1) == H(j, p % 4) * s) << p << " " << j;
  // Combining the period blocks with channel i's signs keeps channel i and cancels the rest.
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Eigen::VectorXd combined = Eigen::VectorXd::Zero(200);
      for (int p = 0; p < 4; ++p) combined += H(i, p) * e.samples.block(200 * p, j, 200, 1);
      EXPECT_NEAR((combined - (i == j ? 4.0 : 0.0) * s).norm(), 0.0, 1e-12) << i << " " << j;
    }
  EXPECT_EQ(e.description.json()["channel_pattern"], "hadamard");
  o.periods = 6;
  EXPECT_THROW(multisine(o, T), Error);
}

TEST(Multisine, RejectsAnEmptyBand) {
  MultisineOptions o;
  o.period_samples = 100;
  o.f_min = 11.0;
  o.f_max = 19.0;  // lines every 10 Hz at T = 1e-3
  EXPECT_THROW(multisine(o, 1e-3), Error);
}

// Frequency from two successive zero crossings (linear interpolation) around sample k.
double zero_crossing_frequency(const Eigen::VectorXd& x, Eigen::Index from, double T, double* at) {
  std::vector<double> crossings;
  for (Eigen::Index k = from; k + 1 < x.size() && crossings.size() < 2; ++k)
    if ((x(k) < 0) != (x(k + 1) < 0)) crossings.push_back((static_cast<double>(k) + x(k) / (x(k) - x(k + 1))) * T);
  *at = 0.5 * (crossings[0] + crossings[1]);
  return 0.5 / (crossings[1] - crossings[0]);
}

TEST(Chirp, InstantaneousFrequencyAtStartAndEnd) {
  const double T = 1e-5;
  const Eigen::Index samples = 100000;  // 1 s
  for (const Sweep sweep : {Sweep::linear, Sweep::logarithmic}) {
    ChirpOptions o;
    o.f_start = 100.0;
    o.f_end = 1000.0;
    o.sweep = sweep;
    const Excitation e = chirp(o, samples, T);
    EXPECT_DOUBLE_EQ(chirp_frequency(o, 1.0, 0.0), 100.0);
    EXPECT_NEAR(chirp_frequency(o, 1.0, 1.0), 1000.0, 1e-9);
    double at = 0.0;
    const Eigen::VectorXd x = e.samples.col(0);
    const double f_start = zero_crossing_frequency(x, 1, T, &at);
    EXPECT_NEAR(f_start, chirp_frequency(o, 1.0, at), 1e-3 * f_start);
    EXPECT_NEAR(at, 0.0075, 0.0003);  // between the first crossings at ~5 ms and ~10 ms
    const double f_end = zero_crossing_frequency(x, samples - 200, T, &at);
    EXPECT_NEAR(f_end, chirp_frequency(o, 1.0, at), 1e-3 * f_end);
    EXPECT_GT(f_end, 990.0);
  }
}

TEST(SteppedSine, WholePeriodsAtSnappedFrequencies) {
  SteppedSineOptions o;
  o.frequencies = {13.0, 170.0, 1234.5};
  o.measure_periods = 5;
  o.settle_time = 0.01;
  o.amplitude = 0.2;
  const double T = 1e-4;
  const Excitation e = stepped_sine(o, T);
  const auto& steps = e.description.json()["steps"];
  ASSERT_EQ(steps.size(), 3U);
  Eigen::Index total = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    const double f = steps[i]["frequency"].get<double>();
    const auto M = steps[i]["measure_samples"].get<Eigen::Index>();
    const auto start = steps[i]["measure_start_sample"].get<Eigen::Index>();
    EXPECT_EQ(steps[i]["settle_samples"], 100);
    EXPECT_NEAR(f, o.frequencies[i], o.frequencies[i] * o.frequencies[i] * T / 5.0);
    EXPECT_NEAR(f * static_cast<double>(M) * T, 5.0, 1e-12);
    // Whole periods: all the energy of the measured block is on DFT line 5.
    const auto X = dft(e.samples.col(0).segment(start, M));
    for (Eigen::Index k = 0; k <= M / 2; ++k) {
      const double magnitude = std::abs(X[static_cast<std::size_t>(k)]);
      if (k == 5)
        EXPECT_NEAR(magnitude, 0.1 * static_cast<double>(M), 1e-9 * static_cast<double>(M));
      else
        EXPECT_LT(magnitude, 1e-9 * static_cast<double>(M)) << "step " << i << " line " << k;
    }
    total += 100 + M;
  }
  EXPECT_EQ(e.samples.rows(), total);
}

}  // namespace excitation_test
}  // namespace ambid::sim
