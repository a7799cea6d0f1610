#pragma once
// Markov parameters (impulse-response matrices) and the recursions between them:
//   - OKID: ARX (observer) coefficients -> system and observer-gain Markov parameters
//     (Lee 1995 eq. 2.18/2.19 and 4.25/4.30, which are the same recursion);
//   - secondary ARX models on the same regressors, e.g. the feedback signal (Lee 4.26/4.31);
//   - closed-loop -> open-loop with a known controller (Lee 2.24/2.25, the k = j term of 2.25
//     kept), and its generalisation to controllers that also read the plant input u;
//   - Markov parameters of a state-space system, and the error measure (Lee 4.36).
//
// Conventions: a Markov sequence is indexed from 0. For a system (A, B, C, D)
//   Y_0 = D, Y_k = C A^(k-1) B (k >= 1)         ("system" Markov parameters)
// and for an innovation / observer model x[k+1] = A x + B u + G e, y = C x + D u + e
//   N_0 = I, N_k = C A^(k-1) G (k >= 1)         ("gain" Markov parameters).
// For the steady-state Kalman predictor G = A K (Lee 2.3: the noise enters through AK).
#include <vector>

#include <Eigen/Core>

#include "core/state_space.hpp"
#include "identifier/time_domain/arx.hpp"

namespace ambid::ident {

using MarkovSequence = std::vector<Eigen::MatrixXd>;

struct MarkovParameters {
  MarkovSequence system;  // Y_0 .. Y_J
  MarkovSequence gain;    // N_0 .. N_J
};

// Y_0 = D, Y_k = C A^(k-1) B for k = 1..count (count + 1 matrices). D may be empty (zero).
MarkovSequence markov_parameters(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& C,
                                 const Eigen::MatrixXd& D, Eigen::Index count);
MarkovSequence markov_parameters(const DiscreteSystem& sys, Eigen::Index count);

// From an ARX model y[k] = sum a_i y[k-i] + sum_{i>=0} b_i u[k-i] (a_i for i = 1..q in a[i-1],
// b_i for i = 0..q in b[i]; missing terms are zero):
//   Y_0 = b_0,  Y_k = b_k + sum_{i=1..k} a_i Y_(k-i)       (Lee 2.18; with b_0 = D, 4.25)
//   N_0 = I,    N_k =       sum_{i=1..k} a_i N_(k-i)       (Lee 2.19; = 4.30)
// for k = 0..count. When the ARX model is the one-step predictor of an innovation model
// (A, B, C, D, G), Y_k and N_k are its Markov parameters as defined above. (OKID: the ARX
// coefficients [b_i, a_i] are the observer Markov parameters C Abar^(i-1) [B - G D, G],
// Abar = A - G C; the OKID observer-gain Markov parameters C A^(k-1) (-G) are -N_k.)
MarkovParameters markov_from_arx(const std::vector<Eigen::MatrixXd>& a, const std::vector<Eigen::MatrixXd>& b,
                                 Eigen::Index count);
MarkovParameters markov_from_arx(const ArxModel& arx, Eigen::Index count);

// From a secondary ARX model z[k] = sum c_i y[k-i] + sum_{i>=0} d_i u[k-i] on the same
// regressors as the primary model whose Markov parameters (Y, N) are given:
//   Z_0 = d_0,  Z_k = d_k + sum_{i=1..k} c_i Y_(k-i)       (Lee 4.26)
//   W_0 = 0,    W_k =       sum_{i=1..k} c_i N_(k-i)       (Lee 4.31)
// For z = -F x (full-state feedback) these are -F A^(k-1) B and -F A^(k-1) G.
// Needs primary sequences of length >= count + 1.
MarkovParameters secondary_markov_from_arx(const std::vector<Eigen::MatrixXd>& c, const std::vector<Eigen::MatrixXd>& d,
                                           const MarkovParameters& primary, Eigen::Index count);
MarkovParameters secondary_markov_from_arx(const ArxModel& arx, const MarkovParameters& primary, Eigen::Index count);

// Lee (2.24)/(2.25) as printed, for a controller u = Yd * y + r (Yd_0 = D_d, Yd_k =
// C_d A_d^(k-1) B_d):
//   alpha_k = sum_{i=1..k} Y_i Yd_(k-i)
//   Y_j = Yc_j - sum_{k=1..j} alpha_k Yc_(j-k)
//   N_j = Nc_j - sum_{k=1..j} alpha_k Nc_(j-k)      (the k = j term alpha_j Nc_0 = alpha_j kept)
// closed_loop: Yc_0..Yc_J (Yc_0 must be zero: strictly proper plant) and Nc_0..Nc_J;
// controller: Yd_0..Yd_J at least. Returns Y_0..Y_J (Y_0 = 0) and N_0..N_J (N_0 = I).
MarkovParameters lee_open_loop_markov(const MarkovParameters& closed_loop, const MarkovSequence& controller);

// The controller of the experiment contract reads [u; y]: uf = Gu * u + Gy * y, u = uf + r.
// Its Markov parameters split by input block; Gu_0 must be zero (no feedthrough from u).
struct ControllerMarkov {
  MarkovSequence from_u;  // Gu_0 .. Gu_J   (plant inputs x plant inputs)
  MarkovSequence from_y;  // Gy_0 .. Gy_J   (plant inputs x plant outputs)
};
// xc[k+1] = A xc + B [u; y], uf = C xc + D [u; y] with `plant_inputs` leading columns of B, D
// for u. Throws Error on inconsistent sizes or a non-zero u column of D.
ControllerMarkov controller_markov(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& C,
                                   const Eigen::MatrixXd& D, Eigen::Index plant_inputs, Eigen::Index count);

// Closed-loop (r -> y Markov Yc, noise Nc) -> open-loop (Y, N) for such a controller:
//   Uc  = (I - Gu)^-1 (I + Gy Yc)   (r -> u),    Unc = (I - Gu)^-1 Gy Nc   (e -> u)
//   Y_j = Yc_j - sum_{i=1..j-1} Y_i Uc_(j-i),    N_j = Nc_j - sum_{i=1..j} Y_i Unc_(j-i)
// (products are convolutions of Markov sequences). With Gu = 0 this is Lee (2.24)/(2.25).
MarkovParameters open_loop_markov(const MarkovParameters& closed_loop, const ControllerMarkov& controller);

// Lee (4.36) per index: ||Y_k - Yhat_k||_2 / ||Y_k||_2 * 100 % for k = first .. first+count-1
// (matrix 2-norm). Throws Error when a true Y_k is zero or a sequence is too short.
std::vector<double> markov_errors_percent(const MarkovSequence& truth, const MarkovSequence& estimate,
                                          Eigen::Index first, Eigen::Index count);

}  // namespace ambid::ident
