#include "plant_sim/maglev_linearize.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace ambid::sim {
namespace {

[[noreturn]] void fail_linearization(const char* what, double value) {
  std::ostringstream msg;
  msg << "maglev1coil_voltage linearisation: " << what << ", got " << value;
  throw Error(msg.str());
}

MaglevLinearization at(const MaglevParameters& p, const MaglevOperatingPoint& op) {
  p.validate();
  if (!(op.x > p.x_min && op.x < p.x_max))
    fail_linearization("the operating gap must lie strictly between the stops", op.x);
  if (!(op.i > 0.0) || !std::isfinite(op.i)) fail_linearization("the operating current must be positive", op.i);
  if (!std::isfinite(op.u)) fail_linearization("the operating command must be finite", op.u);
  MaglevLinearization out;
  out.point = op;
  out.Km = p.m * p.g * std::pow(op.x, p.n_x) / std::pow(op.i, p.n_i);
  out.Ke = p.Ke * out.Km / p.Km;
  out.stiffness = p.n_x * p.g / op.x;
  out.current_gain = p.n_i * p.g / op.i;
  out.unstable_pole = std::sqrt(out.stiffness);
  const double emf = p.n_i * out.Ke * std::pow(op.i, p.n_i - 1.0) / std::pow(op.x, p.n_x);
  Eigen::MatrixXd A(3, 3), B(3, 1), C(2, 3);
  A << 0.0, 1.0, 0.0,                         //
      out.stiffness, 0.0, -out.current_gain,  //
      0.0, emf / p.L, -p.R / p.L;
  B << 0.0, 0.0, p.kw / p.L;
  C << 1.0, 0.0, 0.0,  //
      0.0, 0.0, 1.0;
  out.system = {A, B, C, Eigen::MatrixXd::Zero(2, 1)};
  out.disturbance = Eigen::Vector3d(0.0, 1.0 / p.m, 0.0);
  out.nominal_current = p.equilibrium_current(op.x);
  out.nominal_input = p.R * out.nominal_current / p.kw;
  out.current_ratio = op.i / out.nominal_current;
  out.input_ratio = op.u / out.nominal_input;
  return out;
}

}  // namespace

MaglevLinearization maglev_linearize(const MaglevParameters& parameters, double gap) {
  parameters.validate();
  const double i = parameters.equilibrium_current(gap);
  return at(parameters, {gap, i, parameters.R * i / parameters.kw});
}

MaglevLinearization maglev_linearize_measured(const MaglevParameters& parameters, const MaglevOperatingPoint& point) {
  return at(parameters, point);
}

}  // namespace ambid::sim
