#pragma once
// Seed 000 identification of the `amb1dof_voltage` bearing axis from closed-loop data with
// its known observer/state-feedback/integral controller: the deadbeat physical realisation
// (deadbeat_realization.hpp), the continuous model by the inverse zero-order hold (eq. 8,
// core d2c_zoh), the structure parameters v1..v9 (eq. 4) and the physical quantities, each
// with its one-sigma uncertainty propagated from the least-squares covariance (first order,
// the Jacobian of the whole map A, B -> logm -> v by central differences).
//
// Plant states x, x', i1, i2; outputs y = [x, i1, i2] (C known); inputs u1, u2.
//   Ac = [ 0 1 0 0; v1 0 v2 -v3; 0 -v4 -v5 0; 0 v6 0 -v7 ],  Bc = [0 0; 0 0; v8 0; 0 v9]
// Physical (with the nominal L1, L2, m the data cannot separate; seed 000 notes):
//   R1 = v5 L1, R2 = v7 L2, kw1 = v8 L1, kw2 = v9 L2, kr1 = v2 m, kr2 = v3 m,
//   kr1_emf = v4 L1, kr2_emf = v6 L2, ks = v1 m   (ks = ks1 + ks2)
//
// The controller must have the form of plant_sim/observer_controller.hpp (contract form):
//   states [x_hat (4); s (integrators)], A = [A_o 0; 0 I], B = [B_o L; 0 -E],
//   C = [-F Fe], D = [0 -Fe E]   (inputs [u1, u2, y...], outputs [u1, u2]).
#include <map>
#include <string>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "core/state_space.hpp"
#include "identifier/time_domain/deadbeat_realization.hpp"

namespace ambid::ident {

struct Amb1dofIdentification {
  DeadbeatRealization realization;                      // discrete, physical coordinates
  ContinuousSystem continuous;                          // Ac, Bc, C, D
  std::map<std::string, double> parameters;             // v1..v9
  std::map<std::string, double> parameter_uncertainty;  // one sigma, same keys
  Eigen::MatrixXd parameter_covariance;                 // 9 x 9, v1..v9
  std::map<std::string, double> physical;               // R1 R2 kw1 kw2 kr1 kr2 kr1_emf kr2_emf ks
  std::map<std::string, double> physical_uncertainty;   // one sigma, same keys
  // Largest |entry| of Ac, Bc where the structure of eq. (4) has 0 (or Ac(0,1) - 1),
  // relative to |v1|: how far the data are from the model structure.
  double structure_deviation = 0.0;
};

// The controller's F, Fe, E and integrator count from a contract controller rearranged as
// known_controller() does (inputs [u; y], here u = [u1, u2], y = [x, i1, i2]). Throws Error
// when the controller does not have the form above.
struct ObserverIntegralGains {
  Eigen::MatrixXd F, Fe, E;
};
ObserverIntegralGains observer_integral_gains(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                              const Eigen::MatrixXd& C, const Eigen::MatrixXd& D,
                                              Eigen::Index plant_states, Eigen::Index plant_inputs);

// From matrices: y = [x, i1, i2], u = [u1, u2], uf = u - r (deviations, samples x channels),
// the gains of the controller and its integrator state at the first sample (empty: zero),
// the nominal L1, L2 [H] and m [kg].
Amb1dofIdentification identify_amb1dof_deadbeat(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u,
                                                const Eigen::MatrixXd& uf, const ObserverIntegralGains& gains,
                                                const Eigen::VectorXd& integrator_initial, double sample_time,
                                                double L1, double L2, double m, const DeadbeatOptions& options = {});

// From an experiment of plant model "amb1dof_voltage" with signals y {x, i1, i2}, u {u1, u2},
// r (one per controller output; absent means r = 0) and its controller (integrator state at
// the first sample from controller.initial_state when given). L1 = Ls1 + K1/(2 x0),
// L2 likewise and m come from the nominal plant parameters. Throws Error naming what is
// missing or inconsistent.
Amb1dofIdentification identify_amb1dof_deadbeat(const Experiment& experiment, const DeadbeatOptions& options = {});

}  // namespace ambid::ident
