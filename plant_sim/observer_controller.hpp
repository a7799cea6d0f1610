#pragma once
// Seed 000 (Gosiewski & Paszowski) controller: discrete full-state feedback from a full-order
// prediction observer, with integral action on chosen outputs (eq. 17, 39-43), designed on the
// zero-order-hold model of a continuous plant by LQR (augmented model eq. 41) and the dual
// Riccati equation (observer gain), and written in the experiment contract's form.
//
// Paper:   xh[k+1] = A xh + B u[k] + L (y[k] - C xh)          (eq. 43, L = -G)
//          e[k+1]  = e[k] - E y[k+1]                           (eq. 39)
//          uf[k]   = -F xh[k] + Fe e[k]                        (eq. 42)
// Contract (v = [u; y] at sample k only): the integrator is kept one sample behind,
// s[k] = e[k-1], so e[k] = s[k] - E y[k] and
//   xc = [xh; s],  A_c = [A - L C, 0; 0, I],  B_c = [B, L; 0, -E],
//   C_c = [-F, Fe],  D_c = [0, -Fe E]   (D is zero in every u column).
// This reproduces the paper's law sample for sample.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "core/state_space.hpp"

namespace ambid::sim {

struct ObserverControllerOptions {
  std::vector<std::string> integral_outputs;  // outputs with zero steady-state error (rows of E)
  Eigen::MatrixXd Q;                          // LQR weight on the plant states (n x n)
  Eigen::MatrixXd Q_integral;                 // LQR weight on the integrator states (one per integral output)
  Eigen::MatrixXd R;                          // LQR weight on the plant inputs (m x m)
  Eigen::MatrixXd W;                          // observer design: process covariance (n x n)
  Eigen::MatrixXd V;                          // observer design: measurement covariance (q x q)
  // Observer speed: the observer poles are placed inside |z| < observer_pole_radius (the dual
  // DARE is solved for A / radius). 1 leaves them where W, V put them. In (0, 1].
  double observer_pole_radius = 1.0;
};

// Weights tuned for amb1dof_voltage (states x, x_dot, i1, i2; inputs u1, u2; outputs
// x, i1, i2) at its nominal parameters and sample time 1e-4 s, integral action on x. See the
// definition for the resulting closed-loop poles, damping and bandwidth.
ObserverControllerOptions amb1dof_observer_controller_options();

// Designs the controller on c2d_zoh(plant, sample_time). `input_names` and `output_names` name
// the plant's inputs and outputs (B columns, C rows). The result has inputs
// [input_names..., output_names...] (the observer uses the applied input u = uf + r), outputs
// input_names, and sample_time. Throws Error for inconsistent names or weights, an unknown
// integral output, or when a Riccati equation has no stabilising solution (names which).
StateSpaceController design_observer_controller(const ContinuousSystem& plant, double sample_time,
                                                const std::vector<std::string>& input_names,
                                                const std::vector<std::string>& output_names,
                                                const ObserverControllerOptions& options);

// The linear closed loop of a discrete plant (plant.D may be non-zero) and any contract
// controller whose inputs are among input_names and output_names and whose outputs are among
// input_names (inputs it does not drive get uf = 0):
//   states  [plant states; controller states]
//   inputs  r, one per plant input in input_names order (u = uf + r)
//   outputs [y; u]
// Throws Error for an unknown signal name, a sample-time mismatch, D non-zero in a u column,
// or a singular algebraic loop through plant.D.
DiscreteSystem linear_closed_loop(const DiscreteSystem& plant, const std::vector<std::string>& input_names,
                                  const std::vector<std::string>& output_names, const StateSpaceController& controller);

// max |eigenvalue of sys.A| (< 1: asymptotically stable).
double spectral_radius(const DiscreteSystem& sys);

}  // namespace ambid::sim
