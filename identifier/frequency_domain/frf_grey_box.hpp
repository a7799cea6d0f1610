#pragma once
// Grey-box fit of a structured continuous model to a measured MIMO FRF: the physical
// parameters theta of a model structure G(s; theta) = C (sI - A)^-1 B + D, (A, B, C, D) built by
// the caller from theta (e.g. v1..v9 of amb1dof_voltage, seed 000 eq. 4), are adjusted by Ceres
// (Levenberg-Marquardt, numeric derivatives) to
//   minimise sum_lines sum_(i,j) |w_ij,k (G_model,ij(w_k) - G_ij,k)|^2.
// With sample_time > 0 the model is compared as its exact zero-order-hold equivalent at
// e^{j w T} (data from sampled u and y), so no hold approximation enters.
// Weights: 1/sigma with the FRF's variance when it has one, else 1/rms_k |G_ij,k| per element
// (every element counts alike whatever its units).
#include <functional>
#include <string>

#include <Eigen/Core>

#include "core/state_space.hpp"
#include "identifier/frf_types.hpp"

namespace ambid::ident {

struct GreyBoxOptions {
  double sample_time = 0.0;  // > 0: compare the ZOH equivalent (exact for sampled data)
  bool use_variance = true;  // noise weights when the FRF has variances
  int max_iterations = 200;
};

struct GreyBoxFit {
  Eigen::VectorXd parameters;
  Eigen::MatrixXd covariance;  // from the Jacobian at the solution (QR); scaled by the residual
                               // variance unless noise weights were used; empty if singular
  Eigen::VectorXd standard_deviation;
  double misfit = 0.0;  // mean |w e|^2 over lines and elements
  bool converged = false;
  int iterations = 0;
};

// `model` maps parameters to a continuous system with the FRF's outputs and inputs; it may throw
// Error for parameters outside its domain (the step is then rejected). Initial parameters must
// be non-zero (they set the scale of each parameter). Throws Error for inconsistent sizes or
// lines above the Nyquist frequency, InsufficientData for an element without response (or with
// zero variance). Parameters the lines do not determine leave `covariance` empty.
GreyBoxFit fit_grey_box(const Frf& frf, const std::function<ContinuousSystem(const Eigen::VectorXd&)>& model,
                        const Eigen::VectorXd& initial, const GreyBoxOptions& options = {});

}  // namespace ambid::ident
