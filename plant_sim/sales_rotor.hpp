#pragma once
// One axis of the rotor of seed 003 (Sales), eq. (8): the analytical model whose Bode plot
// matched the measurements.
//   A = [0 1; 2.8e3 0], B = [0; 4.2], C = [0.2e3 0], D = 0
// Unstable pole +sqrt(2800) = 52.9 rad/s (and its mirror -52.9).
#include "plant_sim/linear_plant.hpp"

namespace ambid::sim {

NamedSystem sales_rotor();  // model name "sales_rotor"; states x, x_dot; input u; output y

}  // namespace ambid::sim
