#pragma once
// Numerical linearisation of any Plant at its equilibrium by central differences.
#include <Eigen/Core>

#include "core/state_space.hpp"
#include "plant_sim/plant.hpp"

namespace ambid::sim {

// Typical magnitudes of the states and inputs. Variable j is perturbed by
// h_j = relative_step * max(|equilibrium_j|, scale_j); an empty scale vector means scale 1.
// The default relative_step ~ eps^(1/3) balances truncation and round-off error of central
// differences for variables scaled to their natural size. Give the scales when a variable with
// zero equilibrium lives on a small range (amb1dof_voltage: x within the gap x0, see
// Amb1dofVoltage::state_scale()).
struct LinearizeOptions {
  Eigen::VectorXd state_scale;
  Eigen::VectorXd input_scale;
  double relative_step = 6e-6;
};

// A = df/dx, B = df/du at (equilibrium_state, equilibrium_input, w = 0), C = dh/dx, D = 0.
// Error on scale vectors of the wrong size or a non-positive scale or step.
ContinuousSystem linearize(const Plant& plant, const LinearizeOptions& options = {});

}  // namespace ambid::sim
