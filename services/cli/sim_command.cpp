// `ambid sim`: simulate a plant in closed loop and write an experiment (csv + json).
#include <cmath>
#include <iostream>
#include <memory>

#include "core/error.hpp"
#include "core/experiment_io.hpp"
#include "plant_sim/scenario.hpp"
#include "services/cli/commands.hpp"
#include "services/cli/parameter_overrides.hpp"

namespace ambid::cli {
namespace {

struct SimArguments {
  sim::ScenarioOptions scenario;
  std::vector<std::string> overrides;
  std::string out;
};

void print_summary(const Experiment& e, const std::string& stem, const sim::ClosedLoopStatistics& stats) {
  const Eigen::MatrixXd dy = e.y_deviation();
  const Eigen::MatrixXd du = e.u_deviation();
  auto rms = [](const Eigen::VectorXd& v) { return std::sqrt(v.squaredNorm() / double(v.size())); };
  std::cout << "ambid sim: " << e.plant.model << ", " << e.samples() << " samples at "
            << 1.0 / e.sample_time << " Hz (" << double(e.samples()) * e.sample_time << " s)\n";
  for (Eigen::Index j = 0; j < dy.cols(); ++j)
    std::cout << "  " << e.y_names[std::size_t(j)] << ": rms deviation " << rms(dy.col(j)) << ", peak "
              << dy.col(j).cwiseAbs().maxCoeff() << "\n";
  for (Eigen::Index j = 0; j < du.cols(); ++j)
    std::cout << "  " << e.u_names[std::size_t(j)] << ": rms deviation " << rms(du.col(j)) << " V\n";
  if (stats.saturated_samples > 0)
    std::cout << "  amplifier limit reached in " << stats.saturated_samples << " samples\n";
  std::cout << "  wrote " << stem << ".csv and " << stem << ".json\n";
}

}  // namespace

void add_sim_command(CLI::App& app) {
  auto args = std::make_shared<SimArguments>();
  auto& o = args->scenario;
  CLI::App* sim = app.add_subcommand("sim", "simulate a plant in closed loop and write an experiment");
  sim->add_option("--plant", o.plant, "plant model")->capture_default_str();
  sim->add_option("--duration", o.duration, "record length (s)")->capture_default_str();
  sim->add_option("--sample-time", o.sample_time, "sample time (s)")->capture_default_str();
  sim->add_option("--seed", o.seed, "seed of excitation and noise")->capture_default_str();
  sim->add_option("--controller", o.controller, "controller design: lqr (observer, integral action) | pid")
      ->capture_default_str();
  sim->add_option("--excitation", o.excitation, "prbs | multisine | chirp | stepped_sine | none")
      ->capture_default_str();
  sim->add_option("--amplitude", o.amplitude, "excitation level per plant input (V; rms for multisine)")
      ->capture_default_str();
  sim->add_option("--f-min", o.f_min, "lowest excited frequency (Hz)")->capture_default_str();
  sim->add_option("--f-max", o.f_max, "highest excited frequency (Hz)")->capture_default_str();
  sim->add_option("--position-noise", o.position_noise, "sensor noise std of x (m)")->capture_default_str();
  sim->add_option("--current-noise", o.current_noise, "sensor noise std of i1, i2 (A)")->capture_default_str();
  sim->add_option("--force-noise", o.force_noise, "process noise std of the rotor force (N)")->capture_default_str();
  sim->add_option("--input-limit", o.input_limit, "amplifier command limit |u| (V), 0 for none")
      ->capture_default_str();
  sim->add_option("--set", args->overrides,
                  "NAME=VALUE: a true plant parameter (repeatable); the sidecar keeps the nominal value");
  sim->add_option("--out", args->out, "output stem: writes STEM.csv and STEM.json")->required();
  sim->add_option("--name", o.name, "experiment name")->capture_default_str();
  sim->callback([args] {
    args->scenario.true_parameters = parse_parameter_overrides(args->overrides);
    sim::ClosedLoopStatistics stats;
    const Experiment e = sim::simulate_scenario(args->scenario, &stats);
    write_experiment(e, args->out);
    print_summary(e, args->out, stats);
  });
}

}  // namespace ambid::cli
