// Periodic excitations from a generator other than `ambid sim` (written here, independent of
// plant_sim/excitation.cpp), fed to plant_sim's closed-loop runner (nonlinear amb1dof_voltage
// under its LQR observer controller) with no excitation description in the sidecar: analyse_frf
// must find the period, the whole periods and each reference's lines in r alone, and recover
// the analytic linear plant at every excited line; a random (never repeating) PRBS stays Welch.
// One reference (the seed 003 rotor loop, simulated sample-exactly): exact DFT lines after a late
// start and with a partial last period; a sidecar description that r contradicts is ignored.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "frf_test_helpers.hpp"
#include "identifier/frequency_domain/freq_response.hpp"
#include "identifier/frf_analysis.hpp"
#include "plant_sim/amb1dof_voltage.hpp"
#include "plant_sim/closed_loop.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::ident {
namespace frf_foreign_periodic_test {

using test::kPi;
constexpr double kT = 1e-4;
// Records (multisine phases and noise) of the coverage test.
constexpr std::uint64_t kCoverageSeeds[] = {23, 24, 25, 26, 27, 28};

// Random-phase multisine, rms `level` per channel, `samples` long (need not end on a whole
// period): channel c gets the lines lines[c] of the N-sample grid.
Eigen::MatrixXd foreign_multisine(Eigen::Index N, const std::vector<std::vector<Eigen::Index>>& lines,
                                  Eigen::Index samples, double level, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * kPi);
  Eigen::MatrixXd period = Eigen::MatrixXd::Zero(N, static_cast<Eigen::Index>(lines.size()));
  for (std::size_t c = 0; c < lines.size(); ++c) {
    for (const Eigen::Index k : lines[c]) {
      const double phi = phase(rng);
      for (Eigen::Index n = 0; n < N; ++n)
        period(n, static_cast<Eigen::Index>(c)) += std::cos(2.0 * kPi * static_cast<double>(k * n) / double(N) + phi);
    }
    const double rms = period.col(static_cast<Eigen::Index>(c)).norm() / std::sqrt(double(N));
    period.col(static_cast<Eigen::Index>(c)) *= level / rms;
  }
  Eigen::MatrixXd out(samples, period.cols());
  for (Eigen::Index n = 0; n < samples; ++n) out.row(n) = period.row(n % N);
  return out;
}

// Maximum-length sequence of a 9-bit Fibonacci LFSR (a[n+9] = a[n+4] xor a[n], x^9 + x^4 + 1
// primitive: period 511),
// each bit held `hold` samples, +-amplitude, repeated; channel 2 is channel 1 shifted by half
// the sequence.
Eigen::MatrixXd repeated_mls(int hold, Eigen::Index samples, double amplitude) {
  std::vector<double> bits;
  unsigned state = 0x1FF;
  for (int i = 0; i < 511; ++i) {
    bits.push_back((state & 1u) ? amplitude : -amplitude);
    const unsigned feedback = ((state >> 0) ^ (state >> 4)) & 1u;
    state = (state >> 1) | (feedback << 8);
  }
  const Eigen::Index N = 511 * hold;
  Eigen::MatrixXd out(samples, 2);
  for (Eigen::Index n = 0; n < samples; ++n)
    for (Eigen::Index c = 0; c < 2; ++c) out(n, c) = bits[static_cast<std::size_t>(((n + c * (N / 2)) % N) / hold)];
  return out;
}

// A binary signal whose every clock is an independent coin flip: never periodic.
Eigen::MatrixXd random_binary(Eigen::Index samples, int hold, double amplitude, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Eigen::MatrixXd out(samples, 2);
  for (Eigen::Index n = 0; n < samples; n += hold)
    for (Eigen::Index c = 0; c < 2; ++c) {
      const double v = (rng() & 1u) ? amplitude : -amplitude;
      for (Eigen::Index m = n; m < std::min(samples, n + hold); ++m) out(m, c) = v;
    }
  return out;
}

// plant_sim's bearing and controller with our r; the sidecar keeps no excitation description.
Experiment run_bearing(const Eigen::MatrixXd& r, double position_noise = 0.0, double current_noise = 0.0,
                       std::uint64_t noise_seed = 11) {
  sim::ScenarioOptions s;
  s.duration = static_cast<double>(r.rows()) * kT;
  s.sample_time = kT;
  s.position_noise = position_noise;
  s.current_noise = current_noise;
  s.seed = noise_seed;
  sim::Scenario scenario = sim::build_scenario(s);
  scenario.options.excitation = r;
  scenario.header.extra.json().erase("excitation");
  return sim::run_closed_loop(*scenario.truth, scenario.header, scenario.options);
}

Eigen::MatrixXcd linear_bearing(double f) {
  static const DiscreteSystem plant = c2d_zoh(sim::Amb1dofVoltage().linearize(), kT);
  return freq_response(plant, 2.0 * kPi * f);
}

double unstable_pole_truth() { return poles(sim::Amb1dofVoltage().linearize()).real().maxCoeff(); }

double fitted_unstable_pole(const FrfReport& report) {
  for (const FittedPair& p : report.fits) {
    if (p.name != "x/u1") continue;
    const Eigen::VectorXcd poles = p.fit.model.poles();
    double found = -1.0;
    for (Eigen::Index i = 0; i < poles.size(); ++i)
      if (poles(i).real() > 0.0 && std::abs(poles(i).imag()) < 1e-6 * std::abs(poles(i)))
        found = std::max(found, poles(i).real());
    return found;
  }
  return -1.0;
}

// Worst magnitude ratio error and phase error (degrees) over the excited lines below 1 kHz of
// the four physical pairs, and the worst relative matrix error.
struct Accuracy {
  double magnitude = 0.0, phase_deg = 0.0, matrix = 0.0;
  int lines = 0;
};
Accuracy accuracy(const FrfReport& report) {
  Accuracy a;
  const std::pair<int, int> pairs[] = {{0, 0}, {0, 1}, {1, 0}, {2, 1}};  // x/u1, x/u2, i1/u1, i2/u2
  for (Eigen::Index l = 0; l < report.frequency_hz.size(); ++l) {
    const double f = report.frequency_hz(l);
    if (f >= 1000.0) continue;
    const Eigen::MatrixXcd G0 = linear_bearing(f);
    const Eigen::MatrixXcd& G = report.plant.value[static_cast<std::size_t>(l)];
    for (const auto& [i, j] : pairs) {
      a.magnitude = std::max(a.magnitude, std::abs(std::abs(G(i, j)) / std::abs(G0(i, j)) - 1.0));
      a.phase_deg = std::max(a.phase_deg, std::abs(test::phase_error_deg(G(i, j), G0(i, j))));
    }
    a.matrix = std::max(a.matrix, (G - G0).norm() / G0.norm());
    ++a.lines;
  }
  return a;
}

void record(const char* what, const Accuracy& a, double pole) {
  ::testing::Test::RecordProperty(std::string(what) + "_worst_magnitude", test::scientific(a.magnitude));
  ::testing::Test::RecordProperty(std::string(what) + "_worst_phase_deg", test::scientific(a.phase_deg));
  ::testing::Test::RecordProperty(std::string(what) + "_worst_matrix", test::scientific(a.matrix));
  ::testing::Test::RecordProperty(std::string(what) + "_unstable_pole", test::scientific(pole));
}

// 0.2 s period (5 Hz grid), r1 on the odd lines, r2 on the even lines, 5 Hz to 1 kHz; 4.05 s:
// 20 whole periods and a quarter.
std::vector<std::vector<Eigen::Index>> zippered_lines() {
  std::vector<std::vector<Eigen::Index>> lines(2);
  for (Eigen::Index k = 1; k <= 200; ++k) lines[static_cast<std::size_t>((k + 1) % 2)].push_back(k);
  return lines;
}

TEST(FrfForeignPeriodic, ZipperedMultisineIsDetectedAndGivesTheLinearPlant) {
  const Experiment e = run_bearing(foreign_multisine(2000, zippered_lines(), 40500, 0.05, 21));
  const FrfReport report = analyse_frf(e);
  ASSERT_EQ(report.method, "periodic");
  EXPECT_EQ(report.excitation, "unknown");
  ASSERT_TRUE(report.periodic.has_value());
  const PeriodicExcitation& p = *report.periodic;
  EXPECT_EQ(p.source, "r");
  EXPECT_EQ(p.estimator, "local rational");
  EXPECT_EQ(p.period_samples, 2000);
  EXPECT_EQ(p.whole_periods, 20);
  EXPECT_EQ(p.transient_periods, 1);
  EXPECT_EQ(p.periods_used, 19);
  EXPECT_EQ(p.lines, zippered_lines());
  ASSERT_EQ(report.frequency_hz.size(), 200);  // every line excited by either reference
  EXPECT_NEAR(report.frequency_hz(0), 5.0, 1e-9);
  EXPECT_NEAR(report.frequency_hz(199), 1000.0, 1e-9);

  const Accuracy a = accuracy(report);
  const double pole = fitted_unstable_pole(report), truth = unstable_pole_truth();
  record("zippered", a, pole);
  EXPECT_EQ(a.lines, 199);
  EXPECT_LT(a.magnitude, 0.01);
  EXPECT_LT(a.phase_deg, 1.0);
  EXPECT_LT(std::abs(pole - truth), 0.005 * truth) << pole << " vs " << truth;
}

TEST(FrfForeignPeriodic, RepeatedMaximumLengthPrbsIsDetectedAndGivesTheLinearPlant) {
  // 511 bits held 4 samples: period 2044 samples (0.2044 s, a 4.892 Hz grid); 4 s hold 19.57
  // periods. Both channels excite every line (a half-period shift apart).
  const Experiment e = run_bearing(repeated_mls(4, 40000, 0.05));
  FrfAnalysisOptions o;
  o.f_max = 1000.0;  // the 1020 lines to 5 kHz take 5x longer and are not checked
  const FrfReport report = analyse_frf(e, o);
  ASSERT_EQ(report.method, "periodic");
  ASSERT_TRUE(report.periodic.has_value());
  const PeriodicExcitation& p = *report.periodic;
  EXPECT_EQ(p.period_samples, 2044);
  EXPECT_EQ(p.whole_periods, 19);
  EXPECT_EQ(p.periods_used, 18);
  ASSERT_EQ(p.lines.size(), 2u);
  // Every line to 1 kHz (the hold's first spectral null is at k = 511, 2.5 kHz).
  ASSERT_EQ(p.lines[0].size(), 204u);
  EXPECT_EQ(p.lines[0].front(), 1);
  EXPECT_EQ(p.lines[0].back(), 204);
  EXPECT_EQ(p.lines[1], p.lines[0]);

  const Accuracy a = accuracy(report);
  const double pole = fitted_unstable_pole(report), truth = unstable_pole_truth();
  record("mls", a, pole);
  EXPECT_EQ(a.lines, 204);
  EXPECT_LT(a.magnitude, 0.01);
  EXPECT_LT(a.phase_deg, 1.0);
  EXPECT_LT(std::abs(pole - truth), 0.005 * truth) << pole << " vs " << truth;
}

// Coverage of the noise bounds in one frequency band: values inside their 95 % bound, and
// the mean of |G - G0|^2 / variance (36 / 34 = 1.06 for a calibrated variance on 36 degrees of
// freedom, E[F(2, 36)]).
struct BandCoverage {
  double f_low, f_high;
  int inside = 0, total = 0;
  double ratio_sum = 0.0;
  double coverage() const { return double(inside) / double(total); }
  double mean_ratio() const { return ratio_sum / double(total); }
};

TEST(FrfForeignPeriodic, NoisyBoundsCoverTheTruthAtTheirConfidence) {
  // 0.1 um on x, 1 mA on each current; kCoverageSeeds records of 20 periods (19 used).
  // Every element of every line: |G - G0| <= bound at 95 %, the bound from the period-to-period
  // scatter of the estimator used (the local rational model of each period) with the loop's
  // transient separated, on 2 (19 - 1) degrees of freedom (an F(2, 36) quantile). Per band,
  // so that bounds too wide where the loop's slow modes are (the plain scatter: 4-fold below
  // 50 Hz, 100 % covered there) cannot hide behind the many lines above. The values are not
  // independent (the six elements of a line share its periods' noise, neighbouring lines the
  // local model's window): about 1200 independent lines-and-records in all, a binomial
  // standard deviation of 0.63 % at 95 %. Measured (6 records): below 50 Hz 94.1 % (mean ratio
  // 1.02), 50-200 Hz 95.2 % (0.94), 200-1000 Hz 97.2 % (0.86: still 1.2-fold wide, cause
  // open), 96.7 % in all; the plain scatter gave 100 % (0.23), 99.4 % (0.54), 97.9 % (0.78).
  std::vector<BandCoverage> bands = {{0.0, 50.0}, {50.0, 200.0}, {200.0, 1000.5}};
  for (const std::uint64_t seed : kCoverageSeeds) {
    const Experiment e = run_bearing(foreign_multisine(2000, zippered_lines(), 40000, 0.05, seed), 1e-7, 1e-3, seed);
    FrfAnalysisOptions o;
    o.fit = false;
    const FrfReport report = analyse_frf(e, o);
    ASSERT_EQ(report.method, "periodic");
    ASSERT_EQ(report.periodic->periods_used, 19);
    ASSERT_DOUBLE_EQ(report.plant.variance_dof, 36.0);
    for (const PlantPair& pair : report.pairs) {
      ASSERT_EQ(pair.bound.size(), report.frequency_hz.size());
      const Eigen::Index i = pair.output == "x" ? 0 : pair.output == "i1" ? 1 : 2;
      const Eigen::Index j = pair.input == "u1" ? 0 : 1;
      for (Eigen::Index l = 0; l < report.frequency_hz.size(); ++l) {
        const double f = report.frequency_hz(l);
        const std::complex<double> truth = linear_bearing(f)(i, j);
        const auto band = std::find_if(bands.begin(), bands.end(),
                                       [f](const BandCoverage& b) { return f >= b.f_low && f < b.f_high; });
        ASSERT_NE(band, bands.end()) << f;
        band->inside += std::abs(pair.value(l) - truth) <= pair.bound(l) ? 1 : 0;
        band->ratio_sum += std::norm(pair.value(l) - truth) / pair.variance(l);
        ++band->total;
      }
    }
  }
  int inside = 0, total = 0;
  for (const BandCoverage& b : bands) {
    const std::string name = std::to_string(int(b.f_low)) + "_" + std::to_string(int(b.f_high)) + "_hz";
    RecordProperty("noisy_coverage_95_" + name, test::scientific(b.coverage()));
    RecordProperty("noisy_error_over_variance_" + name, test::scientific(b.mean_ratio()));
    std::cout << b.f_low << "-" << b.f_high << " Hz: coverage of the 95 % bounds " << b.coverage() << " of " << b.total
              << ", mean |G - G0|^2 / variance " << b.mean_ratio() << "\n";
    EXPECT_GT(b.coverage(), 0.92) << b.f_low;
    EXPECT_LT(b.coverage(), 0.985) << b.f_low;
    EXPECT_GT(b.mean_ratio(), 0.75) << b.f_low;
    EXPECT_LT(b.mean_ratio(), 1.4) << b.f_low;
    inside += b.inside;
    total += b.total;
  }
  EXPECT_EQ(total, 1200 * std::ssize(kCoverageSeeds));
  const double coverage = double(inside) / double(total);
  RecordProperty("noisy_coverage_95", test::scientific(coverage));
  std::cout << "coverage of the 95 % bounds: " << coverage << " of " << total << " values\n";
  EXPECT_GT(coverage, 0.935);  // 95 % +- 2.5 % (4 binomial standard deviations)
  EXPECT_LT(coverage, 0.975);
}

TEST(FrfForeignPeriodic, RandomPrbsThatNeverRepeatsStaysWelch) {
  const Experiment e = run_bearing(random_binary(40000, 4, 0.05, 5));
  FrfAnalysisOptions o;
  o.fit = false;
  const FrfReport report = analyse_frf(e, o);
  EXPECT_EQ(report.method, "welch");
  EXPECT_FALSE(report.periodic.has_value());
  EXPECT_TRUE(std::any_of(report.notes.begin(), report.notes.end(),
                          [](const std::string& n) { return n.find("does not repeat") != std::string::npos; }));
}

// The seed 003 rotor under its PD controller (frf_test_helpers.hpp), T = 1 ms, driven by a
// multisine on the odd lines of a 500-sample period (2 Hz grid, 2-198 Hz) switched on at sample
// 300, 8 whole periods and 123 samples.
Experiment rotor_record() {
  const double T = 1e-3;
  std::vector<std::vector<Eigen::Index>> odd(1);
  for (Eigen::Index k = 1; k < 100; k += 2) odd[0].push_back(k);
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(300 + 8 * 500 + 123, 1);
  r.bottomRows(8 * 500 + 123) = foreign_multisine(500, odd, 8 * 500 + 123, 1.0, 5);
  const StateSpaceController K = test::sales_pd_controller(T);
  const test::LoopData d = test::simulate_loop(c2d_zoh(test::sales_rotor_system(), T), K, test::sales_signals(), r);
  Experiment e;
  e.name = "rotor";
  e.sample_time = T;
  e.plant.model = "sales_rotor";
  e.y_names = {"y"};
  e.u_names = {"u"};
  e.r_names = {"r"};
  e.operating_point = {{"y", 0.0}, {"u", 0.0}};
  e.controller = K;
  e.t = Eigen::VectorXd::LinSpaced(r.rows(), 0.0, static_cast<double>(r.rows() - 1) * T);
  e.y = d.y;
  e.u = d.u;
  e.r = r;
  return e;
}

TEST(FrfForeignPeriodic, OneReferenceIsAnalysedAtItsExactLines) {
  const Experiment e = rotor_record();
  FrfAnalysisOptions o;
  o.fit = false;
  const FrfReport report = analyse_frf(e, o);
  ASSERT_EQ(report.method, "periodic");
  const PeriodicExcitation& p = *report.periodic;
  EXPECT_EQ(p.estimator, "exact lines");
  EXPECT_EQ(p.first_sample, 300);
  EXPECT_EQ(p.period_samples, 500);
  EXPECT_EQ(p.whole_periods, 8);
  EXPECT_EQ(p.periods_used, 7);
  ASSERT_EQ(report.frequency_hz.size(), 50);
  double worst = 0.0;
  for (Eigen::Index l = 0; l < report.frequency_hz.size(); ++l) {
    const double f = report.frequency_hz(l);
    EXPECT_NEAR(f, 2.0 * static_cast<double>(2 * l + 1), 1e-9);
    const std::complex<double> z = std::exp(std::complex<double>(0.0, 2.0 * kPi * f * e.sample_time));
    const std::complex<double> truth = test::sales_rotor_zoh(z, e.sample_time);
    worst = std::max(worst, std::abs(report.plant.value[static_cast<std::size_t>(l)](0, 0) / truth - 1.0));
  }
  RecordProperty("rotor_exact_lines_worst_relative_error", test::scientific(worst));
  EXPECT_LT(worst, 1e-8);  // steady state after the discarded period: exact to round-off
}

// A sample where a controller clamp acted is not exogenous: the periodic analysis leaves out
// the period that holds it and the next one (the loop's response to the clamp). The rotor
// record with a clamp [-hi, hi] on u that no recorded sample reaches, except one in the fifth
// recorded period (the fourth used) whose recorded u we put beyond it: the two periods are
// left out and the other five give the exact plant; without the limit the wrong u spoils the
// estimate.
TEST(FrfForeignPeriodic, PeriodsHoldingAClampedSampleAreLeftOut) {
  Experiment e = rotor_record();
  const double hi = 1.5 * e.u.cwiseAbs().maxCoeff();
  const Eigen::Index clamped = 300 + 4 * 500 + 123;  // in the fifth whole period
  e.u(clamped, 0) = 2.0 * hi;
  FrfAnalysisOptions o;
  o.fit = false;
  auto worst_error = [&](const FrfReport& report) {
    double worst = 0.0;
    for (Eigen::Index l = 0; l < report.frequency_hz.size(); ++l) {
      const std::complex<double> z =
          std::exp(std::complex<double>(0.0, 2.0 * kPi * report.frequency_hz(l) * e.sample_time));
      worst = std::max(worst, std::abs(report.plant.value[static_cast<std::size_t>(l)](0, 0) /
                                           test::sales_rotor_zoh(z, e.sample_time) -
                                       1.0));
    }
    return worst;
  };
  const FrfReport unmarked = analyse_frf(e, o);
  EXPECT_EQ(unmarked.clamped_samples, 0);
  EXPECT_EQ(unmarked.periodic->periods_used, 7);
  e.controller->output_limits = {Limit{-hi, hi}};
  const FrfReport report = analyse_frf(e, o);
  ASSERT_EQ(report.method, "periodic");
  EXPECT_EQ(report.clamped_samples, 1);
  EXPECT_EQ(report.blocks_left_out, 2);
  EXPECT_EQ(report.periodic->periods_used, 5);
  EXPECT_TRUE(std::any_of(report.notes.begin(), report.notes.end(), [](const std::string& n) {
    return n.find("1 samples with a controller clamp acting (not exogenous): 2 blocks of periods") != std::string::npos;
  }));
  const double left_out = worst_error(report), kept = worst_error(unmarked);
  RecordProperty("clamped_period_left_out_worst_relative_error", test::scientific(left_out));
  RecordProperty("clamped_period_kept_worst_relative_error", test::scientific(kept));
  EXPECT_LT(left_out, 1e-8);
  EXPECT_GT(kept, 1e-3);
}

TEST(FrfForeignPeriodic, ADescriptionThatRContradictsIsIgnoredWithAWarning) {
  Experiment e = rotor_record();
  FrfAnalysisOptions o;
  o.fit = false;
  e.extra.json()["excitation"] = {{"kind", "multisine"}, {"period_samples", 250}, {"periods", 16}, {"lines", {1, 2}}};
  FrfReport report = analyse_frf(e, o);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("does not repeat with that shift (it repeats every 500 samples"), std::string::npos)
      << report.warnings[0];
  EXPECT_EQ(report.periodic->source, "r");
  EXPECT_EQ(report.periodic->period_samples, 500);
  EXPECT_EQ(report.frequency_hz.size(), 50);

  e.extra.json()["excitation"] = {{"kind", "random_binary"}};
  report = analyse_frf(e, o);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("non-periodic random_binary excitation but the recorded r repeats every 500"),
            std::string::npos)
      << report.warnings[0];
  EXPECT_EQ(report.method, "periodic");
}

}  // namespace frf_foreign_periodic_test
}  // namespace ambid::ident
