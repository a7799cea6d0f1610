#pragma once
// `maglev1coil_voltage` with effects of its catalogue (plant_sim/maglev_effects.hpp) switched
// on: the audit's candidate models of a rig record. With no effect it is the nominal model of
// maglev_parameters.hpp.
//
// The force law is anchored at the operating point of the record: F = F_a (i/i_a)^n_i
// (x_a/x)^n_x, i.e. Km' = F_a x_a^n_x / i_a^n_i, and the back-EMF constant follows it
// (Ke' = Ke Km'/Km, as in maglev_linearize.hpp):
//   measured point: x_a = the true gap where the (possibly wrong) sensor reads x0, i_a = i0,
//     F_a = (m + dm) g: gravity balance closes the force constant there, whatever the exponents;
//   nominal point: x_a = x0, i_a = the nominal equilibrium current at x0, F_a = m g (nominal
//     m): Km' = Km for the nominal exponents; force_law changes the law's shape about x0.
// States: gap, gap_rate, current (the true gap, not the sensor's x: the closed-loop runner
// gives states named like a signal the operating point's value), then harmonic_cos,
// harmonic_sin (harmonic_disturbance), then x_sensor_1..n (sensor_delay: past readings,
// advanced once per sample by advance(), derivative 0). Outputs x (the sensor's reading), i;
// input u (the command; actuator_quantisation rounds it as the record logs it: the audit
// replays the DAC on the logged command, and a step fitted a fraction off the true one puts
// its edges between the logged values where the record has none, so a model that rounded the
// unlogged command would round samples across an edge that the replay cannot; with the true
// 0.35 V step the edges lie midway between the rig's 0.01 V and both agree); disturbance Fz.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "plant_sim/effects.hpp"
#include "plant_sim/maglev_linearize.hpp"
#include "plant_sim/maglev_parameters.hpp"
#include "plant_sim/plant.hpp"

namespace ambid::sim {

class MaglevExtended : public Plant {
 public:
  // `point`: the record's operating point (x0 strictly between the stops, i0 > 0), `measured`
  // whether it was measured. `sample_time` is needed by sensor_delay. Error for an effect not
  // in the catalogue or given twice, parameters the effects make invalid (e.g. R + dR <= 0),
  // a sensor whose reading x0 no gap between the stops gives, a bad sample time or command
  // resolution. `command_resolution`: the step at which the record logs u (0: exact).
  MaglevExtended(const MaglevParameters& nominal, const MaglevOperatingPoint& point, bool measured,
                 const std::vector<Effect>& effects, double sample_time, double command_resolution = 0.0);

  // The parameters after the effects (Km, Ke anchored as above, exponents with force_law).
  const MaglevParameters& parameters() const { return p_; }
  double operating_gap() const { return gap0_; }  // the true gap at the operating point

  std::string model() const override;  // "maglev1coil_voltage"
  std::vector<std::string> state_names() const override;
  std::vector<std::string> input_names() const override;        // u
  std::vector<std::string> output_names() const override;       // x, i
  std::vector<std::string> disturbance_names() const override;  // Fz

  Eigen::VectorXd derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                             const Eigen::VectorXd& w) const override;
  Eigen::VectorXd output(const Eigen::VectorXd& x) const override;
  // One shift of the delay line, then RK4 with at least `substeps` steps and steps of at most
  // 0.2 L/R (the coil's pole lies within a sample at the rig's rates). A body that reaches a
  // stop (x_min, x_max) rests on it, its speed into the stop lost, until the forces pull it off
  // (the rig's magnet against the top or on the ground): a candidate whose replay goes there is a
  // bad fit, not a failed one (at 4 ms the nominal replay of a force_law record touched the top
  // stop in the rig's ringing after a step the record itself survived). Error when the sample
  // time differs from the constructor's while a sensor delay is active.
  void advance(Eigen::VectorXd& x, const Eigen::VectorXd& u, const Eigen::VectorXd& w, double sample_time,
               int substeps) const override;

  // The coil's current `dt` after `current` with `command` held (through the DAC), the body at
  // rest (no back-EMF): current a + (1 - a) kw u_dac / R, a = exp(-R dt / L). The audit's
  // one-step check of the coil (diagnostics/audit/maglev_coil_equation.hpp).
  double coil_current_after(double current, double command, double dt) const;

  // At rest at operating_gap() with the current that holds it; the delay line full of x0.
  Eigen::VectorXd equilibrium_state() const override;
  Eigen::VectorXd equilibrium_input() const override;

 private:
  using Continuous = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 5, 1>;
  Continuous continuous_derivative(const Continuous& s, double u, double Fz) const;
  double sensed(double gap) const;  // before the delay

  MaglevParameters p_;
  double x0_ = 0.0, gap0_ = 0.0, current0_ = 0.0, sample_time_ = 0.0;
  double sensor_scale_ = 1.0, sensor_offset_ = 0.0, sensor_power_ = 1.0, dac_step_ = 0.0;
  double command_resolution_ = 0.0;
  double min_current_ = 0.0;  // floor of |i| in i^(n_i - 1) of the back-EMF
  int harmonic_state_ = -1, delay_state_ = -1, delay_whole_ = 0, delay_length_ = 0, continuous_states_ = 3;
  double harmonic_omega_ = 0.0, harmonic_cos_ = 0.0, harmonic_sin_ = 0.0, delay_fraction_ = 0.0;
};

}  // namespace ambid::sim
