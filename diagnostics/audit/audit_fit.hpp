#pragma once
// Fits the parameters of one candidate effect so that the replayed model (audit_replay.hpp)
// matches the measured outputs on the estimation segment: nonlinear least squares (Ceres,
// Levenberg-Marquardt with dense QR, central-difference Jacobians) in units of each
// parameter's typical scale, within its physical range.
#include <functional>

#include "diagnostics/audit/audit_replay.hpp"
#include "plant_sim/effects.hpp"

namespace ambid::diag {

struct FitOptions {
  int max_iterations = 12;
};

struct EffectFit {
  sim::Effect effect;  // fitted parameters
  double cost = 0.0;   // sum over outputs of NRMSE^2 on the estimation segment
  int iterations = 0;
  bool converged = false;  // Ceres reported convergence (not the iteration limit)
};

// Sum over outputs of NRMSE^2 of the replay with `effects` on `estimation`; +inf when the
// model leaves its valid region (the candidate is then simply a bad one).
double estimation_cost(const Experiment& measured, const Eigen::MatrixXd& measured_y,
                       const std::vector<sim::Effect>& effects, const Segment& estimation);

// The least-squares core of fit_effect, for any replayed model with k parameters in units of
// their scale: `replay(theta)` gives the outputs (deviations) over at least estimation.end
// samples, or throws Error where the model cannot be simulated. Returns the fitted theta and
// the cost (sum over outputs of NRMSE^2 on `estimation`; +inf when even the start fails).
struct ScaledFit {
  Eigen::VectorXd theta;
  double cost = 0.0;
  int iterations = 0;
  bool converged = false;
};
ScaledFit fit_scaled(const Eigen::MatrixXd& measured_y, const Segment& estimation,
                     const std::function<Eigen::MatrixXd(const double* theta)>& replay, Eigen::VectorXd start,
                     const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, const FitOptions& options);

// Starts from `start` (an effect of the catalogue with initial values). `measured_y` is
// measured.y_deviation(). `base`: effects already accepted, held at their values while
// `start` is fitted on top of them. Error when the start itself cannot be simulated.
EffectFit fit_effect(const Experiment& measured, const Eigen::MatrixXd& measured_y, const sim::Effect& start,
                     const Segment& estimation, const FitOptions& options = {},
                     const std::vector<sim::Effect>& base = {});

}  // namespace ambid::diag
