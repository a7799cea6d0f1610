#pragma once
// Local polynomial transient removal (after Pintelon, Schoukens, Vandersteen, Barbe, "Estimation
// of nonparametric noise and FRF models for multivariable systems", MSSP 2010), for periodic
// data whose periods are not in steady state, e.g. the orthogonal (Hadamard) multi-channel
// multisine that flips channel signs from one period to the next: every period then starts
// with a free response of the loop, whose one-period DFT is a smooth (rational) function of
// frequency that leaks into every line. Around each line k, over a window of neighbouring
// excited lines k + r and the P period positions q of a block,
//   Z_q(k + r) = sum_{d<=D} G_d delta^d X_q(k + r) + sum_{d<=D} t_{q,d} delta^d,
// delta = r / (window half width), solved by least squares (QR); the FRF at k is G_0. The
// error is the polynomial approximation of the FRF and of the transient over the window:
// small where the loop's poles are several lines away from the unit circle, larger at sharp
// resonances.
#include <vector>

#include <Eigen/Core>

namespace ambid::ident {

struct LocalPolynomialOptions {
  int degree = 4;      // D (4: noise-free errors ~1e-8 at mid band, ~1e-3 at sharp features)
  int half_width = 0;  // lines on each side; 0: the smallest giving 1.5x as many equations as unknowns
  // Model the transient terms t_{q,d}. Without them (periods in steady state) the window can be
  // narrower, which lowers the interpolation error where lines are sparse next to sharp features.
  bool transient = true;
  // Degree of a common denominator 1 + sum a_d delta^d of the local model (0: polynomial).
  // A local rational model (after McKelvey and Guerin, "Non-parametric frequency response
  // estimation using a local rational model", SYSID 2012) follows a pole near the window that
  // no polynomial over the same lines can: closed-loop poles near DC under integral action.
  int denominator_degree = 0;
};

// X[q]: lines x regressors (references), Z[q]: lines x responses, one entry per period
// position q; `lines`: the DFT indices of the rows (increasing). Returns one (responses x
// regressors) matrix per line. Throws Error for inconsistent sizes and InsufficientData when
// there are too few lines for the window or a local problem is rank deficient.
std::vector<Eigen::MatrixXcd> local_polynomial_frf(const std::vector<Eigen::MatrixXcd>& X,
                                                   const std::vector<Eigen::MatrixXcd>& Z,
                                                   const std::vector<Eigen::Index>& lines,
                                                   const LocalPolynomialOptions& options = {});

}  // namespace ambid::ident
