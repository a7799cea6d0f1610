// The segment jackknife (segment_jackknife.hpp): the sub-records it builds, the formula
// against the analytic standard error of a mean, and calibration of the sigmas it gives the
// ERA-based methods: over seeded Monte-Carlo runs of the nonlinear amb1dof_voltage loop with
// sensor noise, the observed scatter of every v must match the mean reported sigma.
#include "identifier/time_domain/segment_jackknife.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "identifier/identify_experiment.hpp"
#include "plant_sim/scenario.hpp"
#include "time_domain_fixtures.hpp"

namespace ambid::ident {
namespace segment_jackknife_test {

Experiment short_run(double duration) {
  sim::ScenarioOptions s;
  s.duration = duration;
  return sim::simulate_scenario(s);
}

TEST(SegmentJackknife, SubRecordDropsExactlyOneSegment) {
  const Experiment e = short_run(0.0103);  // 103 samples, segments of 25, the last 28
  ASSERT_EQ(e.samples(), 103);
  const LeaveOneSegmentOut cut = experiment_without_segment(e, 1, 4);
  EXPECT_EQ(cut.joint, 25);
  const Experiment& a = cut.experiment;
  ASSERT_EQ(a.samples(), 78);
  EXPECT_EQ(a.y.row(24), e.y.row(24));
  EXPECT_EQ(a.y.row(25), e.y.row(50));
  EXPECT_EQ(a.u.row(77), e.u.row(102));
  EXPECT_EQ(a.r.row(25), e.r.row(50));
  EXPECT_NEAR(a.t(77) - a.t(0), 77 * e.sample_time, 1e-12);
  a.validate();  // uniform sampling
  const LeaveOneSegmentOut cut_last = experiment_without_segment(e, 3, 4);
  EXPECT_EQ(cut_last.joint, 0);
  const Experiment& last = cut_last.experiment;
  ASSERT_EQ(last.samples(), 75);
  EXPECT_EQ(last.y.row(74), e.y.row(74));
  EXPECT_THROW(experiment_without_segment(e, 4, 4), Error);
  EXPECT_THROW(experiment_without_segment(e, 0, 1), Error);
  EXPECT_THROW(experiment_without_segment(e, 0, 60), InsufficientData);
}

// Two-sided 95 % quantiles of Student's t from the tables (independent truth), and the limits:
// 1 degree of freedom is the Cauchy law (tan(0.475 pi)), many the normal law (1.959964).
TEST(SegmentJackknife, StudentTQuantilesAreTheTables) {
  EXPECT_NEAR(student_t_two_sided_quantile(0.95, 1), std::tan(0.475 * std::numbers::pi), 1e-9);
  EXPECT_NEAR(student_t_two_sided_quantile(0.95, 2), 4.302653, 1e-6);
  EXPECT_NEAR(student_t_two_sided_quantile(0.95, 3), 3.182446, 1e-6);
  EXPECT_NEAR(student_t_two_sided_quantile(0.95, 7), 2.364624, 1e-6);
  EXPECT_NEAR(student_t_two_sided_quantile(0.95, 15), 2.131450, 1e-6);
  EXPECT_NEAR(student_t_two_sided_quantile(0.95, 2000), 1.959964, 2e-3);
  EXPECT_NEAR(student_t_two_sided_quantile(0.99, 4), 4.604095, 1e-6);
  EXPECT_THROW(student_t_two_sided_quantile(0.95, 0), Error);
  EXPECT_THROW(student_t_two_sided_quantile(1.0, 3), Error);
}

TEST(SegmentJackknife, MeanOfGroupsGivesTheStandardErrorWidenedForItsDegreesOfFreedom) {
  // theta = mean of K group means; leave-one-out estimates are the means of the other K - 1.
  // The jackknife's s is then exactly std(group means) / sqrt(K); the sigma is s widened by
  // t(5) / 2 for the 95.45 % two-sided quantile t(5) = 2.64865 (K - 1 = 5; by numerical
  // integration of the density).
  const std::vector<double> means = {1.0, 3.0, 2.5, -0.5, 4.0, 2.0};
  const double K = double(means.size());
  double total = 0.0, mean = 0.0, var = 0.0;
  for (double m : means) total += m;
  mean = total / K;
  for (double m : means) var += (m - mean) * (m - mean) / (K - 1.0);
  std::vector<std::map<std::string, double>> loo;
  for (double m : means) loo.push_back({{"theta", (total - m) / (K - 1.0)}, {"twice", 2.0 * (total - m) / (K - 1.0)}});
  const auto sigma = jackknife_sigma(loo);
  const double widen = 2.64865 / 2.0;
  EXPECT_NEAR(sigma.at("theta"), widen * std::sqrt(var / K), 1e-4 * std::sqrt(var / K));
  EXPECT_NEAR(sigma.at("twice"), 2.0 * sigma.at("theta"), 1e-12);
  EXPECT_THROW(jackknife_sigma({loo.front()}), Error);
  loo.back().erase("twice");
  EXPECT_THROW(jackknife_sigma(loo), Error);
}

TEST(SegmentJackknife, EveryParameterAndPhysicalQuantityHasASigma) {
  sim::ScenarioOptions s;
  s.duration = 0.4;
  s.amplitude = 1.0;
  s.position_noise = 1e-9;
  s.current_noise = 1e-6;
  const Experiment e = sim::simulate_scenario(s);
  for (const std::string method : {"okid", "closed-loop", "projection"}) {
    SCOPED_TRACE(method);
    IdentifyOptions o;
    o.method = method;
    const Model m = identify_experiment(e, o);
    ASSERT_EQ(m.parameters.size(), 9u);
    for (const auto* group : {&m.parameters, &m.physical})
      for (const auto& [name, value] : *group) {
        ASSERT_TRUE(m.uncertainty.count(name)) << name;
        EXPECT_GT(m.uncertainty.at(name), 0.0) << name;
        EXPECT_LT(m.uncertainty.at(name), std::abs(value)) << name;
      }
    o.jackknife_segments = 0;
    EXPECT_TRUE(identify_experiment(e, o).uncertainty.empty());
    o.jackknife_segments = 1;
    EXPECT_THROW(identify_experiment(e, o), Error);
  }
}

// Observed scatter of v1..v9 over `runs` seeded records against the mean reported sigma.
std::vector<double> scatter_over_sigma(const std::string& method, int runs, double duration) {
  std::vector<std::vector<double>> values(9), sigmas(9);
  for (int run = 0; run < runs; ++run) {
    sim::ScenarioOptions s;
    s.duration = duration;
    s.amplitude = 1.0;
    s.position_noise = 1e-9;  // the ERA methods' working range (1e-8 m already costs them 20 %)
    s.current_noise = 1e-6;
    s.seed = 100 + std::uint64_t(run);
    IdentifyOptions o;
    o.method = method;
    o.validation_fraction = 0.0;
    const Model m = identify_experiment(sim::simulate_scenario(s), o);
    for (int i = 0; i < 9; ++i) {
      const std::string name = "v" + std::to_string(i + 1);
      values[std::size_t(i)].push_back(m.parameters.at(name));
      sigmas[std::size_t(i)].push_back(m.uncertainty.at(name));
    }
  }
  std::vector<double> ratio;
  for (std::size_t i = 0; i < 9; ++i) {
    double mean = 0.0, var = 0.0, sigma = 0.0;
    for (double v : values[i]) mean += v / runs;
    for (double v : values[i]) var += (v - mean) * (v - mean) / (runs - 1);
    for (double v : sigmas[i]) sigma += v / runs;
    ratio.push_back(std::sqrt(var) / sigma);
  }
  return ratio;
}

TEST(SegmentJackknife, ClosedLoopSigmaIsCalibrated) {
  // 16 runs: the observed standard deviation is itself uncertain by ~18 % (one sigma) and the
  // mean jackknife sigma by ~7 %, so a calibrated sigma gives ratios within 0.6..1.6.
  const std::vector<double> ratio = scatter_over_sigma("closed-loop", 16, 0.5);
  for (std::size_t i = 0; i < 9; ++i) {
    ::testing::Test::RecordProperty("v" + std::to_string(i + 1) + "_scatter_over_sigma", testing::sci(ratio[i]));
    EXPECT_GT(ratio[i], 0.6) << "v" << i + 1;
    EXPECT_LT(ratio[i], 1.6) << "v" << i + 1;
  }
}

}  // namespace segment_jackknife_test
}  // namespace ambid::ident
