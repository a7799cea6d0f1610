#pragma once
// Transformations of an identified realisation to physical coordinates.
//
// Second-order form (Lee 1995 sec. 2.6, eq. 2.35-2.43): when half of the states are measured
// directly (p = n/2 outputs, y = C1 q with a known calibration C1 and q the positions), the
// continuous model  q'' = -M^-1 K q - M^-1 D q' + M^-1 G u  has the unique coordinates
//   x_phys = [q; q'],  P = [C; C Ac]^-1  (after C <- C1^-1 C),
//   P^-1 Ac P = [0 I; A21 A22],  P^-1 Bc = [B1; B2] (B1 = 0 for a strictly proper plant),
//   C P = [I 0].
// The discrete model is first converted by the exact inverse zero-order hold (core d2c_zoh,
// the matrix logarithm of seed 000 eq. 8; Lee's 2.37-2.39 diagonalise A for the same result).
//
// Measured-state coordinates (seed 000 eq. 15): when the true output matrix C is square and
// known, T = C^-1 Chat maps the realisation to the physical states.
#include <Eigen/Core>

#include "core/state_space.hpp"

namespace ambid::ident {

struct SecondOrderForm {
  ContinuousSystem system;         // P^-1 Ac P, P^-1 Bc, C1^-1 C P = [I 0], C1^-1 D
  Eigen::MatrixXd transformation;  // P: realisation state = P * physical state
  Eigen::MatrixXd stiffness;       // A21 = -M^-1 K  (n/2 x n/2)
  Eigen::MatrixXd damping;         // A22 = -M^-1 D
  Eigen::MatrixXd input;           // B2 = M^-1 G    (n/2 x inputs)
  double condition_number = 0.0;   // of [C; C Ac] (after calibration, 1-norm estimate)
};

// `output_calibration` C1 (p x p, invertible) maps the positions to the outputs, y = C1 q;
// empty means identity. Throws Error when n is not twice the number of outputs, C1 is not
// square p x p or singular, or [C; C Ac] is singular (the outputs and their rates do not
// determine the state).
SecondOrderForm second_order_form(const ContinuousSystem& sys, const Eigen::MatrixXd& output_calibration = {});
// d2c_zoh first (Error when A has an eigenvalue on the closed negative real axis).
SecondOrderForm second_order_form(const DiscreteSystem& sys, const Eigen::MatrixXd& output_calibration = {});

// Seed 000 eq. (13)/(15): with the true square output matrix `true_C` (n x n, invertible),
// T = true_C^-1 Chat and the physical realisation T Ahat T^-1, T Bhat, Chat T^-1 = true_C, D.
DiscreteSystem to_measured_coordinates(const DiscreteSystem& sys, const Eigen::MatrixXd& true_C);

}  // namespace ambid::ident
