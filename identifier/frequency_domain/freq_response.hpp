#pragma once
// Frequency responses of state-space models: continuous C (jw I - A)^-1 B + D, discrete
// C (e^{jwT} I - A)^-1 B + D (z on the unit circle), and the contract controller
// (experiment-format.md: xc[k+1] = A xc + B v, uf = C xc + D v, from v to uf). w in rad/s.
#include <Eigen/Core>

#include "core/experiment.hpp"
#include "core/state_space.hpp"
#include "identifier/frf_types.hpp"

namespace ambid::ident {

// Throw Error when the system is invalid, w is not finite, or jw (e^{jwT}) is (numerically)
// an eigenvalue of A (the response is infinite there), naming the frequency.
Eigen::MatrixXcd freq_response(const ContinuousSystem& sys, double omega);
Eigen::MatrixXcd freq_response(const DiscreteSystem& sys, double omega);
Eigen::MatrixXcd freq_response(const StateSpaceController& controller, double omega);

// The same on a grid of frequencies in Hz (variance empty).
Frf freq_response(const ContinuousSystem& sys, const Eigen::VectorXd& frequency_hz);
Frf freq_response(const DiscreteSystem& sys, const Eigen::VectorXd& frequency_hz);

}  // namespace ambid::ident
