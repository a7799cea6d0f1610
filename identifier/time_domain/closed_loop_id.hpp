#pragma once
// Closed-loop identification with a KNOWN controller (Lee 1995 ch. 2; Huang, Hsiao & Cox 1994):
//   1. ARX model of the closed loop from the excitation r to the output y   (2.11)
//   2. closed-loop system and Kalman Markov parameters Yc, Nc              (2.18), (2.19)
//   3. remove the known controller: open-loop Y, N                          (2.24), (2.25)
//   4. ERA on Y -> A, B, C (D = 0: the plant must be strictly proper)      (2.26), (2.27)
//   5. Kalman gain from N by least squares                                  (4.35)
//
// The controller is in the form of the experiment contract: it reads the plant inputs u and
// outputs y,  xc[k+1] = A xc + B [u; y],  uf = C xc + D [u; y],  u = uf + r  (deviations).
// Lee's controller (u = Yd * y + r) is the special case with zero u columns of B; step 3 uses
// the generalisation in markov.hpp (open_loop_markov). D must be zero in every u column.
//
// Assumptions: the plant is strictly proper; with noise, the finite ARX order is exact only
// when the closed-loop predictor is stable, which needs the controller's own loop dynamics
// A + B_u C stable (Lee: an open-loop-stable controller). Its spectral radius is reported.
// Nothing here stabilises the identified plant: an unstable plant comes out unstable.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "core/state_space.hpp"
#include "identifier/time_domain/arx.hpp"
#include "identifier/time_domain/era.hpp"
#include "identifier/time_domain/least_squares.hpp"
#include "identifier/time_domain/markov.hpp"

namespace ambid::ident {

// Inputs ordered [u (plant inputs); y (plant outputs)], outputs one per plant input.
struct KnownController {
  Eigen::MatrixXd A, B, C, D;
};

// The contract controller rearranged to [u_names..., y_names...] inputs and u_names outputs
// (plant inputs the controller does not drive get uf = 0; signals it does not read get zero
// columns). Throws Error for a controller input or output that is not among the names, and
// for direct feedthrough from a plant input (a non-zero D column of a u signal).
KnownController known_controller(const StateSpaceController& controller, const std::vector<std::string>& u_names,
                                 const std::vector<std::string>& y_names);

struct KnownControllerIdOptions {
  Eigen::Index arx_order = 0;      // q (>= 1)
  Eigen::Index markov_count = 30;  // J: open-loop Markov parameters Y_1..Y_J for ERA
  Eigen::Index kalman_count = 0;   // N_1..N_k for the Kalman gain; 0: smallest k with k p >= 2 n, at most J
  double sample_time = 0.0;        // of the data (> 0)
  EraOptions era;                  // order 0: the suggested order
  LeastSquaresOptions least_squares;
  std::vector<Eigen::Index> breaks;  // joints of records joined end to end (ArxOptions::breaks)
};

struct ClosedLoopIdResult {
  DiscreteSystem plant;            // A, B, C, D = 0 in ERA coordinates
  Eigen::MatrixXd predictor_gain;  // AK (innovation model x[k+1] = A x + B u + AK e)
  Eigen::MatrixXd filter_gain;     // K  (4.35); empty when A is singular
  Eigen::VectorXd hankel_singular_values;
  Eigen::Index suggested_order = 0;
  ArxModel arx;                             // closed loop, r -> y
  MarkovParameters closed_loop;             // Yc, Nc (0..J)
  MarkovParameters open_loop;               // Y, N (0..J)
  double controller_spectral_radius = 0.0;  // of A + B_u C
};

// r: samples x plant inputs (excitation added to the controller output), y: samples x
// outputs. Throws Error for inconsistent sizes or options, and InsufficientData when the data
// cannot support the model (too short, unexciting, rank deficient, ill-conditioned).
ClosedLoopIdResult identify_with_known_controller(const Eigen::MatrixXd& r, const Eigen::MatrixXd& y,
                                                  const KnownController& controller,
                                                  const KnownControllerIdOptions& options);

}  // namespace ambid::ident
