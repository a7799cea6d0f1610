#pragma once
// Eigensystem Realization Algorithm (Juang & Pappa 1985; Lee 1995 eq. 2.26/2.27 = 4.33/4.34)
// and ERA with data correlations (ERA/DC, Juang, Cooper & Wright 1988).
//
// From Markov parameters Y_0 = D, Y_k = C A^(k-1) B (k >= 1), with r block rows and s block
// columns (p outputs, m inputs):
//   H(k) = [ Y_(1+k+i+j) ]_{i<r, j<s}                 (p r x m s)
//   H(0) = U S V',  keep n:  A = S_n^-1/2 U_n' H(1) V_n S_n^-1/2,
//                            B = S_n^1/2 V_n' E_m,  C = E_p' U_n S_n^1/2,  D = Y_0.
// ERA/DC replaces H(k) by the block correlation Hankel  [ R(k+i+j) ]_{i,j<=xi},
// R(k) = H(k) H(0)', realises A from it the same way, C from the first block row of its left
// factor, and B = P^+ H(0) E_m with P that factor's first block (the observability matrix).
// ERA/DC squares the dynamic range of the singular values: for strongly unstable sequences
// (e.g. LAMSTF at 100 Hz, growth 1.8^k) plain ERA is the better choice.
//
// Order selection: all singular values are returned; suggest_order() proposes the order at
// the largest gap (largest ratio of consecutive singular values, each floored at a small
// fraction of the largest so that numerically zero ones count as a large, finite gap). The
// caller may override it with EraOptions::order.
#include <vector>

#include <Eigen/Core>

#include "core/error.hpp"
#include "core/state_space.hpp"
#include "identifier/time_domain/markov.hpp"

namespace ambid::ident {

struct EraOptions {
  Eigen::Index order = 0;               // states of the realisation; 0: the suggested order
  Eigen::Index block_rows = 0;          // r; 0 with block_columns 0: Lee's rule (H(0) about square)
  Eigen::Index block_columns = 0;       // s
  bool data_correlation = false;        // ERA/DC
  Eigen::Index correlation_blocks = 2;  // xi: ERA/DC uses (xi + 1) x (xi + 1) blocks of R
  // > 1: refuse (UndeterminedOrder) an order n whose singular value n is not min_gap times
  // singular value n + 1. Noise and truncation put a floor under the singular values; a state
  // whose singular value does not stand above it is not determined by the data, and its
  // eigenvalue lands anywhere (e.g. on the negative real axis, where no continuous model exists).
  double min_gap = 0.0;
};

// The refusal of EraOptions::min_gap: the data do not determine the requested order.
class UndeterminedOrder : public InsufficientData {
 public:
  using InsufficientData::InsufficientData;
};

struct EraResult {
  DiscreteSystem system;
  Eigen::VectorXd hankel_singular_values;       // all singular values of H(0), descending
  Eigen::VectorXd correlation_singular_values;  // ERA/DC: all of the correlation Hankel
  Eigen::Index suggested_order = 0;             // from the singular values the realisation used
  Eigen::Index order = 0;                       // the order realised
  Eigen::Index block_rows = 0, block_columns = 0;
};

// markov: Y_0 .. Y_J (all p x m). Default sizes: r + s = J (ERA) or J - 2 xi (ERA/DC) with
// p r ~ m s (Lee, Appendix B era.m). Throws Error for inconsistent sizes, too few Markov
// parameters for the requested blocks, or an order above min(p r, m s) or above the numerical
// rank of the Hankel matrix (a singular value at or below max(1e-13, size * epsilon) times the
// largest: InsufficientData), or without the gap options.min_gap above it (UndeterminedOrder).
EraResult era(const MarkovSequence& markov, double sample_time, const EraOptions& options = {});

// The order at the largest gap of descending singular values (>= 1): argmax of
// sigma_i / max(sigma_(i+1), zero_tolerance * sigma_1) over the non-zero sigma_i.
Eigen::Index suggest_order(const Eigen::VectorXd& singular_values, double zero_tolerance = 1e-13);

}  // namespace ambid::ident
