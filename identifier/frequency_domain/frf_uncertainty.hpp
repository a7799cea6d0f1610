#pragma once
// Unstructured uncertainty of a nominal model against a family of responses (seed 003, beam
// case: nine load cases against the reduced nominal G_N):
//   additive        |Delta_A(jw)| = |G(jw) - G_N(jw)|
//   multiplicative  |Delta_M(jw)| = |(G(jw) - G_N(jw)) / G_N(jw)|
// For MIMO responses the magnitudes are largest singular values, the multiplicative one of the
// output form G = (I + Delta_M) G_N: Delta_M = (G - G_N) G_N^+.
// The envelope is the largest value over the cases at each line (the paper's "superior
// contour").
#include <vector>

#include <Eigen/Core>

#include "identifier/frf_types.hpp"

namespace ambid::ident {

struct UncertaintyEnvelope {
  Eigen::VectorXd frequency_hz;
  Eigen::MatrixXd additive;           // lines x cases
  Eigen::MatrixXd multiplicative;     // lines x cases
  Eigen::VectorXd additive_envelope;  // max over cases
  Eigen::VectorXd multiplicative_envelope;
};

// Every case must be on the nominal's lines with its shape (Error otherwise); at least one
// case. InsufficientData when the nominal is zero at a line (no multiplicative uncertainty).
UncertaintyEnvelope uncertainty_envelope(const std::vector<Frf>& cases, const Frf& nominal);

}  // namespace ambid::ident
