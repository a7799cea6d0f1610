#include "plant_sim/maglev1coil_voltage.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace ambid::sim {
namespace {

void require_maglev_size(const Eigen::VectorXd& v, Eigen::Index n, const char* what) {
  if (v.size() != n) {
    std::ostringstream msg;
    msg << "maglev1coil_voltage: " << what << " must have " << n << " entries, got " << v.size();
    throw Error(msg.str());
  }
}

}  // namespace

Maglev1coilVoltage::Maglev1coilVoltage(const MaglevParameters& parameters, double operating_gap)
    : p_(parameters), gap_(operating_gap) {
  p_.validate();
  if (!(gap_ > p_.x_min && gap_ < p_.x_max)) {
    std::ostringstream msg;
    msg << "maglev1coil_voltage: operating gap " << gap_ << " m must lie between the stops x_min = " << p_.x_min
        << " m and x_max = " << p_.x_max << " m";
    throw Error(msg.str());
  }
}

std::string Maglev1coilVoltage::model() const { return "maglev1coil_voltage"; }
std::vector<std::string> Maglev1coilVoltage::state_names() const { return {"x", "x_dot", "i"}; }
std::vector<std::string> Maglev1coilVoltage::input_names() const { return {"u"}; }
std::vector<std::string> Maglev1coilVoltage::output_names() const { return {"x", "i"}; }
std::vector<std::string> Maglev1coilVoltage::disturbance_names() const { return {"Fz"}; }

Eigen::VectorXd Maglev1coilVoltage::derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                                               const Eigen::VectorXd& w) const {
  require_maglev_size(x, 3, "state (x, x_dot, i)");
  require_maglev_size(u, 1, "input (u)");
  require_maglev_size(w, 1, "disturbance (Fz)");
  const double gap = x[0], velocity = x[1], current = x[2];
  if (!(gap > 0.0)) {
    std::ostringstream msg;
    msg << "maglev1coil_voltage: the gap x must be positive, got " << gap << " m";
    throw Error(msg.str());
  }
  const double emf = -p_.n_i * p_.Ke * std::pow(std::abs(current), p_.n_i - 1.0) * velocity / std::pow(gap, p_.n_x);
  Eigen::VectorXd d(3);
  d << velocity, p_.g - p_.force(current, gap) / p_.m + w[0] / p_.m, (p_.kw * u[0] - p_.R * current - emf) / p_.L;
  return d;
}

Eigen::VectorXd Maglev1coilVoltage::output(const Eigen::VectorXd& x) const {
  require_maglev_size(x, 3, "state (x, x_dot, i)");
  return Eigen::Vector2d(x[0], x[2]);
}

Eigen::VectorXd Maglev1coilVoltage::equilibrium_state() const {
  return Eigen::Vector3d(gap_, 0.0, p_.equilibrium_current(gap_));
}

Eigen::VectorXd Maglev1coilVoltage::equilibrium_input() const {
  return Eigen::VectorXd::Constant(1, p_.R * p_.equilibrium_current(gap_) / p_.kw);
}

}  // namespace ambid::sim
