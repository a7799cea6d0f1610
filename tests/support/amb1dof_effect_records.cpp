#include "support/amb1dof_effect_records.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "plant_sim/amb1dof_parameters.hpp"
#include "plant_sim/amb1dof_voltage.hpp"
#include "plant_sim/observer_controller.hpp"
#include "plant_sim/pid.hpp"
#include "plant_sim/scenario.hpp"
#include "support/amb1dof_records.hpp"

namespace ambid::test_support {
namespace amb1dof_effect_records {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kMaxModes = 4;
// x, x_dot, i1, i2, v1, v2 (amplifier outputs), i1_force, i2_force, then q, q_dot per mode.
constexpr int kStates = 8 + 2 * kMaxModes;
using State = std::array<double, kStates>;

State axpy(const State& s, double h, const State& d) {
  State out;
  for (int i = 0; i < kStates; ++i) out[std::size_t(i)] = s[std::size_t(i)] + h * d[std::size_t(i)];
  return out;
}

double parameter(const sim::Effect& e, const std::string& name, double otherwise = 0.0) {
  const auto it = e.parameters.find(name);
  return it == e.parameters.end() ? otherwise : it->second;
}

// The true bearing: the nominal parameters with every effect, written from EFFECTS.md.
struct Truth {
  double m = 0, x0 = 0;
  std::array<double, 2> R{}, Ls{}, K{}, kw{};
  double amp_tau = 0;  // amplifier_bandwidth on amp_channel (0: none)
  int amp_channel = 0;
  double eddy_tau = 0;
  double sat_beta = 0, sat_flux0 = 0, sat_flux_limit = 0;  // beta form, or tanh form (limit > 0)
  std::vector<FlexibleModeTruth> modes;
  double harmonic_f = 0, harmonic_c = 0, harmonic_s = 0;
  double delay = 0, gain = 1, offset = 0;
  int drift_channel = 1;
  double drift = 0, drift_period = 1;

  // phi(a) and phi'(a) of the iron (identity without saturation).
  double flux(double a) const {
    if (sat_flux_limit > 0) return sat_flux_limit * std::tanh(a / sat_flux_limit);
    if (sat_beta > 0) return a / std::sqrt(1.0 + sat_beta * (a / sat_flux0) * (a / sat_flux0));
    return a;
  }
  double flux_slope(double a) const {
    if (sat_flux_limit > 0) {
      const double t = std::tanh(a / sat_flux_limit);
      return 1.0 - t * t;
    }
    if (sat_beta > 0) return std::pow(1.0 + sat_beta * (a / sat_flux0) * (a / sat_flux0), -1.5);
    return 1.0;
  }
  double amplifier_gain(int j, double t) const {
    return kw[std::size_t(j)] * (j + 1 == drift_channel ? 1.0 + drift * std::sin(kTwoPi * t / drift_period) : 1.0);
  }

  State derivative(const State& s, const std::array<double, 2>& u, double t, double force_noise) const {
    const double x = s[0], v = s[1];
    if (!(std::abs(x) < x0)) {
      std::ostringstream msg;
      msg << "effect records: the rotor touched the bearing at t = " << t << " s (x = " << x << " m)";
      throw Error(msg.str());
    }
    const std::array<double, 2> gap{x0 - x, x0 + x}, gap_rate{-v, v}, pull{1.0, -1.0};
    State d{};
    double force =
        force_noise + harmonic_c * std::cos(kTwoPi * harmonic_f * t) + harmonic_s * std::sin(kTwoPi * harmonic_f * t);
    for (int j = 0; j < 2; ++j) {
      const auto J = std::size_t(j);
      const double i = s[2 + J], g = gap[J];
      const double force_current = eddy_tau > 0 ? s[6 + J] : i;
      const double phi = flux(force_current / g);
      force += pull[J] * 0.25 * K[J] * phi * phi;
      // Flux linkage Ls i + K/2 phi(i/g): kw u = R i + Ls i' + K/2 phi'(a) (i'/g - i g'/g^2).
      const double voltage = amp_tau > 0 && j + 1 == amp_channel ? s[4 + J] : amplifier_gain(j, t) * u[J];
      const double slope = 0.5 * K[J] * flux_slope(i / g);
      d[2 + J] = (voltage - R[J] * i + slope * i * gap_rate[J] / (g * g)) / (Ls[J] + slope / g);
      if (amp_tau > 0 && j + 1 == amp_channel) d[4 + J] = (amplifier_gain(j, t) * u[J] - s[4 + J]) / amp_tau;
      if (eddy_tau > 0) d[6 + J] = (i - s[6 + J]) / eddy_tau;
    }
    d[0] = v;
    d[1] = force / m;
    for (std::size_t k = 0; k < modes.size(); ++k) {
      const double w = kTwoPi * modes[k].f, q = s[8 + 2 * k], qd = s[9 + 2 * k];
      d[8 + 2 * k] = qd;
      d[9 + 2 * k] = -2.0 * modes[k].zeta * w * qd - w * w * q + modes[k].coupling * d[1];
    }
    return d;
  }
  double sensed(const State& s) const {
    double position = s[0];
    for (std::size_t k = 0; k < modes.size(); ++k) position += s[8 + 2 * k];
    return position;
  }
};

Truth make_truth(const EffectRecordOptions& o) {
  const sim::Amb1dofParameters p = sim::Amb1dofParameters::nominal();
  Truth t;
  t.m = p.m;
  t.x0 = p.x0;
  t.R = {p.R1, p.R2};
  t.Ls = {p.Ls1, p.Ls2};
  t.K = {p.K1, p.K2};
  t.kw = {p.kw1, p.kw2};
  t.modes = o.out_of_catalogue.modes;
  for (const auto& e : o.effects) {
    const std::size_t j = e.channel == 2 ? 1 : 0;
    if (e.name == "coil_resistance") {
      t.R[j] += e.at("dR");
    } else if (e.name == "amplifier_gain") {
      t.kw[j] += e.at("dkw");
    } else if (e.name == "amplifier_bandwidth") {
      t.amp_tau = e.at("tau");
      t.amp_channel = int(j) + 1;
    } else if (e.name == "eddy_current") {
      t.eddy_tau = e.at("tau");
    } else if (e.name == "sensor_delay") {
      t.delay = e.at("delay");
    } else if (e.name == "sensor_gain") {
      t.gain = 1.0 + e.at("dgain");
    } else if (e.name == "flexible_mode") {
      t.modes.push_back({e.at("coupling"), e.at("f"), e.at("zeta")});
    } else if (e.name == "magnetic_saturation") {
      t.sat_beta = parameter(e, "beta");
      t.sat_flux0 = p.i0 / p.x0;
      if (parameter(e, "i_sat") > 0) t.sat_flux_limit = parameter(e, "i_sat") / p.x0;
    } else if (e.name == "air_gap") {
      t.x0 += e.at("dx0");
    } else if (e.name == "rotor_mass") {
      t.m += e.at("dm");
    } else if (e.name == "harmonic_disturbance") {
      t.harmonic_f = e.at("f");
      t.harmonic_c = e.at("Fc");
      t.harmonic_s = e.at("Fs");
    } else if (e.name == "force_factor") {
      t.K[j] *= 1.0 + e.at("dratio");
    } else {
      throw Error("effect records: unknown effect '" + e.name + "'");
    }
  }
  const OutOfCatalogue& x = o.out_of_catalogue;
  t.Ls[x.inductance_channel == 2 ? 1 : 0] *= 1.0 + x.inductance_error;
  t.offset = x.sensor_offset;
  t.drift_channel = x.gain_drift_channel;
  t.drift = x.gain_drift;
  t.drift_period = x.gain_drift_period;
  if (t.modes.size() > std::size_t(kMaxModes)) throw Error("effect records: at most 4 flexible modes");
  return t;
}

// A lead-lag on x (the PID's proportional and derivative action, a lag section instead of its
// integrator) with the PID's proportional current loops.
StateSpaceController lead_lag(double sample_time) {
  sim::LeadLagLoop position{"x", {{"u1", 1.0}, {"u2", -1.0}}, 2.86e7, {{5.68e-4, 1e-4}, {0.05, 0.5}}};
  sim::LeadLagLoop coil1{"i1", {{"u1", 1.0}}, 1000.0, {}};
  sim::LeadLagLoop coil2{"i2", {{"u2", 1.0}}, 1000.0, {}};
  return sim::lead_lag_controller({position, coil1, coil2}, sample_time, {"u1", "u2"});
}

// The sidecar (nominal plant, controller, PRBS r) and the excitation samples.
sim::Scenario header_of(const EffectRecordOptions& o) {
  const auto& known = effect_record_controllers();
  if (std::find(known.begin(), known.end(), o.controller) == known.end())
    throw Error("effect records: unknown controller '" + o.controller + "' (known: lqr, observer, pid, leadlag)");
  sim::ScenarioOptions s;
  s.controller = o.controller == "pid" ? "pid" : "lqr";
  s.amplitude = o.amplitude;
  s.duration = o.duration;
  s.sample_time = o.sample_time;
  s.seed = o.seed;
  sim::Scenario scenario = sim::build_scenario(s);
  if (o.controller == "observer") {
    const sim::Amb1dofVoltage nominal(sim::Amb1dofParameters::nominal());
    scenario.header.controller = sim::design_observer_controller(
        nominal.linearize(), o.sample_time, scenario.header.u_names, scenario.header.y_names, other_observer_options());
  } else if (o.controller == "leadlag") {
    scenario.header.controller = lead_lag(o.sample_time);
  }
  return scenario;
}

nlohmann::json description(const EffectRecordOptions& o) {
  nlohmann::json effects = nlohmann::json::array();
  for (const auto& e : o.effects)
    effects.push_back({{"effect", e.name},
                       {"channel", e.channel ? nlohmann::json(e.channel) : nlohmann::json()},
                       {"parameters", e.parameters}});
  const OutOfCatalogue& x = o.out_of_catalogue;
  nlohmann::json modes = nlohmann::json::array();
  for (const auto& m : x.modes) modes.push_back({{"coupling", m.coupling}, {"f", m.f}, {"zeta", m.zeta}});
  return {{"generator", "tests/support/amb1dof_effect_records (independent RK4, fine-step sensor)"},
          {"controller_design", o.controller},
          {"seed", o.seed},
          {"effects", effects},
          {"out_of_catalogue",
           {{"inductance", {{"channel", x.inductance_channel}, {"relative_error", x.inductance_error}}},
            {"sensor_offset", x.sensor_offset},
            {"modes", modes},
            {"gain_drift",
             {{"channel", x.gain_drift_channel}, {"amplitude", x.gain_drift}, {"period", x.gain_drift_period}}}}},
          {"noise",
           {{"x", o.position_noise},
            {"i1", o.current_noise},
            {"i2", o.current_noise},
            {"coloured_fraction", o.coloured_fraction},
            {"time_constant", o.noise_time_constant},
            {"Fz", o.force_noise}}}};
}

// White plus first-order coloured noise of total rms `rms`.
class SensorNoise {
 public:
  SensorNoise(double rms, double coloured_fraction, double time_constant, double dt)
      : white_(rms * std::sqrt(1.0 - coloured_fraction)),
        coloured_(rms * std::sqrt(coloured_fraction)),
        pole_(std::exp(-dt / time_constant)) {}
  double next(std::mt19937_64& rng) {
    if (first_) state_ = coloured_ * normal_(rng), first_ = false;  // stationary start
    const double value = state_ + white_ * normal_(rng);
    state_ = pole_ * state_ + coloured_ * std::sqrt(1.0 - pole_ * pole_) * normal_(rng);
    return value;
  }

 private:
  double white_, coloured_, pole_, state_ = 0.0;
  bool first_ = true;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

}  // namespace amb1dof_effect_records
using namespace amb1dof_effect_records;

const std::vector<std::string>& effect_record_controllers() {
  static const std::vector<std::string> names = {"lqr", "observer", "pid", "leadlag"};
  return names;
}

Experiment simulate_effect_record(const EffectRecordOptions& o) {
  if (!(o.coloured_fraction >= 0.0 && o.coloured_fraction <= 1.0) || !(o.noise_time_constant > 0.0) || o.substeps < 1)
    throw Error("effect records: coloured_fraction in [0, 1], a positive noise time constant, substeps >= 1");
  const Truth truth = make_truth(o);
  sim::Scenario scenario = header_of(o);
  Experiment e = std::move(scenario.header);
  e.extra.json()["simulation"] = description(o);
  const StateSpaceController& ctrl = *e.controller;
  const double dt = o.sample_time;
  const Eigen::Index N = scenario.options.samples;
  const Eigen::MatrixXd& excitation = scenario.options.excitation;
  const Eigen::VectorXd y_op = e.operating_values(e.y_names), u_op = e.operating_values(e.u_names);

  // Lags faster than half a step would make RK4 unstable: more steps for them.
  double fastest = INFINITY;
  if (truth.amp_tau > 0) fastest = std::min(fastest, truth.amp_tau);
  if (truth.eddy_tau > 0) fastest = std::min(fastest, truth.eddy_tau);
  const int steps = std::max(o.substeps, int(std::ceil(4.0 * dt / fastest)));
  const double h = dt / steps;

  State s{};
  s[2] = s[3] = y_op[1];  // both coils at the bias current (the operating point's i1 = i2)
  for (int j = 0; j < 2; ++j) {
    s[4 + std::size_t(j)] = truth.amplifier_gain(j, 0.0) * u_op[j];
    s[6 + std::size_t(j)] = s[2 + std::size_t(j)];
  }
  // The sensed position at every fine step (the sensor delay reads it between steps).
  std::vector<double> history;
  history.reserve(std::size_t(N * steps + 1));
  history.push_back(truth.sensed(s));
  auto delayed = [&](double t) {
    const double at = (t - truth.delay) / h;
    if (at <= 0.0) return history.front();
    const auto k = std::size_t(std::floor(at));
    if (k + 1 >= history.size()) return history.back();
    const double f = at - double(k);
    return (1.0 - f) * history[k] + f * history[k + 1];
  };

  std::mt19937_64 rng(o.seed ^ 0x5eed5eedULL);
  std::normal_distribution<double> normal(0.0, 1.0);
  SensorNoise x_noise(o.position_noise, o.coloured_fraction, o.noise_time_constant, dt);
  SensorNoise i1_noise(o.current_noise, o.coloured_fraction, o.noise_time_constant, dt);
  SensorNoise i2_noise(o.current_noise, o.coloured_fraction, o.noise_time_constant, dt);

  // Controller routes (experiment-format.md: inputs are y, u or r signals).
  auto index_in = [](const std::vector<std::string>& names, const std::string& n) {
    return std::find(names.begin(), names.end(), n) - names.begin();
  };
  Eigen::VectorXd xc = ctrl.initial_state.size() ? ctrl.initial_state : Eigen::VectorXd::Zero(ctrl.states());
  Eigen::VectorXd v = Eigen::VectorXd::Zero(ctrl.B.cols());
  e.t.resize(N);
  e.y.resize(N, 3);
  e.u.resize(N, 2);
  e.r.resize(N, 2);
  for (Eigen::Index k = 0; k < N; ++k) {
    const double t = double(k) * dt;
    const Eigen::Vector3d y(truth.gain * delayed(t) + truth.offset + x_noise.next(rng), s[2] + i1_noise.next(rng),
                            s[3] + i2_noise.next(rng));
    for (std::size_t j = 0; j < ctrl.inputs.size(); ++j) {
      const std::string& name = ctrl.inputs[j];
      if (const auto i = index_in(e.y_names, name); i < std::ssize(e.y_names))
        v[Eigen::Index(j)] = y[i] - y_op[i];
      else if (const auto r = index_in(e.r_names, name); r < std::ssize(e.r_names))
        v[Eigen::Index(j)] = excitation(k, r);
      else
        v[Eigen::Index(j)] = 0.0;  // a u signal: filled in below (D has no u columns)
    }
    Eigen::VectorXd du = ctrl.C * xc + ctrl.D * v + excitation.row(k).transpose();
    for (std::size_t j = 0; j < ctrl.inputs.size(); ++j)
      if (const auto i = index_in(e.u_names, ctrl.inputs[j]); i < std::ssize(e.u_names)) v[Eigen::Index(j)] = du[i];
    e.t[k] = t;
    e.y.row(k) = y.transpose();
    e.u.row(k) = (u_op + du).transpose();
    e.r.row(k) = excitation.row(k);
    const std::array<double, 2> u{u_op[0] + du[0], u_op[1] + du[1]};
    const double force = o.force_noise * normal(rng);
    for (int step = 0; step < steps; ++step) {
      const double ts = t + step * h;
      const State k1 = truth.derivative(s, u, ts, force);
      const State k2 = truth.derivative(axpy(s, 0.5 * h, k1), u, ts + 0.5 * h, force);
      const State k3 = truth.derivative(axpy(s, 0.5 * h, k2), u, ts + 0.5 * h, force);
      const State k4 = truth.derivative(axpy(s, h, k3), u, ts + h, force);
      for (int i = 0; i < kStates; ++i) {
        const auto I = std::size_t(i);
        s[I] += h / 6.0 * (k1[I] + 2.0 * (k2[I] + k3[I]) + k4[I]);
      }
      history.push_back(truth.sensed(s));
    }
    xc = ctrl.A * xc + ctrl.B * v;
  }
  if (!e.y.allFinite()) throw Error("effect records: the loop went unstable (" + o.controller + ")");
  return e;
}

}  // namespace ambid::test_support
