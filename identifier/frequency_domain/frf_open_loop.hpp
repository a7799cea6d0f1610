#pragma once
// The open-loop plant from closed-loop responses with a known controller (seed 003 eq. 9-11)
// and the controller-consistency check of a measurement (seed 003 eq. 5), in the experiment
// contract's sign u = K y + d (d the disturbance at the plant input; the paper's negative
// feedback K' is -K here).
//
//   closed loop from d to y:  T = (I - G K)^-1 G = G (I - K G)^-1
//   eq. 11:                   G = T (I + K T)^-1             (K inputs x outputs)
//   eq. 5:                    K = G^-1 - T^-1                 (the paper: K' = (G - T)/(T G))
// With the excitation r entering as u = K y + M r (frf_loop.hpp), T = T_yr M^+.
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "identifier/frequency_domain/frf_loop.hpp"
#include "identifier/frf_types.hpp"

namespace ambid::ident {

// Eq. 11 at one frequency. Throws InsufficientData when I + K T is singular there.
Eigen::MatrixXcd open_loop_from_closed_loop(const Eigen::MatrixXcd& closed_loop, const Eigen::MatrixXcd& K);

// Eq. 11 over an FRF from the references to the outputs (T_yr, outputs x references), with
// the recorded controller evaluated at every line. The variance, when T_yr has one, is
// propagated to first order, dG = (I - G K) dT (I + K T)^-1, treating the errors of the
// elements of T as uncorrelated.
Frf open_loop_from_closed_loop(const Frf& output_from_reference, const StateSpaceController& controller,
                               const LoopSignalNames& signals);

// Eq. 5 at one frequency: the controller consistent with the open-loop G and the closed-loop
// T (from d to y). Square G only (Error otherwise); InsufficientData when G or T is singular.
Eigen::MatrixXcd controller_from_responses(const Eigen::MatrixXcd& G, const Eigen::MatrixXcd& closed_loop);

// Eq. 5 over measured responses. For a non-square plant K is not determined by G and T (only
// K G is), so the comparison is made on the loop gain at the plant input:
//   measured  L = I - (G^+ T)^-1   (from T = G (I - K G)^-1),   known  L = K G,
// which for a square plant is the same test as comparing K.
struct ControllerCheck {
  Eigen::VectorXd frequency_hz;
  std::vector<Eigen::MatrixXcd> measured;  // K from G and T (square plants; else empty)
  std::vector<Eigen::MatrixXcd> known;     // K of the recorded controller
  std::vector<Eigen::MatrixXcd> loop_gain_measured, loop_gain_known;
  Eigen::VectorXd relative_error;  // sigma_max(L_meas - L_known) / sigma_max(L_known)
};
ControllerCheck check_controller(const Frf& plant, const Frf& output_from_reference,
                                 const StateSpaceController& controller, const LoopSignalNames& signals);

}  // namespace ambid::ident
