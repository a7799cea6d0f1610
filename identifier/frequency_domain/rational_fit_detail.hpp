#pragma once
// Internal to rational_fit_*.cpp: the fit data after compensation and weighting.
#include <complex>

#include <Eigen/Core>

#include "identifier/frequency_domain/rational_fit.hpp"

namespace ambid::ident::detail {

struct FitData {
  Eigen::VectorXcd x;  // j w_k / w0
  Eigen::VectorXcd g;  // compensated response
  Eigen::VectorXd w;   // weights
  double w0 = 1.0;
  FitWeighting weighting = FitWeighting::uniform;
};

FitData prepare_fit_data(const Eigen::VectorXd& frequency_hz, const Eigen::VectorXcd& response,
                         const Eigen::VectorXd& variance, const RationalFitOptions& options);

// Polynomial sum c_i x^i (ascending coefficients) and the monic denominator x^n + sum a_i x^i.
std::complex<double> polyval(const Eigen::VectorXd& c, std::complex<double> x);
std::complex<double> monic_polyval(const Eigen::VectorXd& a_low, std::complex<double> x);

// Mean over lines of |w (N/D - g)|^2 for a model with coefficients b, a (a without the monic
// leading 1) over all lines of `data`.
double weighted_misfit(const FitData& data, const Eigen::VectorXd& b, const Eigen::VectorXd& a_low);

// Sanathanan-Koerner: returns (b, a_low) and the number of iterations used.
struct Coefficients {
  Eigen::VectorXd b, a_low;
};
Coefficients sanathanan_koerner(const FitData& data, int m, int n, int iterations, double tolerance, int* used);

// Ceres output-error refinement in place; returns true when it ran and did not increase the
// misfit.
bool refine_output_error(const FitData& data, Coefficients& c, int iterations);

// Jacobian (2K x p) of the residual sqrt(2) w (N/D - g) (real and imaginary rows).
Eigen::MatrixXd output_error_jacobian(const FitData& data, const Coefficients& c);

}  // namespace ambid::ident::detail
