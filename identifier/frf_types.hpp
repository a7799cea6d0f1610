#pragma once
// Frequency-response data shared by the frequency-domain identifier (identifier/frf_*,
// sensitivity_*, iso_*, rational_fit_*, freq_*).
//
// Conventions used by every file of this family:
// - A frequency response is G(jw) = C (jw I - A)^-1 B + D for a continuous system and
//   G(e^{jwT}) = C (e^{jwT} I - A)^-1 B + D for a discrete one, so a lag is a NEGATIVE phase.
// - Spectra use the DFT X(k) = (2/N) sum_n x[n] e^{-j 2 pi k n / N}: the phasor of the line,
//   x[n] = a cos(2 pi k n / N + phi)  ->  X(k) = a e^{j phi}.
// - The loop is closed in the experiment contract's sign: u = K y + M r (deviations), i.e.
//   POSITIVE feedback through K (experiment-format.md: u = uf + r, uf = controller output).
//   Papers that write negative feedback u = d - K' y have K' = -K.
#include <vector>

#include <Eigen/Core>

namespace ambid::ident {

// One complex matrix (outputs x inputs) per frequency line, with the variance of each element
// where the estimator knows it.
struct Frf {
  Eigen::VectorXd frequency_hz;
  std::vector<Eigen::MatrixXcd> value;
  // E|estimate - truth|^2 of each element (same layout as value), or empty when unknown.
  std::vector<Eigen::MatrixXd> variance;
  // Real degrees of freedom of the variance estimate (sample variance over B complex blocks:
  // 2 (B - 1)); 0 when the variance is exact or asymptotic (large-sample).
  double variance_dof = 0.0;

  Eigen::Index lines() const { return frequency_hz.size(); }
  Eigen::Index rows() const { return value.empty() ? 0 : value.front().rows(); }
  Eigen::Index cols() const { return value.empty() ? 0 : value.front().cols(); }
  bool has_variance() const { return !variance.empty(); }

  // Element (i, j) across all lines. Throw Error for an index out of range.
  Eigen::VectorXcd element(Eigen::Index i, Eigen::Index j) const;
  Eigen::VectorXd element_variance(Eigen::Index i, Eigen::Index j) const;  // Error if none

  // Throws Error when sizes disagree, a matrix has another shape than the first, a frequency
  // is not positive and finite or not strictly increasing, or an entry is not finite.
  void validate() const;
};

// Squared-radius factor of a confidence disc for a circular complex estimate: with sigma2 the
// (estimated) variance E|G_hat - G|^2, the disc |G_hat - G|^2 <= factor * sigma2 holds with
// probability `confidence`. dof = 0: sigma2 exact, factor = -ln(1 - confidence) (chi-square,
// 2 dof); dof > 0: sigma2 a sample variance on `dof` real degrees of freedom, factor the F(2,
// dof) quantile (dof/2) ((1 - confidence)^(-2/dof) - 1). Error for confidence outside (0, 1) or
// dof < 0.
double confidence_radius_factor(double confidence, double dof);

}  // namespace ambid::ident
