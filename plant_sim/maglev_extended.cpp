#include "plant_sim/maglev_extended.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "plant_sim/maglev_effects.hpp"
#include "plant_sim/maglev_rig.hpp"

namespace ambid::sim {
namespace {

void require_extended_size(const Eigen::VectorXd& v, Eigen::Index n, const char* what) {
  if (v.size() != n) {
    std::ostringstream msg;
    msg << "maglev1coil_voltage with effects: " << what << " must have " << n << " entries, got " << v.size();
    throw Error(msg.str());
  }
}

[[noreturn]] void fail_extended(const std::string& what, double value) {
  std::ostringstream msg;
  msg << "maglev1coil_voltage with effects: " << what << ", got " << value;
  throw Error(msg.str());
}

}  // namespace

MaglevExtended::MaglevExtended(const MaglevParameters& nominal, const MaglevOperatingPoint& point, bool measured,
                               const std::vector<Effect>& effects, double sample_time, double command_resolution)
    : p_(nominal), x0_(point.x), sample_time_(sample_time), command_resolution_(command_resolution) {
  nominal.validate();
  if (!(command_resolution >= 0.0) || !std::isfinite(command_resolution))
    fail_extended("the command's logging resolution must be finite and >= 0", command_resolution);
  if (!(point.x > nominal.x_min && point.x < nominal.x_max))
    fail_extended("the operating gap must lie between the stops", point.x);
  if (measured && !(point.i > 0.0)) fail_extended("the measured operating current must be positive", point.i);
  const auto& catalogue = maglev_effect_catalogue();
  std::set<std::string> seen;
  for (const auto& e : effects) {
    if (!seen.insert(e.name).second) throw Error("effect " + e.name + " given twice");
    if (e.neutral(effect_spec(catalogue, e.name))) continue;
    if (e.name == "force_law") {
      p_.n_i += e.at("dn_i");
      p_.n_x += e.at("dn_x");
    } else if (e.name == "coil_resistance") {
      p_.R += e.at("dR");
    } else if (e.name == "amplifier_gain") {
      p_.kw += e.at("dkw");
    } else if (e.name == "rotor_mass") {
      p_.m += e.at("dm");
    } else if (e.name == "sensor_gain") {
      sensor_scale_ = 1.0 + e.at("dgain");
    } else if (e.name == "sensor_offset") {
      sensor_offset_ = e.at("dy");
    } else if (e.name == "sensor_nonlinearity") {
      sensor_power_ = 1.0 + e.at("dp");
    } else if (e.name == "actuator_quantisation") {
      dac_step_ = e.at("step");
    } else if (e.name == "harmonic_disturbance") {
      harmonic_state_ = continuous_states_;
      continuous_states_ += 2;
      harmonic_omega_ = 2.0 * std::numbers::pi * e.at("f");
      harmonic_cos_ = e.at("Fc");
      harmonic_sin_ = e.at("Fs");
    } else if (e.name == "sensor_delay") {
      if (!(sample_time > 0.0) || !std::isfinite(sample_time))
        fail_extended("effect sensor_delay needs a positive sample time", sample_time);
      const double samples = e.at("delay") / sample_time;
      delay_whole_ = int(std::floor(samples + 1e-9));
      delay_fraction_ = std::max(0.0, samples - delay_whole_);
      if (delay_fraction_ < 1e-9) delay_fraction_ = 0.0;
      delay_length_ = delay_whole_ + (delay_fraction_ > 0.0 ? 1 : 0);
    } else {
      effect_spec(catalogue, e.name);  // Error naming the catalogue for an unknown effect
    }
  }
  if (delay_length_ > 0) delay_state_ = continuous_states_;
  try {
    p_.validate();
  } catch (const Error& err) {
    throw Error(std::string("the effects make the plant invalid: ") + err.what());
  }
  // The true gap where the sensor reads x0: invert y = scale x0 (x/x0)^power + offset.
  const double reading = (x0_ - sensor_offset_) / (sensor_scale_ * x0_);
  if (!(reading > 0.0)) fail_extended("no gap gives the sensor reading x0 with these sensor effects", x0_);
  gap0_ = x0_ * std::pow(reading, 1.0 / sensor_power_);
  if (!(gap0_ > p_.x_min && gap0_ < p_.x_max))
    fail_extended("the sensor effects put the true operating gap outside the stops", gap0_);
  // The force law's anchor (the header comment).
  const double anchor_gap = measured ? gap0_ : x0_;
  const double anchor_current = measured ? point.i : nominal.equilibrium_current(x0_);
  const double anchor_force = (measured ? p_.m : nominal.m) * p_.g;
  const double Km = anchor_force * std::pow(anchor_gap, p_.n_x) / std::pow(anchor_current, p_.n_i);
  p_.Ke = nominal.Ke * Km / nominal.Km;
  p_.Km = Km;
  current0_ = p_.equilibrium_current(gap0_);
  min_current_ = 1e-3 * current0_;
}

std::string MaglevExtended::model() const { return "maglev1coil_voltage"; }
std::vector<std::string> MaglevExtended::input_names() const { return {"u"}; }
std::vector<std::string> MaglevExtended::output_names() const { return {"x", "i"}; }
std::vector<std::string> MaglevExtended::disturbance_names() const { return {"Fz"}; }

std::vector<std::string> MaglevExtended::state_names() const {
  std::vector<std::string> names = {"gap", "gap_rate", "current"};
  if (harmonic_state_ >= 0) names.insert(names.end(), {"harmonic_cos", "harmonic_sin"});
  for (int j = 1; j <= delay_length_; ++j) names.push_back("x_sensor_" + std::to_string(j));
  return names;
}

double MaglevExtended::sensed(double gap) const {
  return sensor_scale_ * x0_ * std::pow(gap / x0_, sensor_power_) + sensor_offset_;
}

MaglevExtended::Continuous MaglevExtended::continuous_derivative(const Continuous& s, double u, double Fz) const {
  const double gap = s[0], rate = s[1], current = s[2];
  const double command = dac_step_ > 0.0 ? round_to(round_to(u, command_resolution_), dac_step_) : u;
  const double gap_power = std::pow(gap, p_.n_x);
  const double emf =
      -p_.n_i * p_.Ke * std::pow(std::max(std::abs(current), min_current_), p_.n_i - 1.0) * rate / gap_power;
  double force = Fz;
  if (harmonic_state_ >= 0) force += harmonic_cos_ * s[harmonic_state_] + harmonic_sin_ * s[harmonic_state_ + 1];
  Continuous d(continuous_states_);
  d[0] = rate;
  d[1] = p_.g + (force - std::copysign(p_.Km * std::pow(std::abs(current), p_.n_i), current) / gap_power) / p_.m;
  // On a stop, at rest, the stop's reaction cancels a force into it.
  if ((gap <= p_.x_min && rate <= 0.0 && d[1] < 0.0) || (gap >= p_.x_max && rate >= 0.0 && d[1] > 0.0)) d[1] = 0.0;
  d[2] = (p_.kw * command - p_.R * current - emf) / p_.L;
  if (harmonic_state_ >= 0) {
    d[harmonic_state_] = -harmonic_omega_ * s[harmonic_state_ + 1];
    d[harmonic_state_ + 1] = harmonic_omega_ * s[harmonic_state_];
  }
  return d;
}

Eigen::VectorXd MaglevExtended::derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                                           const Eigen::VectorXd& w) const {
  require_extended_size(x, continuous_states_ + delay_length_, "state");
  require_extended_size(u, 1, "input (u)");
  require_extended_size(w, 1, "disturbance (Fz)");
  if (!(x[0] > 0.0)) fail_extended("the gap must be positive", x[0]);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(x.size());  // the delay line is discrete: 0
  out.head(continuous_states_) = continuous_derivative(Continuous(x.head(continuous_states_)), u[0], w[0]);
  return out;
}

Eigen::VectorXd MaglevExtended::output(const Eigen::VectorXd& x) const {
  require_extended_size(x, continuous_states_ + delay_length_, "state");
  // value(j): the reading j samples ago (j = 0: now).
  auto value = [&](int j) { return j == 0 ? sensed(x[0]) : x[delay_state_ + j - 1]; };
  double reading = value(delay_whole_);
  if (delay_fraction_ > 0.0) reading = (1.0 - delay_fraction_) * reading + delay_fraction_ * value(delay_whole_ + 1);
  return Eigen::Vector2d(reading, x[2]);
}

void MaglevExtended::advance(Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd& w, double sample_time,
                             int substeps) const {
  require_extended_size(x, continuous_states_ + delay_length_, "state");
  require_extended_size(u, 1, "input (u)");
  require_extended_size(w, 1, "disturbance (Fz)");
  if (!(sample_time > 0.0) || !std::isfinite(sample_time) || substeps < 1)
    throw Error("maglev1coil_voltage with effects: sample time must be positive and substeps at least 1, got " +
                std::to_string(sample_time) + " s and " + std::to_string(substeps));
  if (delay_length_ > 0) {
    if (std::abs(sample_time - sample_time_) > 1e-9 * sample_time_)
      throw Error("effect sensor_delay was set up for sample time " + std::to_string(sample_time_) +
                  " s, advanced with " + std::to_string(sample_time) + " s");
    for (int j = delay_length_ - 1; j > 0; --j) x[delay_state_ + j] = x[delay_state_ + j - 1];
    x[delay_state_] = sensed(x[0]);
  }
  const int steps = std::max(substeps, int(std::ceil(5.0 * sample_time * p_.R / p_.L)));
  const double h = sample_time / steps, command = u[0], Fz = w[0];
  Continuous s = x.head(continuous_states_);
  for (int k = 0; k < steps; ++k) {
    const Continuous k1 = continuous_derivative(s, command, Fz);
    const Continuous k2 = continuous_derivative(Continuous(s + 0.5 * h * k1), command, Fz);
    const Continuous k3 = continuous_derivative(Continuous(s + 0.5 * h * k2), command, Fz);
    const Continuous k4 = continuous_derivative(Continuous(s + h * k3), command, Fz);
    s += (h / 6.0) * (k1 + 2.0 * (k2 + k3) + k4);
    if (!s.allFinite()) fail_extended("the state became non-finite, gap", s[0]);
    // Inelastic stops: the body rests on a stop until the forces pull it off.
    if (s[0] <= p_.x_min) {
      s[0] = p_.x_min;
      s[1] = std::max(s[1], 0.0);
    } else if (s[0] >= p_.x_max) {
      s[0] = p_.x_max;
      s[1] = std::min(s[1], 0.0);
    }
  }
  x.head(continuous_states_) = s;
}

double MaglevExtended::coil_current_after(double current, double command, double dt) const {
  const double applied = dac_step_ > 0.0 ? round_to(round_to(command, command_resolution_), dac_step_) : command;
  const double a = std::exp(-p_.R * dt / p_.L);
  return a * current + (1.0 - a) * p_.kw * applied / p_.R;
}

Eigen::VectorXd MaglevExtended::equilibrium_state() const {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(continuous_states_ + delay_length_);
  x.head(3) << gap0_, 0.0, current0_;
  if (harmonic_state_ >= 0) x[harmonic_state_] = 1.0;  // cos(0), sin(0): the phase starts at t = 0
  if (delay_length_ > 0) x.tail(delay_length_).setConstant(sensed(gap0_));
  return x;
}

Eigen::VectorXd MaglevExtended::equilibrium_input() const {
  return Eigen::VectorXd::Constant(1, p_.R * current0_ / p_.kw);
}

}  // namespace ambid::sim
