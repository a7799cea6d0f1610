#pragma once
// Closed-loop identification with UNKNOWN feedback by projection filters (Lee 1995 ch. 4).
//
// Data: plant input u = r + uf, plant output y, and the feedback signal uf (the controller's
// output; the controller itself need not be known). Steps:
//   1. output ARX   y[k]  = sum a_i y[k-i] + sum_{i>=0} b_i u[k-i]   (4.20; b_0 = D optional)
//      feedback ARX uf[k] = sum c_i y[k-i] + sum_{i>=1} d_i u[k-i]   (4.21; no u[k] term)
//   2. plant Markov Y_k = C A^(k-1) B (4.25), Kalman N_k = C A^(k-1) AK (4.30),
//      feedback Markov -F A^(k-1) B (4.26) and -F A^(k-1) AK (4.31)   (markov.hpp)
//   3. ERA on Y (Lee's case 4; the default), or on the combined sequence
//      [C; -F] A^(k-1) [B, AK] (case 1), giving A, B, C (+ AK, F)
//   4. K by least squares (4.35) and F by least squares from -F [B AB ...] = [Z_1 Z_2 ...].
// Lee's derivation assumes full-state feedback uf = -F x; for a dynamic controller F is only
// the best static fit. The method needs A invertible (a sampled continuous plant).
// Nothing here stabilises the identified plant: an unstable plant comes out unstable.
#include <Eigen/Core>

#include "core/state_space.hpp"
#include "identifier/time_domain/arx.hpp"
#include "identifier/time_domain/era.hpp"
#include "identifier/time_domain/least_squares.hpp"
#include "identifier/time_domain/markov.hpp"

namespace ambid::ident {

struct ProjectionFilterOptions {
  Eigen::Index arx_order = 0;         // q (>= 1)
  Eigen::Index markov_count = 25;     // J: Y_1..Y_J enter ERA (Lee: 25 in simulation, 60 on the rig)
  Eigen::Index gain_count = 0;        // Markov blocks for K and F; 0: smallest k with k min(p, m) >= 2 n, at most J
  bool estimate_feedthrough = false;  // estimate D = b_0 (Lee's "identify D"); false: D = 0
  bool combined_realisation = false;  // ERA on [C; -F] A^(k-1) [B, AK] (Lee's case 1)
  double sample_time = 0.0;
  EraOptions era;
  LeastSquaresOptions least_squares;
  std::vector<Eigen::Index> breaks;  // joints of records joined end to end (ArxOptions::breaks)
};

struct ProjectionFilterResult {
  DiscreteSystem plant;            // A, B, C, D in ERA coordinates
  Eigen::MatrixXd predictor_gain;  // AK
  Eigen::MatrixXd filter_gain;     // K; empty when A is singular
  Eigen::MatrixXd feedback_gain;   // F of uf = -F x (same coordinates)
  Eigen::VectorXd hankel_singular_values;
  Eigen::Index suggested_order = 0;
  ArxModel output_arx, feedback_arx;
  MarkovParameters plant_markov;     // Y_k = C A^(k-1) B (Y_0 = D), N_k = C A^(k-1) AK
  MarkovParameters feedback_markov;  // -F A^(k-1) B, -F A^(k-1) AK
};

// y: samples x outputs, u: samples x inputs (total plant input), uf: samples x inputs.
// Throws Error for inconsistent sizes or options, InsufficientData when the data cannot
// support the model (too short, unexciting, rank deficient, ill-conditioned).
ProjectionFilterResult identify_projection_filter(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u,
                                                  const Eigen::MatrixXd& uf, const ProjectionFilterOptions& options);

}  // namespace ambid::ident
