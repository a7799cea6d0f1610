#pragma once
// The nonlinear `maglev1coil_voltage` plant (maglev_parameters.hpp has its equations): states
// x (gap, m, positive away from the coil), x_dot, i; input u (commanded coil voltage, V);
// outputs x, i; disturbance Fz (N, along +x). The stops are not part of the right-hand side:
// the rig loop (maglev_loop.hpp) ends a record when the body reaches one.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "plant_sim/maglev_parameters.hpp"
#include "plant_sim/plant.hpp"

namespace ambid::sim {

class Maglev1coilVoltage : public Plant {
 public:
  // Validates the parameters; `operating_gap` (strictly between the stops) is where
  // equilibrium_state() holds the body. Error naming the bad value.
  explicit Maglev1coilVoltage(const MaglevParameters& parameters = MaglevParameters::nominal(),
                              double operating_gap = 0.014);

  const MaglevParameters& parameters() const { return p_; }
  double operating_gap() const { return gap_; }

  std::string model() const override;                           // "maglev1coil_voltage"
  std::vector<std::string> state_names() const override;        // x, x_dot, i
  std::vector<std::string> input_names() const override;        // u
  std::vector<std::string> output_names() const override;       // x, i
  std::vector<std::string> disturbance_names() const override;  // Fz

  // Error for wrongly sized vectors and a gap that is not positive (the model is singular).
  Eigen::VectorXd derivative(const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                             const Eigen::VectorXd& w) const override;
  Eigen::VectorXd output(const Eigen::VectorXd& x) const override;

  // x = operating_gap, x_dot = 0, i = equilibrium_current(operating_gap); u = R i / kw.
  Eigen::VectorXd equilibrium_state() const override;
  Eigen::VectorXd equilibrium_input() const override;

 private:
  MaglevParameters p_;
  double gap_;
};

}  // namespace ambid::sim
