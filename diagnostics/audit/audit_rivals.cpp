#include "diagnostics/audit/audit_rivals.hpp"

#include <algorithm>

#include <Eigen/Core>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "diagnostics/audit/audit_significance.hpp"

namespace ambid::diag {
namespace audit_rivals {

// Per output j, the coefficients a (order x outputs) of the autoregression
// e[k] = sum_i a_i e[k - i] + white, fitted by QR to the rows of `residual` in `segment` (the
// samples a clamp acted on are zero there, as everywhere in the audit's sums).
Eigen::MatrixXd noise_autoregression(const Eigen::MatrixXd& residual, const Segment& segment, Eigen::Index order) {
  const Eigen::MatrixXd e = segment.kept_rows(residual);
  const Eigen::Index n = e.rows() - order;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(order, e.cols());
  if (n < 4 * order) return a;  // too short to fit: no whitening
  for (Eigen::Index j = 0; j < e.cols(); ++j) {
    Eigen::MatrixXd lagged(n, order);
    for (Eigen::Index i = 0; i < order; ++i) lagged.col(i) = e.col(j).segment(order - 1 - i, n);
    a.col(j) = linalg::qr_solve(lagged, Eigen::VectorXd(e.col(j).tail(n))).x;
  }
  return a;
}

// y[k] - sum_i a_i y[k - i] per output (the prediction error of the noise's autoregression):
// the same filter for the measurement and every replay.
Eigen::MatrixXd whitened(const Eigen::MatrixXd& y, const Eigen::MatrixXd& a) {
  Eigen::MatrixXd w = y;
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < y.cols(); ++j)
      w.col(j).tail(y.rows() - i - 1) -= a(i, j) * y.col(j).head(y.rows() - i - 1);
  return w;
}

}  // namespace audit_rivals

RivalChoice choose_among_rivals(const Eigen::MatrixXd& measured, const std::vector<const Eigen::MatrixXd*>& replays,
                                const Segment& validation, Eigen::Index covariance_lags, double margin) {
  if (replays.empty()) throw Error("audit: no finding to choose among");
  const auto n = Eigen::Index(replays.size());
  RivalChoice c;
  c.z = Eigen::MatrixXd::Zero(n, n);
  const Eigen::MatrixXd ar =
      audit_rivals::noise_autoregression(measured - *replays.front(), validation, kWhiteningOrder);
  const Eigen::MatrixXd m = audit_rivals::whitened(measured, ar);
  std::vector<Eigen::MatrixXd> y;
  for (const Eigen::MatrixXd* replay : replays) y.push_back(audit_rivals::whitened(*replay, ar));
  for (Eigen::Index a = 0; a < n; ++a)
    for (Eigen::Index b = 0; b < n; ++b)
      if (a != b) c.z(a, b) = improvement_test(m, y[std::size_t(b)], y[std::size_t(a)], validation, covariance_lags).z;
  c.losses.assign(replays.size(), 0);
  for (Eigen::Index a = 0; a < n; ++a)
    for (Eigen::Index b = 0; b < n; ++b)
      if (a != b && c.z(b, a) > margin && c.z(b, a) > c.z(a, b)) ++c.losses[std::size_t(a)];
  c.pick = std::size_t(std::min_element(c.losses.begin(), c.losses.end()) - c.losses.begin());
  return c;
}

}  // namespace ambid::diag
