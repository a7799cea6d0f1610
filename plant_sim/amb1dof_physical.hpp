#pragma once
// The structure parameters v1..v9 of seed 000 eq. (4) and the map between them and the
// physical quantities of `amb1dof_voltage`. Signs as in eq. (3), with A(3,3) = -R1/L1 (the
// paper prints +; a coil is a stable RL circuit):
//   A = [ 0    1    0    0 ;        B = [ 0   0 ;
//         v1   0    v2  -v3 ;             0   0 ;
//         0   -v4  -v5   0 ;              v8  0 ;
//         0    v6   0   -v7 ]             0   v9 ]      C = [e1; e3; e4]^T (x, i1, i2)
//   v1 = (ks1 + ks2)/m, v2 = kr1/m, v3 = kr2/m, v4 = kr1/L1, v5 = R1/L1, v6 = kr2/L2,
//   v7 = R2/L2, v8 = kw1/L1, v9 = kw2/L2,
// with ksj = Kj i0^2 / (2 x0^3) [N/m], krj = Kj i0 / (2 x0^2) [N/A = V s/m],
// Lj = Lsj + Kj / (2 x0) [H].
#include <map>
#include <string>

#include "core/state_space.hpp"
#include "plant_sim/amb1dof_parameters.hpp"

namespace ambid::sim {

// v1..v9 from the physical parameters (keys "v1".."v9").
std::map<std::string, double> amb1dof_structure_parameters(const Amb1dofParameters& p);

// The linear system of eq. (3)/(4) built from v1..v9 (Error naming a missing key).
ContinuousSystem amb1dof_structure_system(const std::map<std::string, double>& v);

// Reads v1..v9 back from a system in the physical coordinates of eq. (4) (4 states, 2 inputs,
// any C). Entries the structure fixes at zero or one are not checked here.
std::map<std::string, double> amb1dof_structure_parameters(const ContinuousSystem& sys);

// Physical quantities from v1..v9 given what the data cannot separate: the nominal coil
// inductances L1, L2 [H] and the rotor mass m [kg] (e.g. Amb1dofParameters::L1()).
//   R1 = v5 L1, R2 = v7 L2, kw1 = v8 L1, kw2 = v9 L2   (coil resistance, amplifier gain)
//   kr1 = v2 m, kr2 = v3 m                              (force factor from the mechanics)
//   kr1_emf = v4 L1, kr2_emf = v6 L2                    (the same factor seen as back-EMF)
//   ks = v1 m                                           (ks1 + ks2, total negative stiffness)
// Keys of to_map(): exactly these names. Error when L1, L2 or m is not positive and finite.
struct Amb1dofPhysical {
  double R1 = 0.0, R2 = 0.0, kw1 = 0.0, kw2 = 0.0, kr1 = 0.0, kr2 = 0.0;
  double kr1_emf = 0.0, kr2_emf = 0.0, ks = 0.0;
  std::map<std::string, double> to_map() const;
};
Amb1dofPhysical amb1dof_physical_from_structure(const std::map<std::string, double>& v, double L1, double L2, double m);
// Same, with L1, L2 and m taken from nominal parameters.
Amb1dofPhysical amb1dof_physical_from_structure(const std::map<std::string, double>& v,
                                                const Amb1dofParameters& nominal);

}  // namespace ambid::sim
