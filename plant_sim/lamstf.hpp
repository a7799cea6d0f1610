#pragma once
// The LAMSTF 5-DOF magnetic suspension of seed 002 (Lee 1995) ch. 3, eq. (3.1)-(3.2): the
// linearised analytical model with the gravity bias removed (shared/notes/seed-002-lee.md 5.2).
//   x' = [0 I; A21 0] x + [0; B2] u,  y = [C1 0] x
// States pitch, yaw, x, y, z (rotations in rad, translations in m) and their rates; inputs
// the five coil currents i1..i5; outputs the five photodetector voltages s1..s5.
// Open-loop eigenvalues (Table 3.1): +-58.78, +-j7.97, +-57.81, +-j0.96, +-9.78.
//
// Plant family `lamstf` (experiment-format.md, "Plant families"; families.hpp): model name
// "lamstf", signals y: s1..s5 (V), u: i1..i5 (A), operating point all zero (deviations).
// Parameters: none; the sidecar's plant.parameters is empty, since the model is the fixed
// matrices below. Its closed loop is lamstf_scenario.hpp.
#include "plant_sim/linear_plant.hpp"

namespace ambid::sim {

NamedSystem lamstf();  // model name "lamstf"

}  // namespace ambid::sim
