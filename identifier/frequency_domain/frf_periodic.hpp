#pragma once
// Non-parametric FRFs from closed-loop data with a periodic excitation (multisine, periodic
// PRBS): exact DFT of whole periods at the excited lines, transient periods discarded,
// averaged over blocks of periods, with the variance of every estimate from the spread across
// blocks.
//
// One block is `periods_per_block` (P) consecutive periods. For one reference P = 1 is usual.
// For several references (the orthogonal multi-channel pattern, e.g. channel j multiplied by
// H(j, p mod P) of a Hadamard matrix) every block holds P periods over which the reference
// phasors R (references x P) have full row rank; for each line and block
//   T_yr = Y R^+,  T_ur = U R^+   (Y outputs x P, U inputs x P; least squares by SVD),
// any P consecutive periods of a cyclic pattern will do. The plant is the indirect (joint
// input-output) estimate, unbiased under feedback:
//   G = T_yr T_ur^+   (= S_yr S_ur^-1; needs references >= inputs and T_ur of full rank).
// Its variance is the sample variance over blocks of the linearised error
// (T_yr,b - G T_ur,b) T_ur^+, divided by the number of blocks (variance of the average)
// (plant_from_period_means: of the per-period local model, below).
// The direct estimate G_dir = sum Y U^H (sum U U^H)^-1 over all periods treats u as if it were
// independent of the noise; under feedback with noise it is biased (towards 1/K).
//
// Transients inside the record: with one reference pattern repeated unchanged (P = 1) the loop
// is in steady state after the discarded transient periods and the line DFTs are exact. The
// orthogonal pattern changes the references from one period to the next, so every period
// starts with a free response of the loop whose DFT leaks into all lines (relative error about
// (closed-loop time constant / period) x sqrt(number of lines) — tens of percent for a dense
// multisine). For P > 1 the per-block responses are therefore estimated by the local
// polynomial method (frf_local_polynomial.hpp), which models that transient as a smooth
// function of frequency around each line (transient_model = automatic).
//
// Several references excited on different lines (zippered or interleaved grids, shifted
// PRBS), P = 1: no single line determines the MIMO response, but with transient_model =
// local_polynomial the references are separated through their different spectra on the
// neighbouring lines of the local window (each period is a block), which gives the full
// T_yr, T_ur and G at every line excited by any reference.
#include <vector>

#include <Eigen/Core>

#include "identifier/frequency_domain/frf_local_polynomial.hpp"
#include "identifier/frf_types.hpp"

namespace ambid::ident {

struct PeriodicFrfOptions {
  double sample_time = 0.0;
  Eigen::Index period_samples = 0;     // N
  std::vector<Eigen::Index> lines;     // excited DFT lines within one period, 0 < k < N/2
  Eigen::Index first_sample = 0;       // where the first period starts
  Eigen::Index transient_periods = 1;  // whole periods discarded after first_sample
  Eigen::Index periods_per_block = 1;  // P (the Hadamard order for the orthogonal pattern)
  enum class TransientModel { automatic, none, local_polynomial };
  TransientModel transient_model = TransientModel::automatic;  // automatic: local polynomial when P > 1
  LocalPolynomialOptions local_polynomial;
  // With the local model and P = 1: the plant from a local model of the period-mean outputs on
  // the period-mean inputs (G is interpolated across lines instead of T_yr and T_ur, whose
  // ratio is ill-conditioned where the loop suppresses an input direction). Its variance is
  // the period-to-period scatter, over the number of periods (2 (periods - 1) degrees of
  // freedom), of the same local model fitted to each period alone on the mean inputs, with the
  // period's input noise moved to its outputs to first order: Y_p - G (U_p - U_mean), and the
  // loop's transient, which telescopes in the mean, separated (frf_period_scatter.hpp; the
  // plain scatter when periods were left out).
  bool plant_from_period_means = false;
  // Per sample (rows of r, u, y): not exogenous (a controller clamp acted there). A block
  // holding one is left out, and so is the block after it (the loop's free response to the
  // clamp would leak into every line there). Empty: none.
  std::vector<bool> left_out;
};

struct PeriodicFrf {
  Frf plant;                  // G, outputs x inputs, indirect, with variance when blocks >= 2
  Frf plant_direct;           // open-loop formula, biased under feedback (no variance)
  Frf output_from_reference;  // T_yr, outputs x references, with variance
  Frf input_from_reference;   // T_ur, inputs x references, with variance
  // Variance of ONE period's phasor (noise level of the line) from the spread across blocks;
  // lines x signals; empty when blocks < 2.
  Eigen::MatrixXd output_noise_variance, input_noise_variance;
  Eigen::Index blocks = 0;
  Eigen::Index periods_used = 0;
  Eigen::Index blocks_left_out = 0;  // after the transient: holding a left-out sample, or right after one
};

// r, u, y: samples x signals, deviations. Throws Error for inconsistent sizes or options (a
// line outside (0, N/2) or repeated, P < references without the local polynomial
// transient model, non-positive sample time), and
// InsufficientData when fewer than one block remains after the transient (and the blocks left
// out), or when at some line
// the references of a block are not of full rank or T_ur is singular (names the line).
PeriodicFrf estimate_periodic_frf(const Eigen::MatrixXd& r, const Eigen::MatrixXd& u, const Eigen::MatrixXd& y,
                                  const PeriodicFrfOptions& options);

}  // namespace ambid::ident
