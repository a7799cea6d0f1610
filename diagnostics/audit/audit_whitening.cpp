#include "diagnostics/audit/audit_whitening.hpp"

#include "core/linalg.hpp"

namespace ambid::diag {

NoiseWhitening fit_noise_whitening(const Eigen::MatrixXd& residual, const Segment& segment, Eigen::Index order) {
  NoiseWhitening w;
  w.left_out.left_out = segment.left_out;
  const Eigen::MatrixXd e = segment.kept_rows(residual);
  const Eigen::Index n = e.rows() - order, q = e.cols();
  if (n < 4 * order * q) return w;
  Eigen::MatrixXd regressors(n, order * q + q);
  for (Eigen::Index i = 0; i < order; ++i)
    for (Eigen::Index l = 0; l < q; ++l) regressors.col(i * q + l) = e.col(l).segment(order - 1 - i, n);
  for (Eigen::Index l = 0; l < q; ++l) regressors.col(order * q + l) = e.col(l).tail(n);
  for (Eigen::Index j = 0; j < q; ++j)
    w.ar.push_back(linalg::qr_solve(regressors.leftCols(order * q + j), Eigen::VectorXd(e.col(j).tail(n))).x);
  return w;
}

Eigen::MatrixXd NoiseWhitening::apply(const Eigen::MatrixXd& signal) const {
  Eigen::MatrixXd y = signal;
  for (Eigen::Index k = 0; k < y.rows(); ++k)
    if (left_out.left_out_at(k)) y.row(k).setZero();
  if (ar.empty()) return y;
  const Eigen::Index q = y.cols(), N = y.rows(), order = ar.front().size() / q;
  Eigen::MatrixXd w = y;
  for (Eigen::Index j = 0; j < q; ++j) {
    const Eigen::VectorXd& c = ar[std::size_t(j)];
    for (Eigen::Index i = 0; i < order; ++i)
      for (Eigen::Index l = 0; l < q; ++l) w.col(j).tail(N - i - 1) -= c[i * q + l] * y.col(l).head(N - i - 1);
    for (Eigen::Index l = 0; l < j; ++l) w.col(j) -= c[order * q + l] * y.col(l);
  }
  return w;
}

}  // namespace ambid::diag
