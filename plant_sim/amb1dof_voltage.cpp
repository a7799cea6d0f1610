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

// States x, x_dot, i1, i2 as plain scalars: the RK4 stages stay in registers.
struct State {
  double pos, vel, i1, i2;
};

State operator+(const State& a, const State& b) { return {a.pos + b.pos, a.vel + b.vel, a.i1 + b.i1, a.i2 + b.i2}; }
State operator*(double c, const State& a) { return {c * a.pos, c * a.vel, c * a.i1, c * a.i2}; }

// The right-hand side with u and Fz held, as the RK4 stages evaluate it. Multiplying the
// current equations by g^2 and the force by g1^2 g2^2 leaves three independent divisions
// per evaluation instead of five chained ones (the same equations to rounding; a sample's
// RK4 stages are one long dependency chain, so its latency sets the simulation speed).
// Terms in the gaps are formed first: the currents and the velocity arrive last.
class RightHandSide {
 public:
  RightHandSide(const Amb1dofParameters& p, double u1, double u2, double Fz)
      : p_(p),
        drive1_(p.kw1 * u1),
        drive2_(p.kw2 * u2),
        acceleration_(Fz / p.m),
        force1_(0.25 * p.K1 / p.m),
        force2_(0.25 * p.K2 / p.m),
        half_K1_(0.5 * p.K1),
        half_K2_(0.5 * p.K2) {}

  // Throws Error ("rotor touched the bearing") when |x| >= x0.
  State operator()(const State& s) const {
    if (!(std::abs(s.pos) < p_.x0)) touched(s.pos);
    const double g1 = p_.x0 - s.pos;  // air gap of coil 1 (pulls toward +x)
    const double g2 = p_.x0 + s.pos;  // air gap of coil 2 (pulls toward -x)
    const double g1g1 = g1 * g1, g2g2 = g2 * g2;
    // m x'' = K1/4 (i1/g1)^2 - K2/4 (i2/g2)^2 + Fz
    const double force = (force1_ * g2g2) * (s.i1 * s.i1) - (force2_ * g1g1) * (s.i2 * s.i2);
    // kw u = R i + Ls i' + K/2 (i'/g + i g'/g^2) with g1' = -x', g2' = +x'.
    const double voltage1 = (drive1_ * g1g1 - (p_.R1 * g1g1) * s.i1) - (half_K1_ * s.vel) * s.i1;
    const double voltage2 = (drive2_ * g2g2 - (p_.R2 * g2g2) * s.i2) + (half_K2_ * s.vel) * s.i2;
    return {s.vel, force / (g1g1 * g2g2) + acceleration_, voltage1 / (g1 * (p_.Ls1 * g1 + half_K1_)),
            voltage2 / (g2 * (p_.Ls2 * g2 + half_K2_))};
  }

  // Out of line: the message formatting would otherwise keep the stages from being inlined.
  [[noreturn, gnu::cold, gnu::noinline]] void touched(double pos) const {
    std::ostringstream msg;
    if (std::isnan(pos))
      msg << "amb1dof_voltage: rotor position x is not a number";
    else
      msg << "amb1dof_voltage: the rotor touched the bearing: x = " << pos << " m, air gap x0 = " << p_.x0 << " m";
    throw Error(msg.str());
  }

  const Amb1dofParameters& p_;
  double drive1_, drive2_, acceleration_, force1_, force2_, half_K1_, half_K2_;
};

}  // namespace

Amb1dofVoltage::Amb1dofVoltage(const Amb1dofParameters& parameters) : p_(parameters) { p_.validate(); }

std::string Amb1dofVoltage::model() const { return "amb1dof_voltage"; }
std::vector<std::string> Amb1dofVoltage::state_names() const { return {"x", "x_dot", "i1", "i2"}; }
std::vector<std::string> Amb1dofVoltage::input_names() const { return {"u1", "u2"}; }
std::vector<std::string> Amb1dofVoltage::output_names() const { return {"x", "i1", "i2"}; }
std::vector<std::string> Amb1dofVoltage::disturbance_names() const { return {"Fz"}; }

Eigen::Vector4d Amb1dofVoltage::derivative(const Eigen::Vector4d& x, const Eigen::Vector2d& u, double Fz) const {
  const State d = RightHandSide(p_, u[0], u[1], Fz)({x[0], x[1], x[2], x[3]});
  return {d.pos, d.vel, d.i1, d.i2};
}

void Amb1dofVoltage::advance(Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd& w, double sample_time,
                             int substeps) const {
  require_size(x, 4, "state (x, x_dot, i1, i2)");
  require_size(u, 2, "input (u1, u2)");
  require_size(w, 1, "disturbance (Fz)");
  if (!(sample_time > 0.0) || !std::isfinite(sample_time) || substeps < 1) {
    std::ostringstream msg;
    msg << "amb1dof_voltage: sample time must be positive and substeps at least 1, got " << sample_time << " s and "
        << substeps;
    throw Error(msg.str());
  }
  const RightHandSide f(p_, u[0], u[1], w[0]);
  const double h = sample_time / substeps;
  State s{x[0], x[1], x[2], x[3]};
  for (int k = 0; k < substeps; ++k) {
    const State k1 = f(s);
    const State k2 = f(s + (0.5 * h) * k1);
    const State k3 = f(s + (0.5 * h) * k2);
    const State k4 = f(s + h * k3);
    s = s + (h / 6.0) * (k1 + 2.0 * (k2 + k3) + k4);
  }
  x << s.pos, s.vel, s.i1, s.i2;
}

Eigen::VectorXd Amb1dofVoltage::derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                                           const Eigen::VectorXd& w) const {
  require_size(x, 4, "state (x, x_dot, i1, i2)");
  require_size(u, 2, "input (u1, u2)");
  require_size(w, 1, "disturbance (Fz)");
  return derivative(Eigen::Vector4d(x), Eigen::Vector2d(u), w[0]);
}

Eigen::VectorXd Amb1dofVoltage::output(const Eigen::VectorXd& x) const {
  Eigen::VectorXd y(3);
  output_into(x, y);
  return y;
}

void Amb1dofVoltage::output_into(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  require_size(x, 4, "state (x, x_dot, i1, i2)");
  y.resize(3);
  y << x[0], x[2], x[3];
}

Eigen::VectorXd Amb1dofVoltage::equilibrium_state() const { return Eigen::Vector4d(0.0, 0.0, p_.i0, p_.i0); }

Eigen::VectorXd Amb1dofVoltage::equilibrium_input() const {
  return Eigen::Vector2d(p_.R1 * p_.i0 / p_.kw1, p_.R2 * p_.i0 / p_.kw2);
}

ContinuousSystem Amb1dofVoltage::linearize() const { return amb1dof_structure_system(structure_parameters()); }

Eigen::MatrixXd Amb1dofVoltage::disturbance_matrix() const { return Eigen::Vector4d(0.0, 1.0 / p_.m, 0.0, 0.0); }

std::map<std::string, double> Amb1dofVoltage::structure_parameters() const { return amb1dof_structure_parameters(p_); }

Eigen::VectorXd Amb1dofVoltage::state_scale() const { return Eigen::Vector4d(p_.x0, p_.x0 * 1e3, p_.i0, p_.i0); }

Eigen::VectorXd Amb1dofVoltage::input_scale() const { return equilibrium_input(); }

}  // namespace ambid::sim
