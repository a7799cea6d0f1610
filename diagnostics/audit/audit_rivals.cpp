#include "diagnostics/audit/audit_rivals.hpp"

#include <algorithm>
#include <vector>

#include <Eigen/Core>

#include "core/error.hpp"
#include "diagnostics/audit/audit_significance.hpp"
#include "diagnostics/audit/audit_whitening.hpp"

namespace ambid::diag {

RivalChoice choose_among_rivals(const Eigen::MatrixXd& measured, const std::vector<const Eigen::MatrixXd*>& replays,
                                const Segment& validation, Eigen::Index covariance_lags, double margin) {
  if (replays.empty()) throw Error("audit: no finding to choose among");
  const auto n = Eigen::Index(replays.size());
  RivalChoice c;
  c.z = Eigen::MatrixXd::Zero(n, n);
  const NoiseWhitening whitening = fit_noise_whitening(measured - *replays.front(), validation);
  const Eigen::MatrixXd m = whitening.apply(measured);
  std::vector<Eigen::MatrixXd> y;
  for (const Eigen::MatrixXd* replay : replays) y.push_back(whitening.apply(*replay));
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
