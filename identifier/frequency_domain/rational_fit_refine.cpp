// Output-error refinement of a rational fit (nonlinear_least_squares.hpp), and the Jacobian for
// the covariance.
#include <cmath>
#include <vector>

#include "identifier/frequency_domain/rational_fit_detail.hpp"
#include "identifier/nonlinear_least_squares.hpp"

namespace ambid::ident::detail {
namespace {

// Residuals sqrt(2) w_k (N(x_k)/D(x_k) - g_k), real and imaginary parts, of the parameters
// [b; a_low], with the analytic Jacobian (row-major) d/db_i = sqrt(2) w x^i / D,
// d/da_i = -sqrt(2) w (N/D) x^i / D.
class OutputError {
 public:
  OutputError(const FitData& data, int nb, int na) : data_(data), nb_(nb), na_(na) {}

  int residual_count() const { return static_cast<int>(2 * data_.x.size()); }

  bool operator()(const double* parameters, double* residuals, double* jacobian) const {
    const Eigen::Map<const Eigen::VectorXd> b(parameters, nb_);
    const Eigen::Map<const Eigen::VectorXd> a(parameters + nb_, na_);
    const int columns = nb_ + na_;
    for (Eigen::Index k = 0; k < data_.x.size(); ++k) {
      const std::complex<double> x = data_.x(k);
      const std::complex<double> N = polyval(b, x), D = monic_polyval(a, x);
      const std::complex<double> H = N / D;
      const double s = std::sqrt(2.0) * data_.w(k);
      const std::complex<double> r = s * (H - data_.g(k));
      residuals[2 * k] = r.real();
      residuals[2 * k + 1] = r.imag();
      if (!std::isfinite(r.real()) || !std::isfinite(r.imag())) return false;
      if (jacobian == nullptr) continue;
      double* re = jacobian + (2 * k) * columns;
      double* im = jacobian + (2 * k + 1) * columns;
      std::complex<double> xi = s / D;
      for (int i = 0; i < std::max(nb_, na_); ++i) {
        if (i < nb_) {
          re[i] = xi.real();
          im[i] = xi.imag();
        }
        if (i < na_) {
          const std::complex<double> v = -H * xi;
          re[nb_ + i] = v.real();
          im[nb_ + i] = v.imag();
        }
        xi *= x;
      }
    }
    return true;
  }

 private:
  const FitData& data_;
  int nb_, na_;
};

}  // namespace

bool refine_output_error(const FitData& data, Coefficients& c, int iterations) {
  const int nb = static_cast<int>(c.b.size()), na = static_cast<int>(c.a_low.size());
  const double before = weighted_misfit(data, c.b, c.a_low);
  Eigen::VectorXd start(nb + na);
  start << c.b, c.a_low;

  const OutputError cost(data, nb, na);
  NonlinearLeastSquares problem;
  problem.residuals = cost;
  problem.residual_count = cost.residual_count();
  NonlinearLeastSquaresOptions options;
  options.max_iterations = iterations;
  options.function_tolerance = 1e-15;
  options.gradient_tolerance = 1e-16;
  options.parameter_tolerance = 1e-14;
  // Ceres logs an error through glog when it gives up after consecutive invalid steps (steps to
  // a non-finite misfit, common for over-parameterised orders); libraries must not print, so
  // let such runs end on the iteration limit instead (the result is checked below either way).
  options.max_consecutive_invalid_steps = iterations;
  const NonlinearLeastSquaresSolution solution = solve_nonlinear_least_squares(problem, start, options);
  if (!solution.usable()) return false;

  const Eigen::VectorXd b_new = solution.x.head(nb);
  const Eigen::VectorXd a_new = solution.x.tail(na);
  const double after = weighted_misfit(data, b_new, a_new);
  if (!std::isfinite(after) || after > before) return false;
  c.b = b_new;
  c.a_low = a_new;
  return true;
}

Eigen::MatrixXd output_error_jacobian(const FitData& data, const Coefficients& c) {
  const int nb = static_cast<int>(c.b.size()), na = static_cast<int>(c.a_low.size());
  const OutputError cost(data, nb, na);
  Eigen::VectorXd parameters(nb + na);
  parameters << c.b, c.a_low;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> J(cost.residual_count(), nb + na);
  Eigen::VectorXd residuals(cost.residual_count());
  cost(parameters.data(), residuals.data(), J.data());
  return J;
}

}  // namespace ambid::ident::detail
