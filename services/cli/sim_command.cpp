// `ambid sim`: simulate a plant in closed loop and write an experiment (csv + json).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/experiment_io.hpp"
#include "plant_sim/families.hpp"
#include "plant_sim/scenario.hpp"
#include "services/cli/commands.hpp"
#include "services/cli/parameter_overrides.hpp"

namespace ambid::cli {
namespace {

struct SimArguments {
  sim::ScenarioOptions scenario;
  std::vector<std::string> overrides;
  std::vector<std::string> rig;
  std::vector<double> levels_mm;
  std::vector<std::string> effects;
  std::string out;
};

void print_summary(const Experiment& e, const std::string& stem, const sim::ClosedLoopStatistics& stats) {
  const Eigen::MatrixXd dy = e.y_deviation();
  const Eigen::MatrixXd du = e.u_deviation();
  auto rms = [](const Eigen::VectorXd& v) { return std::sqrt(v.squaredNorm() / double(v.size())); };
  std::cout << "ambid sim: " << e.plant.model << ", " << e.samples() << " samples at " << 1.0 / e.sample_time << " Hz ("
            << double(e.samples()) * e.sample_time << " s)\n";
  for (Eigen::Index j = 0; j < dy.cols(); ++j)
    std::cout << "  " << e.y_names[std::size_t(j)] << ": rms deviation " << rms(dy.col(j)) << ", peak "
              << dy.col(j).cwiseAbs().maxCoeff() << "\n";
  for (Eigen::Index j = 0; j < du.cols(); ++j)
    std::cout << "  " << e.u_names[std::size_t(j)] << ": rms deviation " << rms(du.col(j)) << " V\n";
  const nlohmann::json& extra = e.extra.json();
  if (extra.is_object() && extra.value("operating_point_source", std::string()) == "measured") {
    std::cout << "  operating point (measured, the first level's means):";
    for (const auto& [name, value] : e.operating_point) std::cout << " " << name << " = " << value;
    std::cout << "\n";
  }
  if (stats.saturated_samples > 0)
    std::cout << "  a limit or clamp acted in " << stats.saturated_samples << " samples\n";
  std::cout << "  wrote " << stem << ".csv and " << stem << ".json\n";
}

bool has_parameter(const sim::EffectSpec& spec, const std::string& name) {
  if (spec.has_channel && name == "channel") return true;
  for (const auto& p : spec.parameters)
    if (p.name == name) return true;
  return false;
}

// Splits the --set values between the true plant parameters and the effects: `EFFECT.PARAM`,
// or `PARAM` when exactly one chosen effect has it; anything else must be a plant parameter.
void route_overrides(const std::map<std::string, double>& values, const std::vector<std::string>& effect_names,
                     sim::ScenarioOptions& o) {
  std::map<std::string, std::map<std::string, double>> per_effect;
  for (const auto& name : effect_names) {
    sim::effect_spec(name);  // Error listing the known effects
    if (!per_effect.emplace(name, std::map<std::string, double>{}).second)
      throw Error("--effect " + name + " given twice");
  }
  const auto& plant_names = sim::plant_family(o.plant, "--plant").parameter_names();
  for (const auto& [key, value] : values) {
    const auto dot = key.find('.');
    if (dot != std::string::npos) {
      const std::string effect = key.substr(0, dot);
      if (!per_effect.count(effect))
        throw Error("--set " + key + ": effect '" + effect + "' is not chosen with --effect");
      per_effect[effect][key.substr(dot + 1)] = value;
      continue;
    }
    std::vector<std::string> owners;
    for (const auto& name : effect_names)
      if (has_parameter(sim::effect_spec(name), key)) owners.push_back(name);
    if (owners.size() > 1) throw Error("--set " + key + ": several chosen effects have it; write EFFECT." + key);
    if (owners.size() == 1) {
      per_effect[owners.front()][key] = value;
    } else if (std::find(plant_names.begin(), plant_names.end(), key) != plant_names.end() || effect_names.empty()) {
      o.true_parameters[key] = value;  // an unknown name without effects: the plant lists its names
    } else {
      std::string valid;
      for (const auto& name : plant_names) valid += name + " ";
      for (const auto& name : effect_names) {
        for (const auto& p : sim::effect_spec(name).parameters) valid += p.name + " ";
        if (sim::effect_spec(name).has_channel) valid += "channel ";
      }
      throw Error("--set " + key + ": neither a plant parameter nor a parameter of the chosen effects (valid: " +
                  valid.substr(0, valid.size() - 1) + ")");
    }
  }
  for (const auto& name : effect_names) o.effects.push_back(sim::make_effect(name, per_effect[name]));
}

// Options the user did not give take the plant family's defaults (a maglev rig samples at
// 3.25 ms with uniform noise on u, a bearing at 0.1 ms with a PRBS).
void apply_family_defaults(const CLI::App& sim, sim::ScenarioOptions& o) {
  const sim::ScenarioOptions d = sim::plant_family(o.plant, "--plant").default_options();
  if (!sim.count("--name")) o.name = d.name;
  if (!sim.count("--duration")) o.duration = d.duration;
  if (!sim.count("--sample-time")) o.sample_time = d.sample_time;
  if (!sim.count("--controller")) o.controller = d.controller;
  if (!sim.count("--excitation")) o.excitation = d.excitation;
  if (!sim.count("--amplitude")) o.amplitude = d.amplitude;
  if (!sim.count("--noise-level")) o.noise_level = d.noise_level;
}

}  // namespace

void add_sim_command(CLI::App& app) {
  auto args = std::make_shared<SimArguments>();
  auto& o = args->scenario;
  CLI::App* sim = app.add_subcommand("sim", "simulate a plant in closed loop and write an experiment");
  sim->add_option("--plant", o.plant, "plant model: " + sim::plant_family_names())->capture_default_str();
  sim->add_option("--duration", o.duration, "record length (s)")->capture_default_str();
  sim->add_option("--sample-time", o.sample_time, "sample time (s)")->capture_default_str();
  sim->add_option("--seed", o.seed, "seed of excitation and noise")->capture_default_str();
  sim->add_option("--controller", o.controller,
                  "controller design: lqr (observer, integral action) | pid | leadlag (both decentralised with "
                  "current loops); lamstf: lqr")
      ->capture_default_str();
  sim->add_option(
         "--excitation", o.excitation,
         "prbs | multisine | chirp | stepped_sine | none; maglev1coil_voltage: uniform | none; lamstf: gaussian | "
         "binary | none")
      ->capture_default_str();
  sim->add_option("--amplitude", o.amplitude, "excitation level per plant input (V; rms for multisine)")
      ->capture_default_str();
  sim->add_option("--f-min", o.f_min, "lowest excited frequency (Hz)")->capture_default_str();
  sim->add_option("--f-max", o.f_max, "highest excited frequency (Hz)")->capture_default_str();
  sim->add_option("--position-noise", o.position_noise, "sensor noise std of x (m)")->capture_default_str();
  sim->add_option("--current-noise", o.current_noise, "sensor noise std of i1, i2 (A)")->capture_default_str();
  sim->add_option("--force-noise", o.force_noise, "process noise std of the rotor force (N)")->capture_default_str();
  sim->add_option("--noise-level", o.noise_level,
                  "lamstf: noise std per channel as a fraction of the noise-free loop's rms (seed 002's % noise; "
                  "default 0.005)");
  sim->add_option("--input-limit", o.input_limit, "amplifier command limit |u| (V; lamstf: A), 0 for none")
      ->capture_default_str();
  sim->add_option("--set", args->overrides,
                  "NAME=VALUE: a true plant parameter or an effect parameter (repeatable; EFFECT.NAME=VALUE when "
                  "two effects share a name); the sidecar keeps the nominal value");
  sim->add_option("--effect", args->effects,
                  "an effect of the truth (repeatable; see plant_sim/EFFECTS.md): coil_resistance, amplifier_gain, "
                  "amplifier_bandwidth, eddy_current, sensor_delay, sensor_gain, flexible_mode, magnetic_saturation, "
                  "air_gap, rotor_mass, harmonic_disturbance");
  sim->add_option("--rig", args->rig,
                  "NAME=VALUE: a setting of the maglev rig's board (repeatable; maglev1coil_voltage only): PID Kp Ti "
                  "Td and clamps, sensor_gain, sensor_offset, sensor_exponent, sensor_coupling, sensor_delay, "
                  "dac_step, v_ref, log_x, log_u, log_i (plant_sim/maglev_rig.hpp)");
  sim->add_option("--levels", args->levels_mm,
                  "reference levels in mm, comma separated, cycled (maglev1coil_voltage only; default "
                  "14,13,15,14.5,16,13.5)")
      ->delimiter(',');
  sim->add_option("--step-period", o.step_period, "seconds each reference level is held (maglev1coil_voltage)")
      ->capture_default_str();
  sim->add_option("--out", args->out, "output stem: writes STEM.csv and STEM.json")->required();
  sim->add_option("--name", o.name, "experiment name")->capture_default_str();
  sim->callback([args, sim] {
    apply_family_defaults(*sim, args->scenario);
    if (!args->rig.empty() || !args->levels_mm.empty()) {
      if (sim::plant_family(args->scenario.plant, "--plant").build_scenario)
        throw Error("--rig and --levels are settings of a rig's own loop; plant model '" + args->scenario.plant +
                    "' runs the generic closed loop");
      args->scenario.rig = parse_parameter_overrides(args->rig);
      for (const double level : args->levels_mm) args->scenario.levels.push_back(level * 1e-3);
    }
    route_overrides(parse_parameter_overrides(args->overrides), args->effects, args->scenario);
    sim::ClosedLoopStatistics stats;
    const Experiment e = sim::simulate_scenario(args->scenario, &stats);
    write_experiment(e, args->out);
    print_summary(e, args->out, stats);
  });
}

}  // namespace ambid::cli
