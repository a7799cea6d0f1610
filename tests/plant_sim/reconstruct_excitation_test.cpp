// `ambid import --reconstruct-r` on a simulated bearing whose amplifiers clamp: the excitation
// computed as u - controller output equals the simulator's at every sample where no clamp
// acted, and exactly the clamped samples are marked not exogenous.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "core/experiment_import.hpp"
#include "core/experiment_io.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::sim {
namespace reconstruct_excitation_test {

namespace fs = std::filesystem;

TEST(ReconstructExcitation, EqualsTheTrueExcitationWhereNoClampActedAndMarksTheClampedSamples) {
  ScenarioOptions o;
  o.controller = "lqr";
  o.excitation = "prbs";
  o.amplitude = 0.5;
  o.duration = 0.3;
  o.input_limit = 9.4;  // 0.65 V above the operating command 8.75 V
  o.position_noise = 1e-7;
  o.current_noise = 1e-4;
  o.seed = 3;
  ClosedLoopStatistics statistics;
  const Experiment truth = simulate_scenario(o, &statistics);
  const Eigen::Index n = truth.samples();
  ASSERT_GT(statistics.saturated_samples, n / 50);  // the clamp matters...
  ASSERT_LT(statistics.saturated_samples, n / 2);   // ...but most samples are exogenous

  const fs::path dir = fs::temp_directory_path() / ("ambid-reconstruct-" + std::to_string(std::random_device{}()));
  write_experiment(truth, dir / "truth");
  Experiment logged = truth;  // the rig's logger has no r
  logged.r_names.clear();
  logged.r.resize(0, 0);
  write_experiment(logged, dir / "logged");

  ImportMapping m;
  m.t = parse_signal_source("t", "t");
  for (const auto& name : truth.y_names) m.y.push_back(parse_signal_mapping(name + "=" + name));
  for (const auto& name : truth.u_names) m.u.push_back(parse_signal_mapping(name + "=" + name));
  ImportOptions options;
  options.template_sidecar = read_sidecar(dir / "truth.json");
  options.reconstruct_r = true;
  const ImportResult result = import_experiment(dir / "logged.csv", m, options);
  const Experiment& e = result.experiment;
  ASSERT_EQ(e.r_names, truth.r_names);
  ASSERT_EQ(e.samples(), n);

  // Independent truth of the clamp: the simulator's command beyond +-input_limit.
  Eigen::Index clamped = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const bool beyond = (truth.u.row(k).array().abs() > o.input_limit).any();
    EXPECT_EQ(result.clamped[std::size_t(k)], beyond) << "sample " << k;
    if (beyond) {
      ++clamped;
      continue;
    }
    for (Eigen::Index j = 0; j < 2; ++j) EXPECT_NEAR(e.r(k, j), truth.r(k, j), 1e-9) << "sample " << k;
  }
  EXPECT_EQ(clamped, statistics.saturated_samples);
  EXPECT_EQ(result.clamped_samples, statistics.saturated_samples);

  // The written experiment carries the mark the contract's way: its readers find the same mask.
  write_experiment(e, dir / "imported");
  const ReadResult reread = read_experiment(dir / "imported");
  EXPECT_EQ(reread.clamped, result.clamped);
  EXPECT_EQ(reread.clamped_samples, statistics.saturated_samples);
  fs::remove_all(dir);
}

}  // namespace reconstruct_excitation_test
}  // namespace ambid::sim
