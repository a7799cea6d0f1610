#pragma once
// Parametric fit of a measured (SISO) frequency response to a continuous rational model
//   G(s) = N(s / w0) / D(s / w0),  N(x) = sum_{i<=m} b_i x^i,  D(x) = x^n + sum_{i<n} a_i x^i,
// with the frequency scale w0 (the largest fitted angular frequency) keeping the monomial
// basis well conditioned over the fitted band.
//
// 1. Sanathanan-Koerner iterations: minimise sum |w_k (N(x_k) - G_k D(x_k))|^2 / |D_prev(x_k)|^2,
//    linear in (b, a), by column-equilibrated QR of the stacked real and imaginary parts,
//    D_prev = 1 at the start, until a stops changing.
// 2. Refinement by Ceres (Levenberg-Marquardt, analytic Jacobian) of the true output error
//    sum |w_k (N/D(x_k) - G_k)|^2.
// Nothing constrains the poles: an open-loop-unstable plant keeps its right-half-plane poles.
//
// Weights w_k: 1/sigma_k with sigma_k^2 the variance of G_k (noise weighting; the misfit is then
// about 1 for a model that explains the data to the noise level), 1/|G_k| (relative), or 1.
//
// The data may be the response of the sampled plant (from sampled u to sampled y through a
// zero-order hold) and may contain a known pure delay; both are compensated before the fit,
// G_k <- G_k e^{j w tau} / h(w), h(w) = (1 - e^{-j w T}) / (j w T) (exact for the ZOH factor; the
// aliased terms of the sampled response are neglected, fine well below the Nyquist frequency).
#include <complex>
#include <string>

#include <Eigen/Core>

#include "core/state_space.hpp"

namespace ambid::ident {

struct RationalModel {
  Eigen::VectorXd numerator;     // b_0..b_m (coefficients of powers of s / w0)
  Eigen::VectorXd denominator;   // a_0..a_n with a_n = 1
  double frequency_scale = 1.0;  // w0, rad/s

  int numerator_degree() const { return static_cast<int>(numerator.size()) - 1; }
  int denominator_degree() const { return static_cast<int>(denominator.size()) - 1; }

  std::complex<double> evaluate(std::complex<double> s) const;  // s in rad/s
  std::complex<double> response(double omega) const { return evaluate({0.0, omega}); }
  Eigen::VectorXcd poles() const;  // rad/s, roots of D
  Eigen::VectorXcd zeros() const;  // rad/s, roots of N (none when m = 0)
  // k of G(s) = k prod(s - z_i) / prod(s - p_i).
  double gain() const;
  // Controllable canonical realisation (minimal unless N and D share a root). Error when
  // m > n (improper).
  ContinuousSystem realization() const;
};

enum class FitWeighting { automatic, noise, relative, uniform };  // automatic: noise if variances given

struct RationalFitOptions {
  int numerator_degree = 0;    // m >= 0
  int denominator_degree = 2;  // n >= 1, m <= n
  FitWeighting weighting = FitWeighting::automatic;
  double delay = 0.0;            // s, a known pure delay contained in the data
  double zoh_sample_time = 0.0;  // > 0: the data are a zero-order-hold sampled response
  int sk_iterations = 40;
  double sk_tolerance = 1e-12;  // relative change of the denominator that ends SK
  bool refine = true;           // Ceres output-error refinement
  int refine_iterations = 200;
};

struct RationalFit {
  RationalModel model;
  FitWeighting weighting = FitWeighting::uniform;  // as resolved
  double misfit = 0.0;                             // mean over lines of |w_k (G_model - G_k)|^2 (compensated data)
  Eigen::Index lines = 0;
  int parameters = 0;  // m + 1 + n
  int sk_iterations = 0;
  bool refined = false;  // Ceres ran and did not make the fit worse
  // Parameter covariance (b_0..b_m, a_0..a_{n-1}, scaled coefficients) from the Jacobian at
  // the solution (QR, no normal equations): absolute with noise weights, else scaled by the
  // residual variance. pole_std: sqrt(E|dp|^2) of each pole of model.poles() (rad/s),
  // first order; NaN where the covariance does not exist.
  Eigen::MatrixXd parameter_covariance;
  Eigen::VectorXd pole_std;
};

// frequency_hz > 0 increasing; response one complex value per line; variance empty or one
// entry per line (> 0; required for noise weighting). Throws Error for bad sizes or options
// and InsufficientData when there are fewer lines than parameters or the least-squares problem
// is rank deficient.
RationalFit fit_rational(const Eigen::VectorXd& frequency_hz, const Eigen::VectorXcd& response,
                         const Eigen::VectorXd& variance, const RationalFitOptions& options);

std::string to_string(FitWeighting weighting);

}  // namespace ambid::ident
