#include "plant_sim/amb1dof_voltage.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "plant_sim/amb1dof_physical.hpp"

namespace ambid::sim {
namespace {

void require_size(const Eigen::VectorXd& v, Eigen::Index n, const char* what) {
  if (v.size() != n) {
    std::ostringstream msg;
    msg << "amb1dof_voltage: " << what << " must have " << n << " entries, got " << v.size();
    throw Error(msg.str());
  }
}

}  // namespace

Amb1dofVoltage::Amb1dofVoltage(const Amb1dofParameters& parameters) : p_(parameters) {
  p_.validate();
}

std::string Amb1dofVoltage::model() const { return "amb1dof_voltage"; }
std::vector<std::string> Amb1dofVoltage::state_names() const {
  return {"x", "x_dot", "i1", "i2"};
}
std::vector<std::string> Amb1dofVoltage::input_names() const { return {"u1", "u2"}; }
std::vector<std::string> Amb1dofVoltage::output_names() const { return {"x", "i1", "i2"}; }
std::vector<std::string> Amb1dofVoltage::disturbance_names() const { return {"Fz"}; }

Eigen::Vector4d Amb1dofVoltage::derivative(const Eigen::Vector4d& x, const Eigen::Vector2d& u,
                                           double Fz) const {
  const double pos = x[0], vel = x[1], i1 = x[2], i2 = x[3];
  if (!(std::abs(pos) < p_.x0)) {
    std::ostringstream msg;
    if (std::isnan(pos))
      msg << "amb1dof_voltage: rotor position x is not a number";
    else
      msg << "amb1dof_voltage: the rotor touched the bearing: x = " << pos
          << " m, air gap x0 = " << p_.x0 << " m";
    throw Error(msg.str());
  }
  const double r1 = 1.0 / (p_.x0 - pos);  // reciprocal gap of coil 1 (pulls toward +x)
  const double r2 = 1.0 / (p_.x0 + pos);  // reciprocal gap of coil 2 (pulls toward -x)
  const double a1 = i1 * r1, a2 = i2 * r2;
  const double force = 0.25 * (p_.K1 * a1 * a1 - p_.K2 * a2 * a2) + Fz;
  // kw u = R i + Ls i' + K/2 (i'/g + i g'/g^2) with g1' = -x', g2' = +x'.
  const double di1 = (p_.kw1 * u[0] - p_.R1 * i1 - 0.5 * p_.K1 * a1 * vel * r1) /
                     (p_.Ls1 + 0.5 * p_.K1 * r1);
  const double di2 = (p_.kw2 * u[1] - p_.R2 * i2 + 0.5 * p_.K2 * a2 * vel * r2) /
                     (p_.Ls2 + 0.5 * p_.K2 * r2);
  return {vel, force / p_.m, di1, di2};
}

void Amb1dofVoltage::advance(Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd& w,
                             double sample_time, int substeps) const {
  require_size(x, 4, "state (x, x_dot, i1, i2)");
  require_size(u, 2, "input (u1, u2)");
  require_size(w, 1, "disturbance (Fz)");
  if (!(sample_time > 0.0) || !std::isfinite(sample_time) || substeps < 1) {
    std::ostringstream msg;
    msg << "amb1dof_voltage: sample time must be positive and substeps at least 1, got " << sample_time
        << " s and " << substeps;
    throw Error(msg.str());
  }
  const Eigen::Vector2d u2(u);
  const double Fz = w[0], h = sample_time / substeps;
  Eigen::Vector4d s(x);
  for (int k = 0; k < substeps; ++k) {
    const Eigen::Vector4d k1 = derivative(s, u2, Fz);
    const Eigen::Vector4d k2 = derivative(Eigen::Vector4d(s + 0.5 * h * k1), u2, Fz);
    const Eigen::Vector4d k3 = derivative(Eigen::Vector4d(s + 0.5 * h * k2), u2, Fz);
    const Eigen::Vector4d k4 = derivative(Eigen::Vector4d(s + h * k3), u2, Fz);
    s += (h / 6.0) * (k1 + 2.0 * (k2 + k3) + k4);
  }
  x = s;
}

Eigen::VectorXd Amb1dofVoltage::derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                                           const Eigen::VectorXd& w) const {
  require_size(x, 4, "state (x, x_dot, i1, i2)");
  require_size(u, 2, "input (u1, u2)");
  require_size(w, 1, "disturbance (Fz)");
  return derivative(Eigen::Vector4d(x), Eigen::Vector2d(u), w[0]);
}

Eigen::VectorXd Amb1dofVoltage::output(const Eigen::VectorXd& x) const {
  require_size(x, 4, "state (x, x_dot, i1, i2)");
  return Eigen::Vector3d(x[0], x[2], x[3]);
}

Eigen::VectorXd Amb1dofVoltage::equilibrium_state() const {
  return Eigen::Vector4d(0.0, 0.0, p_.i0, p_.i0);
}

Eigen::VectorXd Amb1dofVoltage::equilibrium_input() const {
  return Eigen::Vector2d(p_.R1 * p_.i0 / p_.kw1, p_.R2 * p_.i0 / p_.kw2);
}

ContinuousSystem Amb1dofVoltage::linearize() const {
  return amb1dof_structure_system(structure_parameters());
}

Eigen::MatrixXd Amb1dofVoltage::disturbance_matrix() const {
  return Eigen::Vector4d(0.0, 1.0 / p_.m, 0.0, 0.0);
}

std::map<std::string, double> Amb1dofVoltage::structure_parameters() const {
  return amb1dof_structure_parameters(p_);
}

Eigen::VectorXd Amb1dofVoltage::state_scale() const {
  return Eigen::Vector4d(p_.x0, p_.x0 * 1e3, p_.i0, p_.i0);
}

Eigen::VectorXd Amb1dofVoltage::input_scale() const { return equilibrium_input(); }

}  // namespace ambid::sim
