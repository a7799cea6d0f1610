#include "plant_sim/maglev_loop.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "plant_sim/integrator.hpp"
#include "plant_sim/maglev1coil_voltage.hpp"
#include "plant_sim/maglev_controller.hpp"

namespace ambid::sim {
namespace {

[[noreturn]] void fail_loop(const std::string& what, double value) {
  std::ostringstream msg;
  msg << "maglev simulation: " << what << ", got " << value;
  throw Error(msg.str());
}

void check(const MaglevParameters& truth, const MaglevRig& rig, const MaglevRunOptions& o) {
  truth.validate();
  rig.validate();
  if (!(o.sample_time > 0.0) || !std::isfinite(o.sample_time)) fail_loop("sample time must be positive", o.sample_time);
  if (o.samples < 2) fail_loop("the record needs at least 2 samples", double(o.samples));
  if (o.levels.empty()) throw Error("maglev simulation: no reference levels given");
  for (const double level : o.levels)
    if (!(level > truth.x_min && level < truth.x_max))
      fail_loop("reference levels must lie strictly between the stops " + std::to_string(truth.x_min) + " and " +
                    std::to_string(truth.x_max) + " m",
                level);
  if (!(o.step_period >= o.sample_time) || !std::isfinite(o.step_period))
    fail_loop("the step period must be at least one sample", o.step_period);
  for (const double v :
       {o.noise_amplitude, o.position_noise, o.current_noise, o.force_noise, o.harmonic_force, o.harmonic_frequency})
    if (!(v >= 0.0) || !std::isfinite(v)) fail_loop("noise levels must be >= 0", v);
  if (o.substeps < 1) fail_loop("substeps must be at least 1", o.substeps);
}

// The message of a touch at time t with gap x.
std::string touch_message(const MaglevParameters& p, double t, double x) {
  std::ostringstream msg;
  msg << "maglev1coil_voltage: the body touched the " << (x <= p.x_min ? "top stop" : "ground") << " at t = " << t
      << " s (x = " << x * 1e3 << " mm, stop at " << (x <= p.x_min ? p.x_min : p.x_max) * 1e3
      << " mm); the record ends at the sample before";
  return msg.str();
}

}  // namespace

MaglevRun run_maglev_rig(const MaglevParameters& truth, const MaglevParameters& nominal, const MaglevRig& rig,
                         const MaglevRunOptions& o) {
  check(truth, rig, o);
  nominal.validate();
  const Maglev1coilVoltage plant(truth, o.levels.front());
  Rk4Integrator integrator(plant);
  const double Ts = o.sample_time, h = Ts / o.substeps;
  const auto level_samples = std::max<Eigen::Index>(1, Eigen::Index(std::llround(o.step_period / Ts)));
  const auto delay = std::size_t(rig.sensor_delay);

  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);

  Eigen::VectorXd x = plant.equilibrium_state(), u(1), w = Eigen::VectorXd::Zero(1);
  double integral = std::clamp(plant.equilibrium_input()(0), rig.integral_min, rig.integral_max);
  std::deque<double> readings(delay + 1, rig.sense(x(0), x(2)));  // sensor pipeline, oldest first
  double previous_error = 0.0;

  MaglevRun run;
  Experiment& e = run.experiment;
  e.t.resize(o.samples);
  e.y.resize(o.samples, 2);
  e.u.resize(o.samples, 1);
  Eigen::Index k = 0;
  for (; k < o.samples; ++k) {
    readings.push_back(rig.sense(x(0), x(2)));
    readings.pop_front();
    const double y = readings.front() + o.position_noise * normal(rng);
    const double reference = o.levels[std::size_t(k / level_samples) % o.levels.size()];
    const double error = (y - reference) * 1e3;  // mm
    if (k == 0) previous_error = error;
    const double integral_free = integral + rig.Kp * Ts / rig.Ti * error;
    integral = std::clamp(integral_free, rig.integral_min, rig.integral_max);
    const double pid_free = rig.Kp * error + integral + rig.Kp * rig.Td / Ts * (error - previous_error);
    const double pid = std::clamp(pid_free, rig.pid_min, rig.pid_max);
    previous_error = error;
    const double command_free = pid + o.noise_amplitude * uniform(rng);
    const double command = std::clamp(command_free, 0.0, rig.v_ref);
    if (integral != integral_free || pid != pid_free || command != command_free) ++run.clamped_samples;

    e.t(k) = double(k) * Ts;
    e.y(k, 0) = round_to(y, rig.log_x);
    e.y(k, 1) = round_to(x(2) + o.current_noise * normal(rng), rig.log_i);
    e.u(k, 0) = round_to(command, rig.log_u);

    u(0) = rig.dac(command);
    const double force = o.force_noise * normal(rng);
    for (int s = 0; s < o.substeps; ++s) {
      w(0) =
          force + o.harmonic_force * std::sin(2.0 * std::numbers::pi * o.harmonic_frequency * (e.t(k) + (s + 0.5) * h));
      integrator.integrate_sample(x, u, w, h, 1);
      if (!x.allFinite()) fail_loop("the plant state became non-finite at t", e.t(k) + (s + 1) * h);
      if (x(0) <= truth.x_min || x(0) >= truth.x_max) {
        run.ended = touch_message(truth, e.t(k) + (s + 1) * h, x(0));
        break;
      }
    }
    if (!run.ended.empty()) {
      ++k;
      break;
    }
  }
  e.t.conservativeResize(k);
  e.y.conservativeResize(k, 2);
  e.u.conservativeResize(k, 1);

  e.name = o.name;
  e.sample_time = Ts;
  e.plant = {plant.model(), nominal.to_map()};
  e.y_names = plant.output_names();
  e.u_names = plant.input_names();
  // Measured operating point: the second half of the first level (as much of it as was run).
  const Eigen::Index first = std::min(level_samples, k), begin = first / 2,
                     n = std::max<Eigen::Index>(1, first - begin);
  e.operating_point = {{"x", e.y.col(0).segment(begin, n).mean()},
                       {"i", e.y.col(1).segment(begin, n).mean()},
                       {"u", e.u.col(0).segment(begin, n).mean()}};
  nlohmann::json& extra = e.extra.json();
  extra["operating_point_source"] = "measured";
  extra["rig"] = {{"controller", "pid"},
                  {"settings", rig.to_map()},
                  {"reference", {{"levels", o.levels}, {"step_period", double(level_samples) * Ts}}},
                  {"excitation", {{"kind", "uniform"}, {"amplitude", o.noise_amplitude}, {"logged", false}}}};
  extra["simulation"] = {{"true_parameters", truth.to_map()},
                         {"seed", o.seed},
                         {"substeps", o.substeps},
                         {"noise", {{"x", o.position_noise}, {"i", o.current_noise}, {"Fz", o.force_noise}}},
                         {"harmonic_force", {{"amplitude", o.harmonic_force}, {"frequency", o.harmonic_frequency}}},
                         {"clamped_samples", run.clamped_samples}};
  if (!run.ended.empty()) extra["simulation"]["ended"] = run.ended;
  attach_rig_controller(e, rig);
  return run;
}

}  // namespace ambid::sim
