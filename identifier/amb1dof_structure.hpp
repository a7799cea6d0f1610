#pragma once
// The model structure of `amb1dof_voltage` (seed 000 eq. 4) and its physical coordinates:
//   states x, x', i1, i2; outputs y = [x, i1, i2]; inputs u1, u2;
//   Ac = [ 0 1 0 0; v1 0 v2 -v3; 0 -v4 -v5 0; 0 v6 0 -v7 ],  Bc = [0 0; 0 0; v8 0; 0 v9]
// Physical quantities (with the nominal L1, L2, m the data cannot separate):
//   ks = v1 m, kr1 = v2 m, kr2 = v3 m, kr1_emf = v4 L1, R1 = v5 L1, kr2_emf = v6 L2,
//   R2 = v7 L2, kw1 = v8 L1, kw2 = v9 L2.
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "core/state_space.hpp"

namespace ambid::ident {

// "v1".."v9", and the physical quantity each one scales to (same order).
const std::vector<std::string>& amb1dof_structure_names();
const std::vector<std::string>& amb1dof_physical_names();

// v1..v9 read from a continuous model in physical coordinates (4 states, 2 inputs).
Eigen::Matrix<double, 9, 1> amb1dof_structure_vector(const ContinuousSystem& physical);
// Largest |entry| of Ac, Bc where eq. (4) has 0 (or Ac(0,1) - 1), relative to |v1|.
double amb1dof_structure_deviation(const ContinuousSystem& physical);
// The factor that turns v_i into its physical quantity: m, m, m, L1, L1, L2, L2, L1, L2.
Eigen::Matrix<double, 9, 1> amb1dof_physical_scale(double L1, double L2, double m);

// The quantities the data cannot separate, from the experiment's nominal plant parameters:
// L1 = Ls1 + K1/(2 x0), L2 = Ls2 + K2/(2 x0), m. Throws Error (prefixed with `who`) naming
// a missing parameter.
struct Amb1dofNominal {
  double L1 = 0.0, L2 = 0.0, m = 0.0;
};
Amb1dofNominal amb1dof_nominal(const Experiment& experiment, const std::string& who);
// v1..v9 of the nominal plant the experiment's sidecar describes (seed 000 eq. 4 at x = 0,
// i1 = i2 = i0): the model the controller was designed on, a start that needs no data. Throws
// Error (prefixed with `who`) naming a missing parameter.
Eigen::Matrix<double, 9, 1> amb1dof_nominal_structure(const Experiment& experiment, const std::string& who);

struct Amb1dofPhysicalModel {
  DiscreteSystem discrete;      // physical coordinates, C = [1 0 0 0; 0 0 1 0; 0 0 0 1]
  ContinuousSystem continuous;  // d2c_zoh of it
};

// Any 4-state realisation with outputs [x, i1, i2] (e.g. from ERA) in physical coordinates:
// with z the realisation state and Ac = logm(A)/T, the physical state is
//   [x; x'; i1; i2] = T z,  T = [C(0,:); C(0,:) Ac; C(1,:); C(2,:)]
// (x' is the derivative of the measured x). Throws Error for a realisation that is not
// 4 states x 2 inputs x 3 outputs, has D != 0, or whose T is singular (the outputs and the
// rate of x do not determine the state), and when d2c_zoh refuses A.
Amb1dofPhysicalModel amb1dof_physical_model(const DiscreteSystem& realization);
// The same transformation of a continuous-time system (e.g. a linearised plant) with outputs
// [x, i1, i2]: its states become x, x', i1, i2. Throws Error when they are not determined.
ContinuousSystem amb1dof_physical_coordinates(const ContinuousSystem& system);

}  // namespace ambid::ident
