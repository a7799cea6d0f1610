#include "diagnostics/audit/audit_quantisation.hpp"

#include <cmath>

#include <Eigen/Core>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "plant_sim/maglev_rig.hpp"

namespace ambid::diag {
namespace {

// Least squares of `target` on [i[k], 1, d] with Q an orthonormal basis of [i[k], 1] and
// `target_residual` = target less its projection on Q: one more Gram-Schmidt column.
struct Regression {
  Eigen::MatrixXd Q;
  Eigen::VectorXd target_residual;

  double residual(const Eigen::VectorXd& d) const {
    const Eigen::VectorXd orthogonal = d - Q * (Q.transpose() * d);
    const double norm = orthogonal.norm();
    const double rss = target_residual.squaredNorm();
    if (!(norm > 1e-12 * d.norm())) return rss;
    const double along = orthogonal.dot(target_residual) / norm;
    return rss - along * along;
  }
};

Regression regression(const Eigen::VectorXd& current) {
  const Eigen::Index n = current.size() - 1;
  Eigen::MatrixXd basis(n, 2);
  basis.col(0) = current.head(n);
  basis.col(1).setOnes();
  Regression r;
  r.Q = linalg::column_space(basis);  // one column when the current is constant
  const Eigen::VectorXd target = current.tail(n);
  r.target_residual = target - r.Q * (r.Q.transpose() * target);
  return r;
}

Eigen::VectorXd rounded(const Eigen::VectorXd& command, double step) {
  Eigen::VectorXd out(command.size() - 1);
  for (Eigen::Index k = 0; k < out.size(); ++k) out(k) = sim::round_to(command(k), step);
  return out;
}

// The best step of `count` + 1 logarithmically spaced from `lo` to `hi`.
void search(const Regression& r, const Eigen::VectorXd& command, double lo, double hi, int count, DacScreen& best) {
  for (int j = 0; j <= count; ++j) {
    const double step = lo * std::pow(hi / lo, double(j) / count);
    const double rss = r.residual(rounded(command, step));
    if (rss < best.residual) best = {step, rss, best.unrounded};
  }
}

// The middle of the interval of steps that round every command to the same multiple as `step`
// does: command c rounds to n = round(c / s) for s in (c / (n + 1/2), c / (n - 1/2)).
double middle_of_same_rounding(const Eigen::VectorXd& command, double step) {
  double lo = 0.0, hi = INFINITY;
  for (Eigen::Index k = 0; k < command.size(); ++k) {
    const double c = std::abs(command(k)), n = std::nearbyint(c / step);
    lo = std::max(lo, c / (n + 0.5));
    if (n >= 1.0) hi = std::min(hi, c / (n - 0.5));
  }
  return lo < step && step < hi ? 0.5 * (lo + hi) : step;
}

}  // namespace

DacScreen screen_dac_step(const Eigen::VectorXd& command, const Eigen::VectorXd& current, double smallest,
                          double largest) {
  if (command.size() != current.size() || command.size() < 10)
    throw Error("DAC screen: command and current need the same length of at least 10 samples, got " +
                std::to_string(command.size()) + " and " + std::to_string(current.size()));
  if (!command.allFinite() || !current.allFinite()) throw Error("DAC screen: the signals must be finite");
  if (!(smallest > 0.0 && largest > smallest && std::isfinite(largest)))
    throw Error("DAC screen: steps must satisfy 0 < smallest < largest, got " + std::to_string(smallest) + " and " +
                std::to_string(largest));
  const Regression r = regression(current);
  DacScreen best;
  best.unrounded = r.residual(command.head(command.size() - 1));
  best.residual = INFINITY;
  // Coarse: 0.5 % apart; fine: 0.01 % apart within 1 % of the coarse best.
  search(r, command, smallest, largest, int(std::ceil(std::log(largest / smallest) / std::log(1.005))), best);
  const double centre = best.step;
  search(r, command, std::max(smallest, centre / 1.01), std::min(largest, centre * 1.01), 200, best);
  // The residual is flat over the steps that round every logged command alike: its middle
  // puts the DAC's edges midway between the logged values about them, where a command logged
  // at 0.01 V rounds as the DAC rounded the unrounded one (0.01 % off, a 0.35 V step put edges
  // on logged values, and the replay rounded commands across them that the rig did not).
  best.step = middle_of_same_rounding(command.head(command.size() - 1), best.step);
  return best;
}

}  // namespace ambid::diag
