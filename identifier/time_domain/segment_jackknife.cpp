#include "identifier/time_domain/segment_jackknife.hpp"

#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace ambid::ident {

using Index = Eigen::Index;

namespace {

// P(|T| <= x), T Student's t with dof >= 1 degrees of freedom (A&S 26.7.3 odd, 26.7.4 even).
double student_t_two_sided(double x, int dof) {
  const double theta = std::atan(x / std::sqrt(double(dof))), c2 = std::cos(theta) * std::cos(theta);
  double term = 1.0, sum = 1.0;  // term k: the product of the series' ratios times cos^(2k) theta
  if (dof % 2 == 0) {
    for (int k = 1; 2 * k <= dof - 2; ++k) sum += term *= c2 * double(2 * k - 1) / double(2 * k);
    return std::sin(theta) * sum;
  }
  if (dof == 1) return 2.0 * theta / std::numbers::pi;
  for (int k = 1; 2 * k + 1 <= dof - 2; ++k) sum += term *= c2 * double(2 * k) / double(2 * k + 1);
  return 2.0 / std::numbers::pi * (theta + std::sin(theta) * std::cos(theta) * sum);
}

// Two-sided coverage of +-2 standard errors of a normal error: erf(sqrt(2)).
const double kTwoSigmaCoverage = std::erf(std::sqrt(2.0));

}  // namespace

double student_t_two_sided_quantile(double probability, int dof) {
  if (dof < 1 || !(probability > 0.0 && probability < 1.0))
    throw Error("Student t quantile: needs dof >= 1 and 0 < probability < 1, got dof " + std::to_string(dof) +
                ", probability " + std::to_string(probability));
  double lo = 0.0, hi = 1.0;
  while (student_t_two_sided(hi, dof) < probability) hi *= 2.0;
  for (int k = 0; k < 200 && hi - lo > 1e-13 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (student_t_two_sided(mid, dof) < probability ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

LeaveOneSegmentOut experiment_without_segment(const Experiment& e, Index segment, Index segments) {
  if (segments < 2 || segment < 0 || segment >= segments)
    throw Error("jackknife: segment " + std::to_string(segment) + " of " + std::to_string(segments) +
                " (need 0 <= segment < segments, segments >= 2)");
  const Index N = e.samples(), length = N / segments;
  if (length < 2)
    throw InsufficientData("jackknife: " + std::to_string(N) + " samples cannot be cut into " +
                           std::to_string(segments) + " segments");
  // Segment i is [i length, (i + 1) length); the last one takes the remainder.
  const Index begin = segment * length, end = segment + 1 == segments ? N : begin + length;
  const Index kept = N - (end - begin);
  auto without = [&](const Eigen::MatrixXd& m) {
    if (m.rows() == 0) return m;
    Eigen::MatrixXd out(kept, m.cols());
    out << m.topRows(begin), m.bottomRows(N - end);
    return out;
  };
  Experiment out = e;
  out.y = without(e.y);
  out.u = without(e.u);
  out.r = without(e.r);
  out.t = e.t(0) + e.sample_time * Eigen::VectorXd::LinSpaced(kept, 0.0, double(kept - 1)).array();
  return {out, begin > 0 && end < N ? begin : 0};
}

std::map<std::string, double> jackknife_sigma(const std::vector<std::map<std::string, double>>& estimates) {
  if (estimates.size() < 2) throw Error("jackknife: needs at least 2 leave-one-out estimates");
  const double K = double(estimates.size());
  const double widen = student_t_two_sided_quantile(kTwoSigmaCoverage, int(estimates.size()) - 1) / 2.0;
  std::map<std::string, double> sigma;
  for (const auto& [name, unused] : estimates.front()) {
    (void)unused;
    double mean = 0.0;
    for (const auto& e : estimates) {
      const auto it = e.find(name);
      if (it == e.end() || e.size() != estimates.front().size())
        throw Error("jackknife: the leave-one-out estimates do not have the same keys (" + name + ")");
      mean += it->second / K;
    }
    double sum = 0.0;
    for (const auto& e : estimates) sum += (e.at(name) - mean) * (e.at(name) - mean);
    sigma[name] = widen * std::sqrt((K - 1.0) / K * sum);
  }
  return sigma;
}

}  // namespace ambid::ident
