#include "plant_sim/amb1dof_extended.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <sstream>

#include "core/error.hpp"

namespace ambid::sim {
namespace {

// coil_resistance, amplifier_gain, air_gap, rotor_mass and force_factor change the nominal
// parameters.
Amb1dofParameters with_parameter_effects(Amb1dofParameters p, const std::vector<Effect>& effects) {
  std::set<std::string> seen;
  for (const auto& e : effects) {
    if (!seen.insert(e.name).second) throw Error("effect " + e.name + " given twice");
    const std::string channel = std::to_string(e.channel);
    if (e.name == "coil_resistance") p.set("R" + channel, p.get("R" + channel) + e.at("dR"));
    if (e.name == "amplifier_gain") p.set("kw" + channel, p.get("kw" + channel) + e.at("dkw"));
    if (e.name == "air_gap") p.x0 += e.at("dx0");
    if (e.name == "rotor_mass") p.m += e.at("dm");
    if (e.name == "force_factor") p.set("K" + channel, p.get("K" + channel) * (1.0 + e.at("dratio")));
  }
  try {
    p.validate();
  } catch (const Error& err) {
    throw Error(std::string("the effects make the plant invalid: ") + err.what());
  }
  return p;
}

void require_extended_size(const Eigen::VectorXd& v, Eigen::Index n, const char* what) {
  if (v.size() != n) {
    std::ostringstream msg;
    msg << "amb1dof_voltage with effects: " << what << " must have " << n << " entries, got " << v.size();
    throw Error(msg.str());
  }
}

}  // namespace

Amb1dofExtended::Amb1dofExtended(const Amb1dofParameters& nominal, const std::vector<Effect>& effects,
                                 double sample_time)
    : base_(with_parameter_effects(nominal, effects)), sample_time_(sample_time) {
  const Amb1dofParameters& p = base_.parameters();
  constexpr double two_pi = 2.0 * std::numbers::pi;
  for (const auto& e : effects) {
    if (e.neutral()) continue;
    effects_.push_back(e);
    if (e.name == "amplifier_bandwidth") {
      amp_state_ = continuous_states_++;
      amp_channel_ = e.channel;
      amp_tau_ = e.at("tau");
    } else if (e.name == "eddy_current") {
      eddy_state_ = continuous_states_;
      continuous_states_ += 2;
      eddy_tau_ = e.at("tau");
    } else if (e.name == "flexible_mode") {
      flex_state_ = continuous_states_;
      continuous_states_ += 2;
      flex_coupling_ = e.at("coupling");
      flex_omega_ = two_pi * e.at("f");
      flex_zeta_ = e.at("zeta");
    } else if (e.name == "harmonic_disturbance") {
      harmonic_state_ = continuous_states_;
      continuous_states_ += 2;
      harmonic_omega_ = two_pi * e.at("f");
      harmonic_cos_ = e.at("Fc");
      harmonic_sin_ = e.at("Fs");
    } else if (e.name == "magnetic_saturation") {
      saturation_beta_ = e.at("beta");
      flux0_ = p.i0 / p.x0;
    } else if (e.name == "sensor_gain") {
      sensor_gain_ = 1.0 + e.at("dgain");
    } else if (e.name == "sensor_delay") {
      if (!(sample_time > 0.0) || !std::isfinite(sample_time))
        throw Error("effect sensor_delay needs a positive sample time, got " + std::to_string(sample_time));
      const double samples = e.at("delay") / sample_time;
      delay_whole_ = int(std::floor(samples + 1e-9));
      delay_fraction_ = std::max(0.0, samples - delay_whole_);
      if (delay_fraction_ < 1e-9) delay_fraction_ = 0.0;
      delay_length_ = delay_whole_ + (delay_fraction_ > 0.0 ? 1 : 0);
    }
  }
  if (delay_length_ > 0) delay_state_ = continuous_states_;
}

std::string Amb1dofExtended::model() const { return base_.model(); }
std::vector<std::string> Amb1dofExtended::input_names() const { return base_.input_names(); }
std::vector<std::string> Amb1dofExtended::output_names() const { return base_.output_names(); }
std::vector<std::string> Amb1dofExtended::disturbance_names() const { return base_.disturbance_names(); }

std::vector<std::string> Amb1dofExtended::state_names() const {
  std::vector<std::string> names = base_.state_names();
  if (amp_state_ >= 0) names.push_back("v" + std::to_string(amp_channel_));
  if (eddy_state_ >= 0) names.insert(names.end(), {"i1_force", "i2_force"});
  if (flex_state_ >= 0) names.insert(names.end(), {"q", "q_dot"});
  if (harmonic_state_ >= 0) names.insert(names.end(), {"harmonic_cos", "harmonic_sin"});
  for (int j = 1; j <= delay_length_; ++j) names.push_back("x_sensor_" + std::to_string(j));
  for (int j = 1; j <= delay_length_; ++j) names.push_back("x_dot_sensor_" + std::to_string(j));
  return names;
}

Amb1dofExtended::Continuous Amb1dofExtended::continuous_derivative(const Continuous& s, const Eigen::Vector2d& u,
                                                                   double Fz) const {
  const Amb1dofParameters& p = base_.parameters();
  const Eigen::Vector4d core = s.head<4>();
  Eigen::Vector2d u_coil = u;  // the command that, through kw, gives the coil voltage
  if (amp_state_ >= 0) u_coil[amp_channel_ - 1] = s[amp_state_] / (amp_channel_ == 1 ? p.kw1 : p.kw2);
  double force = Fz;
  if (harmonic_state_ >= 0) force += harmonic_cos_ * s[harmonic_state_] + harmonic_sin_ * s[harmonic_state_ + 1];
  Eigen::Vector4d d = base_.derivative(core, u_coil, force);
  if (eddy_state_ >= 0 || saturation_beta_ > 0.0) {
    // The force follows the force currents (lagged by eddy currents, reduced by saturation),
    // the coil circuits the true currents.
    Eigen::Vector4d force_state = core;
    if (eddy_state_ >= 0) force_state.tail<2>() = s.segment<2>(eddy_state_);
    if (saturation_beta_ > 0.0) {
      for (int j = 0; j < 2; ++j) {
        const double gap = j == 0 ? p.x0 - core[0] : p.x0 + core[0];
        const double flux = force_state[2 + j] / (gap * flux0_);
        force_state[2 + j] /= std::sqrt(1.0 + saturation_beta_ * flux * flux);
        // The air-gap flux linkage K/2 phi(a) falls with it: the coil equation of the nominal
        // model with K/2 scaled by phi'(a) = (1 + beta (a/a0)^2)^(-3/2).
        const double a = core[2 + j] / gap,
                     slope = std::pow(1.0 + saturation_beta_ * (a / flux0_) * (a / flux0_), -1.5);
        const double K = (j == 0 ? p.K1 : p.K2) * slope, sign = j == 0 ? -1.0 : 1.0;
        d[2 + j] = ((j == 0 ? p.kw1 : p.kw2) * u_coil[j] - (j == 0 ? p.R1 : p.R2) * core[2 + j] +
                    sign * 0.5 * K * a * core[1] / gap) /
                   ((j == 0 ? p.Ls1 : p.Ls2) + 0.5 * K / gap);
      }
    }
    d[1] = base_.derivative(force_state, u_coil, force)[1];
  }
  Continuous out(continuous_states_);
  out.head<4>() = d;
  if (amp_state_ >= 0) {
    const double kw = amp_channel_ == 1 ? p.kw1 : p.kw2;
    out[amp_state_] = (kw * u[amp_channel_ - 1] - s[amp_state_]) / amp_tau_;
  }
  if (eddy_state_ >= 0) out.segment<2>(eddy_state_) = (core.tail<2>() - s.segment<2>(eddy_state_)) / eddy_tau_;
  if (flex_state_ >= 0) {
    const double q = s[flex_state_], qd = s[flex_state_ + 1];
    out[flex_state_] = qd;
    out[flex_state_ + 1] = -2.0 * flex_zeta_ * flex_omega_ * qd - flex_omega_ * flex_omega_ * q + flex_coupling_ * d[1];
  }
  if (harmonic_state_ >= 0) {
    out[harmonic_state_] = -harmonic_omega_ * s[harmonic_state_ + 1];
    out[harmonic_state_ + 1] = harmonic_omega_ * s[harmonic_state_];
  }
  return out;
}

Eigen::VectorXd Amb1dofExtended::derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                                            const Eigen::VectorXd& w) const {
  require_extended_size(x, continuous_states_ + 2 * delay_length_, "state");
  require_extended_size(u, 2, "input (u1, u2)");
  require_extended_size(w, 1, "disturbance (Fz)");
  Eigen::VectorXd out = Eigen::VectorXd::Zero(x.size());  // the delay line is discrete: 0
  out.head(continuous_states_) =
      continuous_derivative(Continuous(x.head(continuous_states_)), Eigen::Vector2d(u), w[0]);
  return out;
}

double Amb1dofExtended::sensed_position(const Eigen::VectorXd& x) const {
  return flex_state_ >= 0 ? x[0] + x[flex_state_] : x[0];
}

double Amb1dofExtended::sensed_velocity(const Eigen::VectorXd& x) const {
  return flex_state_ >= 0 ? x[1] + x[flex_state_ + 1] : x[1];
}

Eigen::VectorXd Amb1dofExtended::output(const Eigen::VectorXd& x) const {
  require_extended_size(x, continuous_states_ + 2 * delay_length_, "state");
  // value(j): the sensed position j samples ago (j = 0: now).
  // value(j), slope(j): the sensed position and velocity j samples ago (j = 0: now).
  auto value = [&](int j) { return j == 0 ? sensed_position(x) : x[delay_state_ + j - 1]; };
  auto slope = [&](int j) { return j == 0 ? sensed_velocity(x) : x[delay_state_ + delay_length_ + j - 1]; };
  double position = value(delay_whole_);
  if (delay_fraction_ > 0.0) {
    // Cubic Hermite between the samples around t - delay (s = 0 the older, 1 the newer): a
    // pure delay, where linear interpolation of the positions would also low-pass them
    // (|1 - f + f e^{-jwT}| < 1), which made a true delay of 1.5 samples fit as 1.9.
    const double s = 1.0 - delay_fraction_, s2 = s * s, s3 = s2 * s, T = sample_time_;
    const int newer = delay_whole_, older = delay_whole_ + 1;
    position = (2 * s3 - 3 * s2 + 1) * value(older) + (s3 - 2 * s2 + s) * T * slope(older) +
               (-2 * s3 + 3 * s2) * value(newer) + (s3 - s2) * T * slope(newer);
  }
  return Eigen::Vector3d(sensor_gain_ * position, x[2], x[3]);
}

void Amb1dofExtended::advance(Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd& w,
                              double sample_time, int substeps) const {
  require_extended_size(x, continuous_states_ + 2 * delay_length_, "state");
  require_extended_size(u, 2, "input (u1, u2)");
  require_extended_size(w, 1, "disturbance (Fz)");
  if (delay_length_ > 0) {
    if (std::abs(sample_time - sample_time_) > 1e-9 * sample_time_)
      throw Error("effect sensor_delay was set up for sample time " + std::to_string(sample_time_) +
                  " s, advanced with " + std::to_string(sample_time) + " s");
    for (int j = delay_length_ - 1; j > 0; --j) {
      x[delay_state_ + j] = x[delay_state_ + j - 1];
      x[delay_state_ + delay_length_ + j] = x[delay_state_ + delay_length_ + j - 1];
    }
    x[delay_state_] = sensed_position(x);
    x[delay_state_ + delay_length_] = sensed_velocity(x);
  }
  if (continuous_states_ == 4 && saturation_beta_ == 0.0) {  // nothing beyond the nominal dynamics
    Eigen::VectorXd core = x.head(4);
    base_.advance(core, u, w, sample_time, substeps);
    x.head(4) = core;
    return;
  }
  if (!(sample_time > 0.0) || !std::isfinite(sample_time) || substeps < 1)
    throw Error("amb1dof_voltage with effects: sample time must be positive and substeps at least 1, got " +
                std::to_string(sample_time) + " s and " + std::to_string(substeps));
  // RK4 is stable for |h lambda| < 2.78: fast lags (amplifier, eddy currents) get sub-steps
  // of at most half their time constant. An oscillator (flexible mode, harmonic force) gets
  // w h <= 0.25: at one step per sample a lightly damped mode at 1.3 kHz (w h = 0.82) came
  // out 14 % off a fine integration, at 2.5 kHz 32 %, and beyond 4.4 kHz RK4 diverges.
  const double fastest = std::min(amp_state_ >= 0 ? amp_tau_ : INFINITY, eddy_state_ >= 0 ? eddy_tau_ : INFINITY);
  const double omega = std::max(flex_state_ >= 0 ? flex_omega_ : 0.0, harmonic_state_ >= 0 ? harmonic_omega_ : 0.0);
  const int steps =
      std::max({substeps, int(std::ceil(2.0 * sample_time / fastest)), int(std::ceil(4.0 * omega * sample_time))});
  const Eigen::Vector2d u2(u);
  const double Fz = w[0], h = sample_time / steps;
  Continuous s = x.head(continuous_states_);
  for (int k = 0; k < steps; ++k) {
    const Continuous k1 = continuous_derivative(s, u2, Fz);
    const Continuous k2 = continuous_derivative(Continuous(s + 0.5 * h * k1), u2, Fz);
    const Continuous k3 = continuous_derivative(Continuous(s + 0.5 * h * k2), u2, Fz);
    const Continuous k4 = continuous_derivative(Continuous(s + h * k3), u2, Fz);
    s += (h / 6.0) * (k1 + 2.0 * (k2 + k3) + k4);
  }
  x.head(continuous_states_) = s;
}

Eigen::VectorXd Amb1dofExtended::equilibrium_state() const {
  const Amb1dofParameters& p = base_.parameters();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(continuous_states_ + 2 * delay_length_);
  x.head(4) = base_.equilibrium_state();
  if (amp_state_ >= 0) x[amp_state_] = (amp_channel_ == 1 ? p.R1 : p.R2) * p.i0;  // coil voltage
  if (eddy_state_ >= 0) x.segment(eddy_state_, 2).setConstant(p.i0);
  if (harmonic_state_ >= 0) x[harmonic_state_] = 1.0;  // cos(0), sin(0): the phase starts at t = 0
  return x;
}

Eigen::VectorXd Amb1dofExtended::equilibrium_input() const { return base_.equilibrium_input(); }

}  // namespace ambid::sim
