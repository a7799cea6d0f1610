#include "diagnostics/audit/audit_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "diagnostics/plant_families.hpp"
#include "identifier/nonlinear_least_squares.hpp"

namespace ambid::diag {
namespace {

// Lags and delays are fitted no closer to zero than this fraction of their scale: a lag much
// faster than a sample changes nothing measurable but costs integrator sub-steps.
constexpr double kSmallestLag = 0.05;

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

ScaledFit fit_scaled(const Eigen::MatrixXd& measured_y, const Segment& estimation,
                     const std::function<Eigen::MatrixXd(const double* theta)>& replay, Eigen::VectorXd start,
                     const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, const FitOptions& options) {
  // 1 / ||y_j - mean|| on the estimation segment: the residuals are the NRMSE's terms.
  const Eigen::VectorXd inverse_spread =
      nrmse(measured_y, Eigen::MatrixXd::Zero(measured_y.rows(), measured_y.cols()), estimation).cwiseInverse();
  const Eigen::Index n = estimation.size();
  ident::NonlinearLeastSquares problem;
  problem.residuals = [&](const double* theta, double* residuals, double*) {
    Eigen::MatrixXd y;
    try {
      y = replay(theta);
    } catch (const Error&) {
      return false;  // the rotor touched the bearing, or an invalid parameter: not a step to take
    }
    Eigen::Map<Eigen::MatrixXd> r(residuals, n, y.cols());
    // Samples where a controller clamp acted (estimation.left_out) contribute a zero residual.
    r = estimation.kept_rows(measured_y.topRows(estimation.end) - y.topRows(estimation.end)) *
        inverse_spread.asDiagonal();
    return r.allFinite();
  };
  problem.residual_count = int(n * measured_y.cols());
  problem.differentiation = ident::Differentiation::central;
  problem.lower = lower;
  problem.upper = upper;
  ident::NonlinearLeastSquaresOptions solver;
  solver.max_iterations = options.max_iterations;
  start = start.cwiseMax(lower).cwiseMin(upper);
  const ident::NonlinearLeastSquaresSolution solution = ident::solve_nonlinear_least_squares(problem, start, solver);
  return {solution.x, 2.0 * solution.final_cost,  // the solver reports half the sum of squares
          solution.iterations, solution.termination == ident::Termination::converged};
}

EffectFit fit_effect(const Experiment& measured, const Eigen::MatrixXd& measured_y, const sim::Effect& start,
                     const Segment& estimation, const FitOptions& options, const std::vector<sim::Effect>& base) {
  const sim::EffectSpec& spec = sim::effect_spec(effect_catalogue_of(measured.plant.model, "audit"), start.name);
  auto at = [&](const double* theta) {
    sim::Effect e = start;
    for (std::size_t i = 0; i < spec.parameters.size(); ++i)
      e.parameters[spec.parameters[i].name] = theta[i] * spec.parameters[i].scale;
    return e;
  };
  const auto k = Eigen::Index(spec.parameters.size());
  Eigen::VectorXd theta(k), lower(k), upper(k);
  for (Eigen::Index i = 0; i < k; ++i) {
    const auto& p = spec.parameters[std::size_t(i)];
    lower(i) = p.unit == "s" && p.lower == 0.0 ? kSmallestLag : p.lower / p.scale;
    upper(i) = p.upper / p.scale;
    theta(i) = start.at(p.name) / p.scale;
  }
  const ScaledFit fit = fit_scaled(
      measured_y, estimation,
      [&](const double* x) {
        std::vector<sim::Effect> effects = base;
        effects.push_back(at(x));
        return replay_outputs(measured, effects, estimation.end);
      },
      theta, lower, upper, options);
  if (!std::isfinite(fit.cost))
    throw Error("audit: the fit of " + start.name + " could not start from its initial values");
  return {at(fit.theta.data()), fit.cost, fit.iterations, fit.converged};
}

}  // namespace ambid::diag
