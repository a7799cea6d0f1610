#include "identifier/time_domain/levenberg_marquardt.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::ident {
namespace {

using Index = Eigen::Index;
const std::string kLmWho = "levenberg-marquardt";
constexpr double kMinDamping = 1e-15, kMaxDamping = 1e15;

// argmin ||R delta - z||^2 + lambda ||D delta||^2 by a QR of [R z; sqrt(lambda) D 0].
Eigen::VectorXd damped_step(const Eigen::MatrixXd& R, const Eigen::VectorXd& z, const Eigen::VectorXd& D,
                            double lambda) {
  const Index n = R.cols();
  Eigen::MatrixXd augmented = Eigen::MatrixXd::Zero(2 * n, n + 1);
  augmented.topLeftCorner(n, n) = R;
  augmented.topRightCorner(n, 1) = z;
  augmented.bottomLeftCorner(n, n).diagonal() = std::sqrt(lambda) * D;
  const Eigen::MatrixXd S = linalg::qr_r(augmented);
  return S.topLeftCorner(n, n).triangularView<Eigen::Upper>().solve(S.col(n).head(n));
}

}  // namespace

LevenbergMarquardtResult levenberg_marquardt(const BlockLeastSquares& problem, const Eigen::VectorXd& start,
                                             const LevenbergMarquardtOptions& options) {
  const Index n = problem.parameters;
  if (n < 1 || !problem.linearise || !problem.cost || start.size() != n)
    throw Error(kLmWho + ": needs parameters, a linearisation and a cost, and a start of " + std::to_string(n) +
                " values (got " + std::to_string(start.size()) + ")");
  if (options.max_iterations < 0 || !(options.step_tolerance > 0.0) || !(options.initial_damping > 0.0) ||
      options.max_trials < 1)
    throw Error(kLmWho + ": max_iterations >= 0, step_tolerance > 0, initial_damping > 0 and max_trials >= 1 needed");
  auto linearise = [&](const Eigen::VectorXd& p, const std::string& where) {
    LeastSquaresAccumulator rows(n, 1, problem.names);
    if (!problem.linearise(p, rows)) throw InsufficientData(kLmWho + ": the residuals cannot be evaluated " + where);
    return rows;
  };
  LevenbergMarquardtResult out{start, linearise(start, "at the start"), 0, false, "", 0.0, 0.0};
  Eigen::VectorXd D = Eigen::VectorXd::Zero(n);
  double lambda = options.initial_damping, growth = 2.0;
  for (bool first = true;; first = false) {
    const Eigen::MatrixXd F = out.rows.factor();
    const Eigen::MatrixXd R = F.topLeftCorner(n, n);
    const Eigen::VectorXd z = F.col(n).head(n);
    const double squares = z.squaredNorm() + F(n, n) * F(n, n);
    out.final_cost = 0.5 * squares;
    if (first) out.initial_cost = out.final_cost;
    const double sigma = std::sqrt(squares / double(std::max<Index>(out.rows.rows(), 1)));
    if (z.norm() <= options.step_tolerance * sigma) {
      out.converged = true;
      out.message = "the Gauss-Newton step is below " + std::to_string(options.step_tolerance) + " standard errors";
      break;
    }
    if (out.iterations >= options.max_iterations) {
      out.message = "iteration limit (" + std::to_string(options.max_iterations) + ") reached";
      break;
    }
    for (Index j = 0; j < n; ++j) D(j) = std::max(D(j), R.col(j).norm());
    const Eigen::VectorXd scale = (D.array() > 0.0).select(D, 1.0);  // a dead column: unit damping
    bool accepted = false;
    for (int trial = 0; trial < options.max_trials && lambda <= kMaxDamping; ++trial) {
      const Eigen::VectorXd delta = damped_step(R, z, scale, lambda);
      const double predicted = 0.5 * (z.squaredNorm() - (R.triangularView<Eigen::Upper>() * delta - z).squaredNorm());
      const Eigen::VectorXd p = out.p + delta;
      const double cost =
          delta.allFinite() && predicted > 0.0 ? problem.cost(p) : std::numeric_limits<double>::infinity();
      const double ratio = (out.final_cost - cost) / predicted;
      if (std::isfinite(cost) && ratio > 1e-4) {
        out.p = p;
        lambda = std::max(kMinDamping, lambda * std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * ratio - 1.0, 3)));
        growth = 2.0;
        accepted = true;
        break;
      }
      lambda *= growth;
      growth *= 2.0;
    }
    if (!accepted) {
      out.message = "no damped step decreases the cost (round-off or a poor model)";
      break;
    }
    ++out.iterations;
    out.rows = linearise(out.p, "after step " + std::to_string(out.iterations));
  }
  return out;
}

}  // namespace ambid::ident
