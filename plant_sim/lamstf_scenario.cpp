#include "plant_sim/lamstf_scenario.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "plant_sim/excitation.hpp"
#include "plant_sim/lamstf.hpp"
#include "plant_sim/linear_plant.hpp"
#include "plant_sim/lqr.hpp"

namespace ambid::sim {
namespace {

constexpr double kPoleRadius = 0.85;  // closed-loop poles of the LQR inside |z| < 0.85

void require(bool ok, const std::string& message) {
  if (!ok) throw Error("simulation: lamstf: " + message);
}

// Observer-based state feedback uf = -F xhat with the Kalman predictor for process
// covariance W (states) and measurement covariance V, reading [u; y].
StateSpaceController observer_lqr(const DiscreteSystem& plant, const NamedSystem& named, const Eigen::MatrixXd& W,
                                  const Eigen::MatrixXd& V) {
  const Eigen::Index n = plant.states(), m = plant.inputs(), p = plant.outputs();
  const Eigen::MatrixXd F = dlqr(plant.A / kPoleRadius, plant.B / kPoleRadius, Eigen::MatrixXd::Identity(n, n),
                                 Eigen::MatrixXd::Identity(m, m))
                                .K;
  // A tiny regularisation keeps (A, W^1/2) stabilisable for the singular W = B S B'.
  const Eigen::MatrixXd L = predictor_gain(plant.A, plant.C, W + 1e-12 * Eigen::MatrixXd::Identity(n, n),
                                           V + 1e-12 * Eigen::MatrixXd::Identity(p, p))
                                .L;
  StateSpaceController k;
  k.sample_time = plant.sample_time;
  k.inputs = named.input_names;
  k.inputs.insert(k.inputs.end(), named.output_names.begin(), named.output_names.end());
  k.outputs = named.input_names;
  k.A = plant.A - L * plant.C;
  k.B.resize(n, m + p);
  k.B << plant.B, L;
  k.C = -F;
  k.D = Eigen::MatrixXd::Zero(m, m + p);
  return k;
}

Eigen::VectorXd rms(const Eigen::MatrixXd& x) { return (x.colwise().squaredNorm() / double(x.rows())).cwiseSqrt(); }

}  // namespace

Scenario build_lamstf_scenario(const ScenarioOptions& o) {
  require(std::isfinite(o.sample_time) && o.sample_time > 0,
          "sample time must be positive, got " + std::to_string(o.sample_time));
  require(std::isfinite(o.duration) && o.duration >= 2 * o.sample_time,
          "duration must be at least two samples, got " + std::to_string(o.duration));
  require(std::isfinite(o.amplitude) && o.amplitude >= 0, "amplitude must be >= 0, got " + std::to_string(o.amplitude));
  require(std::isfinite(o.noise_level) && o.noise_level >= 0 && o.noise_level < 1,
          "noise level must be in [0, 1), got " + std::to_string(o.noise_level));
  require(std::isfinite(o.input_limit) && o.input_limit >= 0,
          "input limit must be >= 0, got " + std::to_string(o.input_limit));
  require(o.true_parameters.empty(), "the model has no parameters to set (its matrices are seed 002's)");
  require(o.effects.empty(), "the family has no effect catalogue");
  require(o.position_noise == 0 && o.current_noise == 0 && o.force_noise == 0,
          "noise is given relative to the loop's signals: use the noise level, not position, current or force noise");
  require(o.controller == "lqr",
          "the loop is seed 002's LQR with a Kalman predictor (controller 'lqr'), got '" + o.controller + "'");
  require(o.excitation == "gaussian" || o.excitation == "binary" || o.excitation == "none",
          "unknown excitation '" + o.excitation + "' (known: gaussian, binary, none)");

  const NamedSystem named = lamstf();
  const DiscreteSystem plant = c2d_zoh(named.system, o.sample_time);
  const Eigen::Index m = plant.inputs(), p = plant.outputs();
  Scenario s;
  s.truth = std::make_unique<LinearPlant>(named);
  Experiment& h = s.header;
  h.name = o.name;
  h.sample_time = o.sample_time;
  h.plant = {named.model, {}};
  h.y_names = named.output_names;
  h.u_names = named.input_names;
  for (const auto& name : h.y_names) h.operating_point[name] = 0.0;
  for (const auto& name : h.u_names) h.operating_point[name] = 0.0;
  const Eigen::Index samples = Eigen::Index(std::llround(o.duration / o.sample_time));
  s.options.samples = samples;
  s.options.seed = o.seed;
  // One RK4 step per 10 ms sample is 6e-4 off the zero-order hold per step for the 58.8 1/s
  // pole ((h lambda)^5 / 120), a 0.4 % bias of the 30th Markov parameter; 20 steps: 2e-10.
  s.options.substeps = std::max(1, int(std::ceil(o.sample_time / 5e-4)));
  if (o.excitation != "none" && o.amplitude > 0) {
    RandomOptions r;
    r.kind = o.excitation == "gaussian" ? NoiseKind::gaussian : NoiseKind::binary;
    r.amplitude = o.amplitude;
    r.seed = o.seed;
    r.channels = int(m);
    Excitation e = random_signal(r, samples, o.sample_time);
    s.options.excitation = std::move(e.samples);
    h.extra.json()["excitation"] = std::move(e.description.json());
    for (Eigen::Index j = 0; j < m; ++j) {
      h.r_names.push_back("r" + std::to_string(j + 1));
      h.operating_point[h.r_names.back()] = 0.0;
    }
  }
  nlohmann::json simulation = {{"seed", o.seed},
                               {"controller_design", "lqr (Q = I, R = I, poles in |z| < 0.85) + Kalman predictor"},
                               {"noise_level", o.noise_level}};
  if (o.noise_level > 0) {
    // The noise-free loop (any observer is exact without noise) gives the signal levels.
    Experiment calibration = h;
    calibration.controller = observer_lqr(plant, named, plant.B * plant.B.transpose(), Eigen::MatrixXd::Identity(p, p));
    ClosedLoopOptions clean = s.options;
    const Experiment run = run_closed_loop(*s.truth, calibration, clean);
    const Eigen::VectorXd ry = rms(run.y_deviation()), ru = rms(run.u_deviation());
    s.options.measurement_noise_std = o.noise_level * ry;
    s.options.process_noise_std = o.noise_level * ru;
    h.controller =
        observer_lqr(plant, named, plant.B * s.options.process_noise_std.cwiseAbs2().asDiagonal() * plant.B.transpose(),
                     s.options.measurement_noise_std.cwiseAbs2().asDiagonal());
    simulation["noise"] = {
        {"measurement_std",
         std::vector<double>(s.options.measurement_noise_std.begin(), s.options.measurement_noise_std.end())},
        {"process_std", std::vector<double>(s.options.process_noise_std.begin(), s.options.process_noise_std.end())}};
  } else {
    h.controller = observer_lqr(plant, named, plant.B * plant.B.transpose(), Eigen::MatrixXd::Identity(p, p));
  }
  if (o.input_limit > 0) {
    h.controller->output_limits.assign(std::size_t(m), Limit{-o.input_limit, o.input_limit});
    simulation["input_limit"] = o.input_limit;
  }
  h.extra.json()["simulation"] = std::move(simulation);
  return s;
}

Experiment simulate_lamstf(const ScenarioOptions& options, ClosedLoopStatistics* statistics) {
  const Scenario s = build_lamstf_scenario(options);
  return run_closed_loop(*s.truth, s.header, s.options, statistics);
}

ScenarioOptions lamstf_default_options() {
  ScenarioOptions o;
  o.plant = "lamstf";
  o.name = "lamstf simulation";
  o.sample_time = 0.01;
  o.duration = 80.0;
  o.controller = "lqr";
  o.excitation = "gaussian";
  o.amplitude = 1.0;
  o.noise_level = 0.005;
  return o;
}

}  // namespace ambid::sim
