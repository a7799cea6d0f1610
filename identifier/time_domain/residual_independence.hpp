#pragma once
// Whether a model's one-step prediction errors are what a right model leaves: white and
// independent of the past excitation (Ljung, System Identification, 2nd ed., sec. 16.6). A
// fit in a wrong local minimum, or with a wrong structure, leaves errors that the past r and
// the errors' own past still predict.
//
// For each residual e_j (mean removed) and lag k = 1..lags:
//   z = sqrt(N - k) * corr(e_j[t], s[t - k]),   s = e_j itself or each excitation r_i (mean removed).
// When e_j is white and independent of r each z is approximately N(0, 1), however coloured r
// is (the variance of sum e[t] s[t-k] is sigma_e^2 sum s^2 for white e). The check reports the
// largest |z| and where it is, with the past r and with the residuals' own past apart:
// - with r: a wrong plant model leaves the excitation's effect in the errors. A model error
//   even in the input's square (the bearing's force ~ i^2 nonlinearity) does not correlate
//   with a symmetric excitation (its third moments vanish), so a right linear model of a
//   nonlinear plant passes on noise-free data too;
// - with itself: a wrong noise model, or any model-structure error, the nonlinearity included
//   (noise-free records of the amb1dof bearing at 1 V: z 100-140 at lags 1-2).
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ambid::ident {

struct ResidualIndependence {
  double z = 0.0;               // largest |z| with the past r over every residual and lag
  double correlation = 0.0;     // its correlation coefficient (z / sqrt(N - k))
  std::string worst;            // where: "e_x with r1 at lag 3"
  double whiteness_z = 0.0;     // largest |z| with the residual's own past
  std::string whiteness_worst;  // where: "e_i1 with itself at lag 1"
  Eigen::Index lags = 0;
  Eigen::Index correlations = 0;  // how many z were tested, both kinds (each kind the maximum of that many N(0, 1))
};

// e: samples x p residuals named `e_names`, r: samples x m excitations named `r_names`. Throws
// Error for mismatched sizes or names, lags < 1, fewer than 2 lags' worth of samples
// (N <= 2 lags), or a non-finite sample. A residual or excitation that is constant
// gives no correlation (skipped).
ResidualIndependence residual_independence(const Eigen::MatrixXd& e, const std::vector<std::string>& e_names,
                                           const Eigen::MatrixXd& r, const std::vector<std::string>& r_names,
                                           Eigen::Index lags);

}  // namespace ambid::ident
