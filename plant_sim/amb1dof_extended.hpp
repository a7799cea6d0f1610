#pragma once
// `amb1dof_voltage` with effects of the catalogue (plant_sim/effects.hpp, equations in
// plant_sim/EFFECTS.md) switched on: the truth of a simulated machine that the nominal model
// does not fully describe, and the candidate models of the audit. With no effect, or only
// neutral ones, it behaves exactly as Amb1dofVoltage with the same parameters.
//
// States: x, x_dot, i1, i2 (as amb1dof_voltage), then the states of the active effects:
//   amplifier_bandwidth  v1 or v2         coil voltage of the lagging amplifier [V]
//   eddy_current         i1_force, i2_force  currents that make the force [A]
//   flexible_mode        q, q_dot          modal displacement seen by the sensor [m, m/s]
//   harmonic_disturbance harmonic_cos, harmonic_sin  cos and sin of 2 pi f t (start 1, 0)
//   sensor_delay         x_sensor_1..n, x_dot_sensor_1..n  past sensed positions and velocities (discrete: advanced
//   once per
//                                          sample by advance(), derivative 0)
// Outputs x (as the sensor reports it), i1, i2; inputs u1, u2; disturbance Fz.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "plant_sim/amb1dof_parameters.hpp"
#include "plant_sim/amb1dof_voltage.hpp"
#include "plant_sim/effects.hpp"
#include "plant_sim/plant.hpp"

namespace ambid::sim {

class Amb1dofExtended : public Plant {
 public:
  // `nominal`: the parameters before the parameter effects (coil_resistance, amplifier_gain,
  // air_gap, rotor_mass, force_factor) are applied. `sample_time` is needed only by sensor_delay (the delay
  // line holds one value per sample). Error for an effect given twice, a sensor delay without
  // a positive sample time, or parameters that become invalid (e.g. R1 + dR <= 0).
  Amb1dofExtended(const Amb1dofParameters& nominal, const std::vector<Effect>& effects, double sample_time = 0.0);

  // The parameters after the parameter effects, and the effects that act (non-neutral).
  const Amb1dofParameters& parameters() const { return base_.parameters(); }
  const std::vector<Effect>& effects() const { return effects_; }

  std::string model() const override;  // "amb1dof_voltage"
  std::vector<std::string> state_names() const override;
  std::vector<std::string> input_names() const override;
  std::vector<std::string> output_names() const override;
  std::vector<std::string> disturbance_names() const override;

  Eigen::VectorXd derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                             const Eigen::VectorXd& w) const override;
  Eigen::VectorXd output(const Eigen::VectorXd& x) const override;
  // RK4 on the continuous states (Amb1dofVoltage::advance when there are none beyond the
  // four of the nominal model; more sub-steps when a lag is faster than half a sub-step),
  // after one shift of the sensor delay line. Error when the
  // sample time differs from the constructor's while a sensor delay is active.
  void advance(Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd& w, double sample_time,
               int substeps) const override;

  Eigen::VectorXd equilibrium_state() const override;
  Eigen::VectorXd equilibrium_input() const override;

 private:
  using Continuous = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 12, 1>;
  Continuous continuous_derivative(const Continuous& s, const Eigen::Vector2d& u, double Fz) const;
  double sensed_position(const Eigen::VectorXd& x) const;  // x + q, before delay and gain
  double sensed_velocity(const Eigen::VectorXd& x) const;  // x_dot + q_dot

  Amb1dofVoltage base_;
  std::vector<Effect> effects_;
  double sample_time_ = 0.0;
  // Layout and parameters of the active dynamic effects (-1: effect not active).
  int amp_state_ = -1, amp_channel_ = 0, eddy_state_ = -1, flex_state_ = -1, harmonic_state_ = -1;
  int delay_state_ = -1, delay_whole_ = 0, delay_length_ = 0, continuous_states_ = 4;
  double amp_tau_ = 0.0, eddy_tau_ = 0.0, flex_coupling_ = 0.0, flex_omega_ = 0.0, flex_zeta_ = 0.0;
  double harmonic_omega_ = 0.0, harmonic_cos_ = 0.0, harmonic_sin_ = 0.0, delay_fraction_ = 0.0;
  double saturation_beta_ = 0.0, flux0_ = 0.0, sensor_gain_ = 1.0;
};

}  // namespace ambid::sim
