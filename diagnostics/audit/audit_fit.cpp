#include "diagnostics/audit/audit_fit.hpp"

#include <cmath>
#include <limits>

#include <ceres/ceres.h>

#include "core/error.hpp"

namespace ambid::diag {
namespace {

// Lags and delays are fitted no closer to zero than this fraction of their scale: a lag much
// faster than a sample changes nothing measurable but costs integrator sub-steps.
constexpr double kSmallestLag = 0.05;

struct ReplayResiduals {
  const Experiment& measured;
  const Eigen::MatrixXd& measured_y;
  sim::Effect effect;
  std::vector<sim::EffectParameterSpec> specs;
  Segment estimation;
  Eigen::VectorXd inverse_spread;  // 1 / ||y_j - mean|| on the estimation segment

  sim::Effect at(const double* theta) const {
    sim::Effect e = effect;
    for (std::size_t i = 0; i < specs.size(); ++i) e.parameters[specs[i].name] = theta[i] * specs[i].scale;
    return e;
  }

  bool operator()(double const* const* parameters, double* residuals) const {
    Eigen::MatrixXd y;
    try {
      y = replay_outputs(measured, {at(parameters[0])}, estimation.end);
    } catch (const Error&) {
      return false;  // the rotor touched the bearing, or an invalid parameter: not a step to take
    }
    const Eigen::Index n = estimation.size();
    Eigen::Map<Eigen::MatrixXd> r(residuals, n, y.cols());
    r = (measured_y.middleRows(estimation.begin, n) - y.middleRows(estimation.begin, n)) * inverse_spread.asDiagonal();
    return r.allFinite();
  }
};

}  // namespace

double estimation_cost(const Experiment& measured, const Eigen::MatrixXd& measured_y,
                       const std::vector<sim::Effect>& effects, const Segment& estimation) {
  try {
    const Eigen::MatrixXd y = replay_outputs(measured, effects, estimation.end);
    return nrmse(measured_y, y, estimation).squaredNorm();
  } catch (const InsufficientData&) {
    throw;
  } catch (const Error&) {
    return std::numeric_limits<double>::infinity();
  }
}

EffectFit fit_effect(const Experiment& measured, const Eigen::MatrixXd& measured_y, const sim::Effect& start,
                     const Segment& estimation, const FitOptions& options) {
  const sim::EffectSpec& spec = sim::effect_spec(start.name);
  auto* functor = new ReplayResiduals{measured, measured_y, start, spec.parameters, estimation, {}};
  functor->inverse_spread = nrmse(measured_y, Eigen::MatrixXd::Zero(measured_y.rows(), measured_y.cols()), estimation)
                                .cwiseInverse();
  const int k = int(spec.parameters.size());
  std::vector<double> theta(std::size_t(k), 0.0);
  for (int i = 0; i < k; ++i) theta[std::size_t(i)] = start.at(spec.parameters[std::size_t(i)].name) / spec.parameters[std::size_t(i)].scale;

  auto* cost = new ceres::DynamicNumericDiffCostFunction<ReplayResiduals, ceres::CENTRAL>(functor);
  cost->AddParameterBlock(k);
  cost->SetNumResiduals(int(estimation.size() * measured_y.cols()));
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, theta.data());
  for (int i = 0; i < k; ++i) {
    const auto& p = spec.parameters[std::size_t(i)];
    double lower = p.lower / p.scale;
    if (p.unit == "s" && p.lower == 0.0) lower = kSmallestLag;
    theta[std::size_t(i)] = std::clamp(theta[std::size_t(i)], lower, p.upper / p.scale);
    problem.SetParameterLowerBound(theta.data(), i, lower);
    problem.SetParameterUpperBound(theta.data(), i, p.upper / p.scale);
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.logging_type = ceres::SILENT;
  solver.minimizer_progress_to_stdout = false;
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);

  EffectFit fit;
  fit.effect = functor->at(theta.data());
  fit.cost = 2.0 * summary.final_cost;  // Ceres reports half the sum of squares
  fit.iterations = int(summary.iterations.size());
  fit.converged = summary.termination_type == ceres::CONVERGENCE;
  if (!std::isfinite(fit.cost)) throw Error("audit: the fit of " + start.name + " could not start from its initial values");
  return fit;
}

}  // namespace ambid::diag
