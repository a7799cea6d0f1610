#pragma once
// Levenberg-Marquardt for least squares whose Jacobian arrives in row blocks (long records):
// min over p of 1/2 ||r(p)||^2. Each iteration the problem streams the rows [J | -r] at p
// into a LeastSquaresAccumulator (block Householder QR, least_squares.hpp), so memory stays
// (parameters + 1)^2 however long the record is and J'J is never formed. From its factor
// [R z; 0 rho] (||r||^2 = ||z||^2 + rho^2) every step is
//   delta(lambda) = argmin ||R delta - z||^2 + lambda ||D delta||^2
// by a QR of [R z; sqrt(lambda) D 0], D the largest column norms of J seen (More 1978), and the
// damping lambda follows the ratio of the actual to the predicted decrease (Nielsen 1999).
//
// Converged: the Gauss-Newton step at p moves p by at most `step_tolerance` of its standard
// error, ||z|| <= step_tolerance * sigma with sigma^2 = ||r||^2 / rows (||z|| = ||R delta_GN||
// is the step's length in the metric of the parameter covariance sigma^2 (J'J)^-1). The test
// is scale free: it holds the same on noise-free data, where sigma is the model error.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "identifier/time_domain/least_squares.hpp"

namespace ambid::ident {

struct BlockLeastSquares {
  Eigen::Index parameters = 0;
  std::vector<std::string> names;  // one per parameter, for the rank messages (optional)
  // Adds the rows [J | -r] at p to `rows`; false when the residuals cannot be evaluated at p.
  // It may re-weight the residuals (e.g. by their rms at p); `cost` must then use the
  // weights of the last linearisation.
  std::function<bool(const Eigen::VectorXd& p, LeastSquaresAccumulator& rows)> linearise;
  // 1/2 ||r(p)||^2; +infinity when r cannot be evaluated at p.
  std::function<double(const Eigen::VectorXd& p)> cost;
};

struct LevenbergMarquardtOptions {
  int max_iterations = 50;       // linearisations after the first
  double step_tolerance = 1e-3;  // in standard errors of p (see above)
  double initial_damping = 1e-3;
  int max_trials = 30;  // rejected steps in a row before giving up
};

struct LevenbergMarquardtResult {
  Eigen::VectorXd p;  // the last point linearised (the rows below are at p)
  LeastSquaresAccumulator rows;
  int iterations = 0;  // accepted steps
  bool converged = false;
  std::string message;  // why it stopped
  double initial_cost = 0.0, final_cost = 0.0;
};

// Throws Error for a problem without parameters or functions, or a start of the wrong size;
// InsufficientData when the residuals cannot be evaluated at the start.
LevenbergMarquardtResult levenberg_marquardt(const BlockLeastSquares& problem, const Eigen::VectorXd& start,
                                             const LevenbergMarquardtOptions& options = {});

}  // namespace ambid::ident
