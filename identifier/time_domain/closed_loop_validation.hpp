#pragma once
// Validation of an identified plant on data the fit did not see (experiment-format.md,
// `nrmse`): the model is simulated in closed loop with the recorded controller, driven by
// the recorded excitation, and compared with the recorded outputs,
//   nrmse_j = ||y_j - y_model_j|| / ||y_j - mean(y_j)||.
// The controller state at the first sample is known (the controller replayed on the recorded
// signals); the plant's is not, so it is fitted by least squares together with a constant
// term of every state equation (2 n numbers against samples x outputs residuals: they remove
// the start transient and the operating-point shift of a plant off nominal, which settles at
// other bias currents and has no term in the linear model; not the model error).
#include <vector>

#include <Eigen/Core>

#include "core/state_space.hpp"
#include "identifier/time_domain/closed_loop_id.hpp"

namespace ambid::ident {

// The controller's state after each sample: row k is xc[k+1] of xc[k+1] = A xc + B [u; y]
// from xc[0] = initial (zero when empty). u, y: deviations, samples x channels.
Eigen::MatrixXd replay_controller(const KnownController& controller, const Eigen::MatrixXd& u, const Eigen::MatrixXd& y,
                                  const Eigen::VectorXd& initial);

// Closed-loop outputs of `plant` (D must be 0: no algebraic loop) with `controller` from plant
// state x0 and controller state xc0, driven by r (samples x plant inputs) and a constant term
// g of the plant's state equation, x[k+1] = A x + B u + g (empty: zero).
Eigen::MatrixXd simulate_closed_loop(const DiscreteSystem& plant, const KnownController& controller,
                                     const Eigen::MatrixXd& r, const Eigen::VectorXd& x0, const Eigen::VectorXd& xc0,
                                     const Eigen::VectorXd& constant = {});

// nrmse per output over the record, with x0 fitted as above. Samples k with left_out[k]
// (a controller clamp acted: not exogenous; empty: none) count neither in the fit of x0 nor
// in the norms. Throws Error for inconsistent sizes or D != 0, InsufficientData for an output
// without variation (nrmse undefined) or fewer than two samples scored; returns non-finite
// entries when the controller does not stabilise the model.
Eigen::VectorXd closed_loop_nrmse(const DiscreteSystem& plant, const KnownController& controller,
                                  const Eigen::MatrixXd& r, const Eigen::MatrixXd& y, const Eigen::VectorXd& xc0,
                                  const std::vector<bool>& left_out = {});

}  // namespace ambid::ident
