// Output-error refinement of a rational fit by Ceres, and the Jacobian for the covariance.
#include <cmath>
#include <vector>

#include <ceres/ceres.h>

#include "identifier/frequency_domain/rational_fit_detail.hpp"

namespace ambid::ident::detail {
namespace {

// Residuals sqrt(2) w_k (N(x_k)/D(x_k) - g_k), real and imaginary parts, with the analytic
// Jacobian d/db_i = sqrt(2) w x^i / D, d/da_i = -sqrt(2) w (N/D) x^i / D.
class OutputError final : public ceres::CostFunction {
 public:
  OutputError(const FitData& data, int nb, int na) : data_(data), nb_(nb), na_(na) {
    set_num_residuals(static_cast<int>(2 * data.x.size()));
    mutable_parameter_block_sizes()->push_back(nb);
    mutable_parameter_block_sizes()->push_back(na);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Map<const Eigen::VectorXd> b(parameters[0], nb_);
    const Eigen::Map<const Eigen::VectorXd> a(parameters[1], na_);
    for (Eigen::Index k = 0; k < data_.x.size(); ++k) {
      const std::complex<double> x = data_.x(k);
      const std::complex<double> N = polyval(b, x), D = monic_polyval(a, x);
      const std::complex<double> H = N / D;
      const double s = std::sqrt(2.0) * data_.w(k);
      const std::complex<double> r = s * (H - data_.g(k));
      residuals[2 * k] = r.real();
      residuals[2 * k + 1] = r.imag();
      if (!std::isfinite(r.real()) || !std::isfinite(r.imag())) return false;
      if (jacobians == nullptr) continue;
      std::complex<double> xi = s / D;
      for (int i = 0; i < std::max(nb_, na_); ++i) {
        if (jacobians[0] != nullptr && i < nb_) {
          jacobians[0][(2 * k) * nb_ + i] = xi.real();
          jacobians[0][(2 * k + 1) * nb_ + i] = xi.imag();
        }
        if (jacobians[1] != nullptr && i < na_) {
          const std::complex<double> v = -H * xi;
          jacobians[1][(2 * k) * na_ + i] = v.real();
          jacobians[1][(2 * k + 1) * na_ + i] = v.imag();
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
  std::vector<double> b(c.b.data(), c.b.data() + nb), a(c.a_low.data(), c.a_low.data() + na);
  const double before = weighted_misfit(data, c.b, c.a_low);

  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  problem.AddResidualBlock(new OutputError(data, nb, na), nullptr, b.data(), a.data());
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = iterations;
  options.function_tolerance = 1e-15;
  options.gradient_tolerance = 1e-16;
  options.parameter_tolerance = 1e-14;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  // Ceres logs an error through glog when it gives up after consecutive invalid steps (steps to
  // a non-finite misfit, common for over-parameterised orders); libraries must not print, so
  // let such runs end on the iteration limit instead (the result is checked below either way).
  options.max_num_consecutive_invalid_steps = iterations;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (summary.termination_type == ceres::FAILURE || summary.termination_type == ceres::USER_FAILURE) return false;

  const Eigen::VectorXd b_new = Eigen::Map<const Eigen::VectorXd>(b.data(), nb);
  const Eigen::VectorXd a_new = Eigen::Map<const Eigen::VectorXd>(a.data(), na);
  const double after = weighted_misfit(data, b_new, a_new);
  if (!std::isfinite(after) || after > before) return false;
  c.b = b_new;
  c.a_low = a_new;
  return true;
}

Eigen::MatrixXd output_error_jacobian(const FitData& data, const Coefficients& c) {
  const int nb = static_cast<int>(c.b.size()), na = static_cast<int>(c.a_low.size());
  const auto rows = 2 * data.x.size();
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Jb(rows, nb), Ja(rows, na);
  Eigen::VectorXd residuals(rows);
  OutputError cost(data, nb, na);
  const double* parameters[2] = {c.b.data(), c.a_low.data()};
  double* jacobians[2] = {Jb.data(), Ja.data()};
  cost.Evaluate(parameters, residuals.data(), jacobians);
  Eigen::MatrixXd J(rows, nb + na);
  J << Jb, Ja;
  return J;
}

}  // namespace ambid::ident::detail
