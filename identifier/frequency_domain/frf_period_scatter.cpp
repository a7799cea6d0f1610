#include "identifier/frequency_domain/frf_period_scatter.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include "core/error.hpp"

namespace ambid::ident {

std::vector<Eigen::MatrixXd> period_mean_variance(const std::vector<std::vector<Eigen::MatrixXcd>>& per_period,
                                                  Eigen::Index pooled_half_width) {
  const auto B = static_cast<Eigen::Index>(per_period.size());
  if (B < 3) throw Error("period scatter: need at least 3 periods, got " + std::to_string(B));
  const auto nl = static_cast<Eigen::Index>(per_period.front().size());
  if (nl < 1) throw Error("period scatter: no lines");
  const Eigen::Index rows = per_period.front().front().rows(), cols = per_period.front().front().cols();
  for (const auto& period : per_period) {
    if (std::ssize(period) != nl) throw Error("period scatter: the periods have different numbers of lines");
    for (const auto& m : period)
      if (m.rows() != rows || m.cols() != cols) throw Error("period scatter: the estimates differ in shape");
  }
  if (pooled_half_width < 0) throw Error("period scatter: pooled_half_width must be >= 0");

  // |D_j|^2 of every line and element, j = 1 .. B-1 (rows), and the regressor g_j.
  const Eigen::Index J = B - 1, elements = rows * cols;
  std::vector<Eigen::MatrixXd> power(static_cast<std::size_t>(nl), Eigen::MatrixXd(J, elements));
  Eigen::VectorXd g(J);
  const double b_count = static_cast<double>(B);
  for (Eigen::Index j = 1; j <= J; ++j) {
    const double s = std::sin(std::numbers::pi * static_cast<double>(j) / b_count);
    g(j - 1) = (2.0 + (b_count - 1.0) * 4.0 * s * s) / b_count;
    std::vector<std::complex<double>> weight(static_cast<std::size_t>(B));
    for (Eigen::Index b = 0; b < B; ++b)
      weight[static_cast<std::size_t>(b)] =
          std::polar(1.0 / b_count, -2.0 * std::numbers::pi * static_cast<double>(j * b) / b_count);
    for (Eigen::Index l = 0; l < nl; ++l) {
      Eigen::MatrixXcd D = Eigen::MatrixXcd::Zero(rows, cols);
      for (Eigen::Index b = 0; b < B; ++b)
        D += weight[static_cast<std::size_t>(b)] * per_period[static_cast<std::size_t>(b)][static_cast<std::size_t>(l)];
      power[static_cast<std::size_t>(l)].row(j - 1) = D.cwiseAbs2().reshaped().transpose();
    }
  }
  // Each line's |D_j|^2 over its mean across j (the noise level differs from line to line).
  std::vector<Eigen::MatrixXd> shape(static_cast<std::size_t>(nl));
  for (Eigen::Index l = 0; l < nl; ++l) {
    const Eigen::MatrixXd& p = power[static_cast<std::size_t>(l)];
    const Eigen::RowVectorXd level = p.colwise().mean();
    shape[static_cast<std::size_t>(l)] = Eigen::MatrixXd::Zero(J, elements);
    for (Eigen::Index e = 0; e < elements; ++e)
      if (level(e) > 0.0) shape[static_cast<std::size_t>(l)].col(e) = p.col(e) / level(e);
  }

  constexpr double kRhoMax = 1e6;  // the transient swamps the noise: alpha from the lowest j
  const Eigen::VectorXd gc = g.array() - g.mean();
  std::vector<Eigen::MatrixXd> out(static_cast<std::size_t>(nl), Eigen::MatrixXd(rows, cols));
  for (Eigen::Index l = 0; l < nl; ++l) {
    const Eigen::Index first = std::max<Eigen::Index>(0, l - pooled_half_width);
    const Eigen::Index last = std::min<Eigen::Index>(nl - 1, l + pooled_half_width);
    Eigen::MatrixXd pooled = Eigen::MatrixXd::Zero(J, elements);
    for (Eigen::Index m = first; m <= last; ++m) pooled += shape[static_cast<std::size_t>(m)];
    const Eigen::MatrixXd& p = power[static_cast<std::size_t>(l)];
    for (Eigen::Index e = 0; e < elements; ++e) {
      // Straight line a + b g through the pooled shape (one regressor: closed form).
      const double slope = gc.dot(pooled.col(e)) / gc.squaredNorm();
      const double intercept = pooled.col(e).mean() - slope * g.mean();
      const double rho = intercept > 0.0 ? std::clamp(slope / intercept, 0.0, kRhoMax) : (slope > 0.0 ? kRhoMax : 0.0);
      const double alpha = (p.col(e).array() / (1.0 + rho * g.array())).mean();
      out[static_cast<std::size_t>(l)].reshaped()(e) = alpha * (1.0 + 2.0 * rho / b_count);
    }
  }
  return out;
}

}  // namespace ambid::ident
