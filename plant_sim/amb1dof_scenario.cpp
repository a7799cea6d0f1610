#include "plant_sim/amb1dof_scenario.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "plant_sim/amb1dof_extended.hpp"
#include "plant_sim/amb1dof_voltage.hpp"
#include "plant_sim/excitation.hpp"
#include "plant_sim/observer_controller.hpp"
#include "plant_sim/pid.hpp"

namespace ambid::sim {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw Error("simulation: " + message);
}

// Decentralised alternative to the observer design: a proportional current loop per coil
// (kc = 1000 V/A puts the coil pole at -(R + kw kc)/L = -2372 rad/s) and a PID on the position
// driving the coils differentially. With the current loops closed, a volt of position command
// gives 2 kr / kc newtons, so kp = 2 ks kc / kr (twice the negative stiffness) leaves a net
// stiffness of 2 ks (about 880 rad/s), kd gives a damping ratio near 0.5 and ki acts below
// 20 rad/s. On the nominal bearing the slowest mode has damping 0.2; coil and amplifier
// faults of 20 % keep it stable (tests/plant_sim/scenario_test.cpp).
StateSpaceController amb1dof_pid(double sample_time) {
  PidLoop position{"x", {{"u1", 1.0}, {"u2", -1.0}}, 2.86e6, 5.7e7, 1625.0, 1e-4};
  PidLoop coil1{"i1", {{"u1", 1.0}}, 1000.0, 0.0, 0.0, 0.0};
  PidLoop coil2{"i2", {{"u2", 1.0}}, 1000.0, 0.0, 0.0, 0.0};
  return pid_controller({position, coil1, coil2}, sample_time, {"u1", "u2"});
}

// The other classical design (tests and stacks that must not all see one controller): the
// same proportional current loops, and on the position a lead-lag with integral action,
// C(s) = 2.5e6 (1.2 ms s + 1) / ((0.15 ms s + 1) (0.03 ms s + 1)) + 5e7 / s: net stiffness
// about 1e6 N/m, phase lead centred near 2300 rad/s (zero at 833, pole at 6667 rad/s), a
// roll-off at 33 krad/s, the integral (below 20 rad/s) bringing x to 0 with both coils at
// the same current. Tustin, not the PID's Euler forms. A continuous approximation of the loop
// (coil pole, no back-EMF) puts its slowest oscillating mode near 1230 rad/s with damping
// 0.35; coil and amplifier faults of 20 % keep it stable (tests/plant_sim/scenario_test.cpp).
StateSpaceController amb1dof_lead_lag(double sample_time) {
  LeadLagLoop position{"x", {{"u1", 1.0}, {"u2", -1.0}}, 2.5e6, {{1.2e-3, 1.5e-4}, {0.0, 3e-5}}, 5e7};
  LeadLagLoop coil1{"i1", {{"u1", 1.0}}, 1000.0, {}, 0.0};
  LeadLagLoop coil2{"i2", {{"u2", 1.0}}, 1000.0, {}, 0.0};
  return lead_lag_controller({position, coil1, coil2}, sample_time, {"u1", "u2"});
}

Excitation make_excitation(const ScenarioOptions& o, Eigen::Index samples, int channels) {
  if (o.excitation == "prbs") {
    PrbsOptions p;
    p.register_length = std::clamp(int(std::ceil(std::log2(double(samples) + 1.0))), 6, 24);
    p.amplitude = o.amplitude;
    p.seed = o.seed;
    p.channels = channels;
    return prbs(p, samples, o.sample_time);
  }
  if (o.excitation == "multisine") {
    MultisineOptions m;
    m.f_min = o.f_min;
    m.f_max = o.f_max;
    // One-second periods give 1 Hz lines; shorter records use one period per Hadamard block.
    m.period_samples = std::min<Eigen::Index>(Eigen::Index(std::llround(1.0 / o.sample_time)), samples / 2);
    const int block = channels > 1 ? 2 : 1;
    m.periods = int(samples / m.period_samples) / block * block;
    require(m.periods >= block, "the record is too short for a multisine with whole periods");
    m.level = o.amplitude;
    m.seed = o.seed;
    m.channels = channels;
    m.pattern = channels > 1 ? ChannelPattern::hadamard : ChannelPattern::identical;
    Excitation e = multisine(m, o.sample_time);
    // Pad to the record length with zeros (after the last whole period).
    Eigen::MatrixXd padded = Eigen::MatrixXd::Zero(samples, channels);
    padded.topRows(e.samples.rows()) = e.samples;
    e.samples = padded;
    return e;
  }
  if (o.excitation == "chirp") {
    ChirpOptions c;
    c.f_start = o.f_min;
    c.f_end = o.f_max;
    c.amplitude = o.amplitude;
    c.sweep = Sweep::logarithmic;
    c.channels = channels;
    return chirp(c, samples, o.sample_time);
  }
  if (o.excitation == "stepped_sine") {
    SteppedSineOptions s;
    for (double f = o.f_min; f <= o.f_max * (1 + 1e-9); f *= std::pow(10.0, 0.1)) s.frequencies.push_back(f);
    s.amplitude = o.amplitude;
    s.settle_time = 0.05;
    s.channels = channels;
    Excitation e = stepped_sine(s, o.sample_time);
    require(e.samples.rows() <= samples, "the stepped sine needs " + std::to_string(e.samples.rows()) +
                                             " samples; raise the duration to at least " +
                                             std::to_string(double(e.samples.rows()) * o.sample_time) + " s");
    Eigen::MatrixXd padded = Eigen::MatrixXd::Zero(samples, channels);
    padded.topRows(e.samples.rows()) = e.samples;
    e.samples = padded;
    return e;
  }
  throw Error("simulation: unknown excitation '" + o.excitation +
              "' (known: prbs, multisine, chirp, stepped_sine, none)");
}

}  // namespace

Scenario build_amb1dof_scenario(const ScenarioOptions& o) {
  require(std::isfinite(o.sample_time) && o.sample_time > 0,
          "sample time must be positive, got " + std::to_string(o.sample_time));
  require(std::isfinite(o.duration) && o.duration >= 2 * o.sample_time,
          "duration must be at least two samples, got " + std::to_string(o.duration));
  require(std::isfinite(o.amplitude) && o.amplitude >= 0, "amplitude must be >= 0, got " + std::to_string(o.amplitude));
  for (const auto& [what, value] : {std::pair{"position noise", o.position_noise},
                                    {"current noise", o.current_noise},
                                    {"force noise", o.force_noise},
                                    {"input limit", o.input_limit}})
    require(std::isfinite(value) && value >= 0, std::string(what) + " must be >= 0, got " + std::to_string(value));
  require(o.noise_level == 0.0, "a relative noise level is lamstf's; give position, current and force noise");

  const Amb1dofParameters nominal = Amb1dofParameters::nominal();
  Amb1dofParameters true_parameters = nominal;
  for (const auto& [name, value] : o.true_parameters) true_parameters.set(name, value);
  true_parameters.validate();
  const Amb1dofVoltage nominal_plant(nominal);

  Scenario s;
  if (o.effects.empty())
    s.truth = std::make_unique<Amb1dofVoltage>(true_parameters);
  else
    s.truth = std::make_unique<Amb1dofExtended>(true_parameters, o.effects, o.sample_time);
  Experiment& h = s.header;
  h.name = o.name;
  h.sample_time = o.sample_time;
  h.plant = {nominal_plant.model(), nominal.to_map()};
  h.y_names = nominal_plant.output_names();
  h.u_names = nominal_plant.input_names();
  const Eigen::VectorXd x_op = nominal_plant.equilibrium_state(), u_op = nominal_plant.equilibrium_input();
  h.operating_point = {{"x", x_op(0)}, {"i1", x_op(2)}, {"i2", x_op(3)}, {"u1", u_op(0)}, {"u2", u_op(1)}};

  if (o.controller == "lqr") {
    h.controller = design_observer_controller(nominal_plant.linearize(), o.sample_time, h.u_names, h.y_names,
                                              amb1dof_observer_controller_options());
  } else if (o.controller == "pid") {
    h.controller = amb1dof_pid(o.sample_time);
  } else if (o.controller == "leadlag") {
    h.controller = amb1dof_lead_lag(o.sample_time);
  } else {
    throw Error("simulation: unknown controller '" + o.controller + "' (known: lqr, pid, leadlag)");
  }

  const Eigen::Index samples = Eigen::Index(std::llround(o.duration / o.sample_time));
  s.options.samples = samples;
  s.options.seed = o.seed;
  nlohmann::json simulation = {
      {"true_parameters", true_parameters.to_map()},
      {"seed", o.seed},
      {"controller_design", o.controller},
      {"noise", {{"x", o.position_noise}, {"i1", o.current_noise}, {"i2", o.current_noise}, {"Fz", o.force_noise}}}};
  for (const auto& e : o.effects)
    simulation["effects"].push_back({{"effect", e.name},
                                     {"channel", e.channel ? nlohmann::json(e.channel) : nlohmann::json()},
                                     {"parameters", e.parameters}});
  if (o.excitation != "none" && o.amplitude > 0) {
    h.r_names = {"r1", "r2"};
    h.operating_point["r1"] = 0.0;
    h.operating_point["r2"] = 0.0;
    Excitation e = make_excitation(o, samples, 2);
    s.options.excitation = std::move(e.samples);
    h.extra.json()["excitation"] = std::move(e.description.json());
  }
  if (o.position_noise > 0 || o.current_noise > 0)
    s.options.measurement_noise_std = Eigen::Vector3d(o.position_noise, o.current_noise, o.current_noise);
  if (o.force_noise > 0) s.options.process_noise_std = Eigen::VectorXd::Constant(1, o.force_noise);
  if (o.input_limit > 0) {
    s.options.input_lower = Eigen::VectorXd::Constant(2, -o.input_limit);
    s.options.input_upper = Eigen::VectorXd::Constant(2, o.input_limit);
    simulation["input_limit"] = o.input_limit;
    // The contract's form of the same clamp, so readers mark the clamped samples.
    h.controller->output_limits.assign(h.controller->outputs.size(), Limit{-o.input_limit, o.input_limit});
  }
  // What the simulator knew and the sidecar's nominal view does not: kept under its own key so
  // tests and users can compare an identification with the truth.
  h.extra.json()["simulation"] = std::move(simulation);
  return s;
}

Experiment simulate_amb1dof(const ScenarioOptions& options, ClosedLoopStatistics* statistics) {
  const Scenario s = build_amb1dof_scenario(options);
  return run_closed_loop(*s.truth, s.header, s.options, statistics);
}

}  // namespace ambid::sim
