#include "diagnostics/audit/audit_significance.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace ambid::diag {
namespace {

double normal_upper_tail(double z) { return 0.5 * std::erfc(z / std::sqrt(2.0)); }

// sum_k a[k] b[k + h] over the samples where both exist.
double lagged_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b, Eigen::Index h) {
  const Eigen::Index n = a.size();
  return h >= 0 ? a.head(n - h).dot(b.tail(n - h)) : a.tail(n + h).dot(b.head(n + h));
}

}  // namespace

ImprovementTest improvement_test(const Eigen::MatrixXd& measured, const Eigen::MatrixXd& nominal,
                                 const Eigen::MatrixXd& extended, const Segment& validation, Eigen::Index max_lag) {
  const Eigen::Index n = validation.size(), q = measured.cols();
  if (validation.begin < 0 || n < 8 || measured.rows() < validation.end || nominal.rows() < validation.end ||
      extended.rows() < validation.end || nominal.cols() != q || extended.cols() != q)
    throw Error("audit: improvement test segment [" + std::to_string(validation.begin) + ", " +
                std::to_string(validation.end) + ") does not fit the signals");
  // The samples left out (a controller clamp acted) are zero in m, e0, d and the noise: no
  // sum below counts them, and the means and covariances are over the kept ones.
  const Eigen::VectorXd kept = validation.kept();
  const double n_kept = kept.sum();
  if (n_kept < 8.0) throw InsufficientData("audit: fewer than 8 samples without a controller clamp to test");
  const Eigen::MatrixXd m = validation.kept_rows(measured);
  const Eigen::MatrixXd e0 = m - validation.kept_rows(nominal);
  const Eigen::MatrixXd d = validation.kept_rows(extended) - validation.kept_rows(nominal);
  Eigen::MatrixXd noise = e0 - d;
  noise -= kept * (noise.colwise().sum() / n_kept);
  Eigen::VectorXd w(q);
  for (Eigen::Index j = 0; j < q; ++j) {
    const double spread2 = ((m.col(j).array() - m.col(j).sum() / n_kept) * kept.array()).square().sum();
    if (!(spread2 > 0.0)) throw InsufficientData("audit: measured output " + std::to_string(j + 1) + " is constant");
    w[j] = 1.0 / spread2;
  }
  ImprovementTest t;
  double projection = 0.0;
  for (Eigen::Index j = 0; j < q; ++j) {
    projection += w[j] * e0.col(j).dot(d.col(j));
    t.reduction += w[j] * (e0.col(j).squaredNorm() - (e0.col(j) - d.col(j)).squaredNorm());
  }
  const Eigen::Index M = std::clamp<Eigen::Index>(max_lag, 0, n / 4);
  double variance = 0.0;
  for (Eigen::Index j = 0; j < q; ++j)
    for (Eigen::Index l = 0; l < q; ++l)
      for (Eigen::Index h = -M; h <= M; ++h) {
        const double taper = 1.0 - double(std::abs(h)) / double(M + 1);
        const double gamma = lagged_dot(noise.col(j), noise.col(l), h) / n_kept;
        variance += w[j] * w[l] * taper * gamma * lagged_dot(d.col(j), d.col(l), h);
      }
  if (!(variance > 0.0)) {
    // d = 0 (the fit stayed at the nominal model) or no noise at all: no evidence either way
    // unless the residual is explained exactly.
    t.z = projection > 0.0 && noise.squaredNorm() == 0.0 ? INFINITY : 0.0;
  } else {
    t.z = projection / std::sqrt(variance);
  }
  t.p_value = normal_upper_tail(t.z);
  return t;
}

double acceptance_threshold(double alpha, int candidates) {
  if (!(alpha > 0.0 && alpha < 1.0))
    throw Error("audit: false-acceptance probability must be in (0, 1), got " + std::to_string(alpha));
  if (candidates < 1) throw Error("audit: at least one candidate is needed for an acceptance threshold");
  // Inverse of the upper normal tail by bisection (monotone, 60 halvings are exact to double).
  const double tail = alpha / double(candidates);
  double lo = -40.0, hi = 40.0;
  for (int i = 0; i < 200 && hi - lo > 1e-12; ++i) {
    const double mid = 0.5 * (lo + hi);
    (normal_upper_tail(mid) > tail ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace ambid::diag
