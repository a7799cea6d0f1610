#pragma once
// Non-parametric FRFs from closed-loop data with a non-periodic excitation (random, PRBS not
// synchronised to the record, chirp): Welch-averaged cross spectra (periodic Hann window,
// overlapping segments) and coherence.
//
// With S_ab = sum_segments A B^H (A, B the windowed segment DFTs):
//   T_yr = S_yr S_rr^-1, T_ur = S_ur S_rr^-1,
//   G    = S_yr S_ur^+      indirect (joint input-output): unbiased under feedback,
//   G_dir = S_yu S_uu^-1    the open-loop formula: biased under feedback with noise (the
//                           noise is fed back into u; at frequencies where the noise dominates
//                           it tends to 1/K, K the feedback of u = K y + ...).
// Variance of G (large-sample, element-wise): var G_ij = S_vv,ii [S_ur^+H S_rr S_ur^+]_jj /
// M_eff, with S_vv the spectrum of v = y - G u (corrected for the fitted degrees of freedom)
// and M_eff the number of segments reduced for the correlation of overlapping windowed
// segments (Welch 1967). Coherence: multiple coherence of each output (input) with all
// references, gamma^2 = [S_yr S_rr^-1 S_ry]_ii / S_yy,ii.
#include <vector>

#include <Eigen/Core>

#include "identifier/frf_types.hpp"

namespace ambid::ident {

struct WelchFrfOptions {
  double sample_time = 0.0;
  Eigen::Index segment_samples = 0;  // L: window length; lines at k / (L T), 0 < k < L/2
  double overlap = 0.5;              // fraction of L shared by successive segments, [0, 1)
  Eigen::Index first_sample = 0;     // samples before it are discarded (transient)
  double f_min = 0.0;                // keep lines with f_min <= f <= f_max (0: up to Nyquist)
  double f_max = 0.0;
  // Per sample (rows of r, u, y): not exogenous (a controller clamp acted there); a segment
  // holding one is skipped. Empty: none.
  std::vector<bool> left_out;
};

struct WelchFrf {
  Frf plant;                          // G indirect, with asymptotic variance (variance_dof 0)
  Frf plant_direct;                   // G_dir, no variance
  Frf output_from_reference;          // T_yr
  Frf input_from_reference;           // T_ur
  Eigen::MatrixXd output_coherence;   // lines x outputs, in [0, 1]
  Eigen::MatrixXd input_coherence;    // lines x inputs
  Eigen::Index segments = 0;          // averaged
  Eigen::Index skipped_segments = 0;  // holding a sample left out (WelchFrfOptions::left_out)
  double effective_segments = 0.0;    // M_eff
};

// r, u, y: samples x signals, deviations. Throws Error for inconsistent sizes or options and
// InsufficientData when fewer segments than references + 1 fit (or remain after skipping), or at a line where S_rr or
// S_ur is singular (names the line).
WelchFrf estimate_welch_frf(const Eigen::MatrixXd& r, const Eigen::MatrixXd& u, const Eigen::MatrixXd& y,
                            const WelchFrfOptions& options);

}  // namespace ambid::ident
