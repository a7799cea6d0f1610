#include "identifier/time_domain/segment_jackknife.hpp"

#include <cmath>

#include "core/error.hpp"

namespace ambid::ident {

using Index = Eigen::Index;

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
    sigma[name] = std::sqrt((K - 1.0) / K * sum);
  }
  return sigma;
}

}  // namespace ambid::ident
