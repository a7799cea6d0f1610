#pragma once
// The nonlinear `amb1dof_voltage` plant of the experiment contract (seed 000 eq. 1):
//   m x''  = K1/4 (i1/(x0 - x))^2 - K2/4 (i2/(x0 + x))^2 + Fz
//   kw1 u1 = R1 i1 + Ls1 i1' + K1/2 d/dt( i1/(x0 - x) )
//   kw2 u2 = R2 i2 + Ls2 i2' + K2/2 d/dt( i2/(x0 + x) )
// States x, x_dot, i1, i2; inputs u1, u2 (amplifier command voltages); outputs x, i1, i2;
// disturbance Fz [N]. Coil 1 pulls toward +x, coil 2 toward -x.
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/state_space.hpp"
#include "plant_sim/amb1dof_parameters.hpp"
#include "plant_sim/plant.hpp"

namespace ambid::sim {

class Amb1dofVoltage : public Plant {
 public:
  // Validates the parameters (Error naming the bad one).
  explicit Amb1dofVoltage(const Amb1dofParameters& parameters = Amb1dofParameters::nominal());

  const Amb1dofParameters& parameters() const { return p_; }

  std::string model() const override;                           // "amb1dof_voltage"
  std::vector<std::string> state_names() const override;        // x, x_dot, i1, i2
  std::vector<std::string> input_names() const override;        // u1, u2
  std::vector<std::string> output_names() const override;       // x, i1, i2
  std::vector<std::string> disturbance_names() const override;  // Fz

  // Throws Error ("rotor touched the bearing") when |x| >= x0, and on wrongly sized vectors.
  Eigen::VectorXd derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                             const Eigen::VectorXd& w) const override;
  Eigen::VectorXd output(const Eigen::VectorXd& x) const override;
  void output_into(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override;

  // RK4 on the fixed-size right-hand side: the same scheme as Rk4Integrator, without heap
  // allocation (the closed-loop runner's hot path).
  void advance(Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd& w, double sample_time,
               int substeps) const override;

  // Allocation-free right-hand side for fixed-size callers (same equations and checks).
  Eigen::Vector4d derivative(const Eigen::Vector4d& x, const Eigen::Vector2d& u, double Fz) const;

  // x = 0, x_dot = 0, i1 = i2 = i0; u_j = R_j i0 / kw_j. With K1 != K2 the forces at this
  // point do not balance: it stays the nominal operating point, not a rest point.
  Eigen::VectorXd equilibrium_state() const override;
  Eigen::VectorXd equilibrium_input() const override;

  // Analytic Jacobian at the operating point, seed 000 eq. (3)/(4): states x, x_dot, i1, i2;
  // inputs u1, u2; outputs x, i1, i2; D = 0. Deviations from the operating point.
  ContinuousSystem linearize() const;
  // d(state')/dFz at the operating point: [0, 1/m, 0, 0]^T (seed 000 eq. 3, B_F).
  Eigen::MatrixXd disturbance_matrix() const;
  // v1..v9 of seed 000 eq. (4) for these parameters (see amb1dof_physical.hpp).
  std::map<std::string, double> structure_parameters() const;

  // Typical magnitude of each state and input (x0, x0 * 1e3 1/s, i0, i0; u at equilibrium):
  // the scale for numerical differentiation (linearize.hpp).
  Eigen::VectorXd state_scale() const;
  Eigen::VectorXd input_scale() const;

 private:
  Amb1dofParameters p_;
};

}  // namespace ambid::sim
