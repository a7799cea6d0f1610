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

struct ReplayResiduals {
  const Experiment& measured;
  const Eigen::MatrixXd& measured_y;
  sim::Effect effect;
  std::vector<sim::EffectParameterSpec> specs;
  Segment estimation;
  Eigen::VectorXd inverse_spread;  // 1 / ||y_j - mean|| on the estimation segment
  std::vector<sim::Effect> base;   // effects already accepted, replayed along

  sim::Effect at(const double* theta) const {
    sim::Effect e = effect;
    for (std::size_t i = 0; i < specs.size(); ++i) e.parameters[specs[i].name] = theta[i] * specs[i].scale;
    return e;
  }

  bool operator()(const double* theta, double* residuals) const {
    Eigen::MatrixXd y;
    try {
      std::vector<sim::Effect> effects = base;
      effects.push_back(at(theta));
      y = replay_outputs(measured, effects, estimation.end);
    } catch (const Error&) {
      return false;  // the rotor touched the bearing, or an invalid parameter: not a step to take
    }
    const Eigen::Index n = estimation.size();
    Eigen::Map<Eigen::MatrixXd> r(residuals, n, y.cols());
    // Samples where a controller clamp acted (estimation.left_out) contribute a zero residual.
    r = estimation.kept_rows(measured_y.topRows(estimation.end) - y) * inverse_spread.asDiagonal();
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
                     const Segment& estimation, const FitOptions& options, const std::vector<sim::Effect>& base) {
  const sim::EffectSpec& spec = sim::effect_spec(effect_catalogue_of(measured.plant.model, "audit"), start.name);
  ReplayResiduals residuals{measured, measured_y, start, spec.parameters, estimation, {}, base};
  residuals.inverse_spread =
      nrmse(measured_y, Eigen::MatrixXd::Zero(measured_y.rows(), measured_y.cols()), estimation).cwiseInverse();
  const int k = int(spec.parameters.size());
  Eigen::VectorXd theta(k);
  ident::NonlinearLeastSquares problem;
  problem.residuals = [&residuals](const double* x, double* r, double*) { return residuals(x, r); };
  problem.residual_count = int(estimation.size() * measured_y.cols());
  problem.differentiation = ident::Differentiation::central;
  problem.lower.resize(k);
  problem.upper.resize(k);
  for (int i = 0; i < k; ++i) {
    const auto& p = spec.parameters[std::size_t(i)];
    double lower = p.lower / p.scale;
    if (p.unit == "s" && p.lower == 0.0) lower = kSmallestLag;
    problem.lower(i) = lower;
    problem.upper(i) = p.upper / p.scale;
    theta(i) = std::clamp(start.at(p.name) / p.scale, lower, p.upper / p.scale);
  }
  ident::NonlinearLeastSquaresOptions solver;
  solver.max_iterations = options.max_iterations;
  const ident::NonlinearLeastSquaresSolution solution = ident::solve_nonlinear_least_squares(problem, theta, solver);

  EffectFit fit;
  fit.effect = residuals.at(solution.x.data());
  fit.cost = 2.0 * solution.final_cost;  // the solver reports half the sum of squares
  fit.iterations = solution.iterations;
  fit.converged = solution.termination == ident::Termination::converged;
  if (!std::isfinite(fit.cost))
    throw Error("audit: the fit of " + start.name + " could not start from its initial values");
  return fit;
}

}  // namespace ambid::diag
