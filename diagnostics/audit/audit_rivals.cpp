#include "diagnostics/audit/audit_rivals.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "diagnostics/audit/audit_significance.hpp"

namespace ambid::diag {
namespace audit_rivals {

// The joint autoregression of the outputs' noise, output by output in their order:
// e_j[k] = sum_{i=1..order} sum_l a e_l[k - i] + sum_{l<j} c e_l[k] + white, fitted by QR to the
// rows of `residual` in `segment` (the samples a clamp acted on are zero there, as everywhere
// in the audit's sums). Per output j the coefficients of those regressors (lagged outputs,
// then the earlier outputs at the same sample); empty: too short to fit, no whitening.
std::vector<Eigen::VectorXd> noise_autoregression(const Eigen::MatrixXd& residual, const Segment& segment,
                                                  Eigen::Index order) {
  const Eigen::MatrixXd e = segment.kept_rows(residual);
  const Eigen::Index n = e.rows() - order, q = e.cols();
  if (n < 4 * order * q) return {};
  std::vector<Eigen::VectorXd> a;
  Eigen::MatrixXd regressors(n, order * q + q);
  for (Eigen::Index i = 0; i < order; ++i)
    for (Eigen::Index l = 0; l < q; ++l) regressors.col(i * q + l) = e.col(l).segment(order - 1 - i, n);
  for (Eigen::Index l = 0; l < q; ++l) regressors.col(order * q + l) = e.col(l).tail(n);
  for (Eigen::Index j = 0; j < q; ++j)
    a.push_back(linalg::qr_solve(regressors.leftCols(order * q + j), Eigen::VectorXd(e.col(j).tail(n))).x);
  return a;
}

// Per output j, y_j[k] less its prediction by the noise's autoregression from y itself (the
// prediction error of the noise model): the same filter for the measurement and every replay.
// The samples a clamp acted on (`left_out`) are set to zero first, so that what was logged
// there reaches no whitened sample after them either.
Eigen::MatrixXd whitened(const Eigen::MatrixXd& signal, const std::vector<Eigen::VectorXd>& a,
                         const Segment& left_out) {
  Eigen::MatrixXd y = signal;
  for (Eigen::Index k = 0; k < y.rows(); ++k)
    if (left_out.left_out_at(k)) y.row(k).setZero();
  if (a.empty()) return y;
  const Eigen::Index q = y.cols(), N = y.rows(), order = (a.front().size()) / q;
  Eigen::MatrixXd w = y;
  for (Eigen::Index j = 0; j < q; ++j) {
    const Eigen::VectorXd& c = a[std::size_t(j)];
    for (Eigen::Index i = 0; i < order; ++i)
      for (Eigen::Index l = 0; l < q; ++l) w.col(j).tail(N - i - 1) -= c[i * q + l] * y.col(l).head(N - i - 1);
    for (Eigen::Index l = 0; l < j; ++l) w.col(j) -= c[order * q + l] * y.col(l);
  }
  return w;
}

}  // namespace audit_rivals

RivalChoice choose_among_rivals(const Eigen::MatrixXd& measured, const std::vector<const Eigen::MatrixXd*>& replays,
                                const Segment& validation, Eigen::Index covariance_lags, double margin,
                                const std::vector<OneStepPrediction>& one_step) {
  if (replays.empty()) throw Error("audit: no finding to choose among");
  if (!one_step.empty() && one_step.size() != replays.size())
    throw Error("audit: " + std::to_string(one_step.size()) + " one-step predictions for " +
                std::to_string(replays.size()) + " rivals");
  const auto n = Eigen::Index(replays.size());
  RivalChoice c;
  c.z = Eigen::MatrixXd::Zero(n, n);
  const std::vector<Eigen::VectorXd> ar =
      audit_rivals::noise_autoregression(measured - *replays.front(), validation, kWhiteningOrder);
  const Eigen::MatrixXd m = audit_rivals::whitened(measured, ar, validation);
  std::vector<Eigen::MatrixXd> y;
  for (const Eigen::MatrixXd* replay : replays) y.push_back(audit_rivals::whitened(*replay, ar, validation));
  for (Eigen::Index a = 0; a < n; ++a)
    for (Eigen::Index b = 0; b < n; ++b)
      if (a != b) c.z(a, b) = improvement_test(m, y[std::size_t(b)], y[std::size_t(a)], validation, covariance_lags).z;
  if (!one_step.empty()) {
    c.z_one_step = Eigen::MatrixXd::Zero(n, n);
    for (Eigen::Index a = 0; a < n; ++a)
      for (Eigen::Index b = 0; b < n; ++b)
        if (a != b)
          c.z_one_step(a, b) = improvement_test(one_step[std::size_t(a)].measured, one_step[std::size_t(b)].predicted,
                                                one_step[std::size_t(a)].predicted, validation, covariance_lags)
                                   .z;
  }
  c.losses.assign(replays.size(), 0);
  for (Eigen::Index a = 0; a < n; ++a)
    for (Eigen::Index b = 0; b < n; ++b)
      if (a != b && c.deciding(b, a) > margin && c.deciding(b, a) > c.deciding(a, b)) ++c.losses[std::size_t(a)];
  c.pick = std::size_t(std::min_element(c.losses.begin(), c.losses.end()) - c.losses.begin());
  return c;
}

}  // namespace ambid::diag
