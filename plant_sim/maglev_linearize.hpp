#pragma once
// Linearisation of `maglev1coil_voltage` (states x, x_dot, i; input u; outputs x, i; deviations)
// at an operating point, analytic:
//   dx''  = (n_x g / x0) dx - (n_i g / i0) di + dFz / m
//   di'   = (kw du - R di + n_i Ke' i0^(n_i-1) / x0^n_x dx') / L
// The mechanical row uses gravity balance at (x0, i0), Km' i0^n_i / x0^n_x = m g, so it needs
// neither Km nor m. At the model's own equilibrium Km' = Km; at a *measured* operating point
// (experiment-format.md, operating_point_source "measured") Km' is the force constant that
// balance closes there, and the back-EMF constant is scaled alike (Ke' = Ke Km'/Km: both come
// from the same flux). How far the nominal model's own equilibrium at x0 is from the measured
// point is reported, not refused.
#include "core/state_space.hpp"
#include "plant_sim/maglev_parameters.hpp"

namespace ambid::sim {

struct MaglevOperatingPoint {
  double x = 0.0;  // gap, m
  double i = 0.0;  // coil current, A
  double u = 0.0;  // commanded voltage, V
};

struct MaglevLinearization {
  ContinuousSystem system;
  Eigen::MatrixXd disturbance;  // d(state')/dFz = [0, 1/m, 0]^T
  MaglevOperatingPoint point;
  double Km = 0.0, Ke = 0.0;   // the constants the linearisation used (closed by gravity balance)
  double stiffness = 0.0;      // n_x g / x0 [1/s^2]
  double current_gain = 0.0;   // n_i g / i0 [m/(s^2 A)]
  double unstable_pole = 0.0;  // sqrt(n_x g / x0): the mechanical pole with the current held [rad/s]
  // The nominal model's own equilibrium at x0 (current, command) and the measured point's
  // ratio to it (1 at the model's own equilibrium).
  double nominal_current = 0.0, nominal_input = 0.0;
  double current_ratio = 1.0, input_ratio = 1.0;
};

// At the model's own equilibrium at `gap`. Error for a gap outside the stops.
MaglevLinearization maglev_linearize(const MaglevParameters& parameters, double gap);

// At a measured operating point (x0 strictly between the stops, i0 > 0, u0 finite), with the
// force constant closed by gravity balance there. Error naming the bad value.
MaglevLinearization maglev_linearize_measured(const MaglevParameters& parameters, const MaglevOperatingPoint& point);

}  // namespace ambid::sim
