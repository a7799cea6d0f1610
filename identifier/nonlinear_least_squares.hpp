#pragma once
// Nonlinear least squares, min over x of 1/2 sum_i r_i(x)^2 within optional bounds, by Ceres'
// trust-region Levenberg-Marquardt with a dense QR, silent, one thread. The one place that sets
// up a Ceres problem (its .cpp is the only file that includes <ceres/ceres.h>); this header
// does not include Ceres.
#include <functional>
#include <string>

#include <Eigen/Core>

namespace ambid::ident {

// The residuals at x and, when `jacobian` is not null, d residuals / d x, row-major
// (residuals x parameters). Returns false when x cannot be evaluated (a diverging model, a
// refused value): the solver then takes a smaller step.
using ResidualFunction = std::function<bool(const double* x, double* residuals, double* jacobian)>;

enum class Differentiation {
  provided,  // the function fills `jacobian`
  central,   // Ceres' central differences of the residuals (relative step 1e-6); `jacobian` is always null
};

struct NonlinearLeastSquares {
  ResidualFunction residuals;
  int residual_count = 0;
  Differentiation differentiation = Differentiation::provided;
  Eigen::VectorXd lower, upper;  // bounds of x; empty: none
};

// The defaults are Ceres'.
struct NonlinearLeastSquaresOptions {
  int max_iterations = 50;
  double function_tolerance = 1e-6;
  double gradient_tolerance = 1e-10;
  double parameter_tolerance = 1e-8;
  int max_consecutive_invalid_steps = 5;  // steps to a point the function refuses, before failing
  bool jacobian = false;                  // also evaluate the residuals and Jacobian at the solution
};

enum class Termination {
  converged,        // a tolerance was met
  iteration_limit,  // max_iterations reached: the solution is usable
  failure,          // the solver failed: the solution is not usable
};

struct NonlinearLeastSquaresSolution {
  Eigen::VectorXd x;
  Termination termination = Termination::failure;
  std::string message;  // the solver's
  int iterations = 0;
  double initial_cost = 0.0, final_cost = 0.0;  // 1/2 sum r^2
  // With options.jacobian, at x (if the function evaluates there; else `evaluated` is false).
  bool evaluated = false;
  Eigen::VectorXd residuals;
  Eigen::MatrixXd jacobian;

  bool usable() const { return termination != Termination::failure; }
};

// From `start` (clamped into the bounds by the caller). Throws Error for sizes that do not agree.
NonlinearLeastSquaresSolution solve_nonlinear_least_squares(const NonlinearLeastSquares& problem,
                                                            const Eigen::VectorXd& start,
                                                            const NonlinearLeastSquaresOptions& options = {});

}  // namespace ambid::ident
