#include "diagnostics/audit/audit_rivals.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/error.hpp"
#include "diagnostics/audit/audit_significance.hpp"
#include "diagnostics/audit/audit_whitening.hpp"

namespace ambid::diag {

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
  const NoiseWhitening whitening = fit_noise_whitening(measured - *replays.front(), validation);
  const Eigen::MatrixXd m = whitening.apply(measured);
  std::vector<Eigen::MatrixXd> y;
  for (const Eigen::MatrixXd* replay : replays) y.push_back(whitening.apply(*replay));
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
