#include "identifier/nonlinear_least_squares.hpp"

#include <memory>
#include <vector>

#include <ceres/ceres.h>

#include "core/error.hpp"

namespace ambid::ident {
namespace {

// One parameter block, the function's own Jacobian.
class ProvidedJacobian final : public ceres::CostFunction {
 public:
  ProvidedJacobian(const ResidualFunction& f, int residuals, int parameters) : f_(f) {
    set_num_residuals(residuals);
    mutable_parameter_block_sizes()->push_back(parameters);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    return f_(parameters[0], residuals, jacobians != nullptr ? jacobians[0] : nullptr);
  }

 private:
  const ResidualFunction& f_;
};

// The residuals alone, for Ceres' numeric differentiation.
struct ResidualsOnly {
  const ResidualFunction& f;
  bool operator()(double const* const* parameters, double* residuals) const {
    return f(parameters[0], residuals, nullptr);
  }
};

std::unique_ptr<ceres::CostFunction> cost_function(const NonlinearLeastSquares& p, int parameters) {
  if (p.differentiation == Differentiation::provided)
    return std::make_unique<ProvidedJacobian>(p.residuals, p.residual_count, parameters);
  auto cost = std::make_unique<ceres::DynamicNumericDiffCostFunction<ResidualsOnly, ceres::CENTRAL>>(
      new ResidualsOnly{p.residuals});
  cost->AddParameterBlock(parameters);
  cost->SetNumResiduals(p.residual_count);
  return cost;
}

Termination termination(ceres::TerminationType type) {
  switch (type) {
    case ceres::CONVERGENCE:
    case ceres::USER_SUCCESS:
      return Termination::converged;
    case ceres::NO_CONVERGENCE:
      return Termination::iteration_limit;
    case ceres::FAILURE:
    case ceres::USER_FAILURE:
      break;
  }
  return Termination::failure;
}

}  // namespace

NonlinearLeastSquaresSolution solve_nonlinear_least_squares(const NonlinearLeastSquares& p,
                                                            const Eigen::VectorXd& start,
                                                            const NonlinearLeastSquaresOptions& o) {
  const auto n = static_cast<int>(start.size());
  if (!p.residuals || p.residual_count < 1 || n < 1)
    throw Error("least squares: needs a residual function, residuals and parameters, got " +
                std::to_string(p.residual_count) + " residuals and " + std::to_string(n) + " parameters");
  if ((p.lower.size() != 0 && p.lower.size() != n) || (p.upper.size() != 0 && p.upper.size() != n))
    throw Error("least squares: bounds of " + std::to_string(p.lower.size()) + " and " +
                std::to_string(p.upper.size()) + " values for " + std::to_string(n) + " parameters");

  NonlinearLeastSquaresSolution out;
  out.x = start;
  const std::unique_ptr<ceres::CostFunction> cost = cost_function(p, n);
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;  // `cost` evaluates the Jacobian after the solve
  ceres::Problem problem(po);
  problem.AddResidualBlock(cost.get(), nullptr, out.x.data());
  for (int i = 0; i < static_cast<int>(p.lower.size()); ++i)
    problem.SetParameterLowerBound(out.x.data(), i, p.lower(i));
  for (int i = 0; i < static_cast<int>(p.upper.size()); ++i)
    problem.SetParameterUpperBound(out.x.data(), i, p.upper(i));

  ceres::Solver::Options so;
  so.minimizer_type = ceres::TRUST_REGION;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = o.max_iterations;
  so.function_tolerance = o.function_tolerance;
  so.gradient_tolerance = o.gradient_tolerance;
  so.parameter_tolerance = o.parameter_tolerance;
  so.max_num_consecutive_invalid_steps = o.max_consecutive_invalid_steps;
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = false;
  so.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);

  out.termination = termination(summary.termination_type);
  out.message = summary.message;
  out.iterations = static_cast<int>(summary.iterations.size());
  out.initial_cost = summary.initial_cost;
  out.final_cost = summary.final_cost;
  if (o.jacobian) {
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> J(p.residual_count, n);
    out.residuals.resize(p.residual_count);
    const double* parameters[1] = {out.x.data()};
    double* jacobians[1] = {J.data()};
    out.evaluated = cost->Evaluate(parameters, out.residuals.data(), jacobians);
    out.jacobian = J;
  }
  return out;
}

}  // namespace ambid::ident
