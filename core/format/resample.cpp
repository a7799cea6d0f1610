#include "core/format/resample.hpp"

#include <algorithm>
#include <cmath>

namespace ambid {

Eigen::Index resampled_length(const Eigen::VectorXd& t, double T) {
  return Eigen::Index(std::floor((t(t.size() - 1) - t(0)) / T + 1e-9)) + 1;
}

void resample_linear(Eigen::VectorXd& t, Eigen::MatrixXd& values, double T) {
  const Eigen::Index n = t.size();
  const Eigen::Index m = resampled_length(t, T);
  Eigen::VectorXd grid(m);
  Eigen::MatrixXd out(m, values.cols());
  Eigen::Index j = 0;
  for (Eigen::Index k = 0; k < m; ++k) {
    grid(k) = t(0) + static_cast<double>(k) * T;
    while (j + 2 < n && t(j + 1) < grid(k)) ++j;
    const double w = std::clamp((grid(k) - t(j)) / (t(j + 1) - t(j)), 0.0, 1.0);
    out.row(k) = (1.0 - w) * values.row(j) + w * values.row(j + 1);
  }
  t = std::move(grid);
  values = std::move(out);
}

}  // namespace ambid
