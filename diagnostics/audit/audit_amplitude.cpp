#include "diagnostics/audit/audit_amplitude.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "identifier/frf_welch.hpp"

namespace ambid::diag {
namespace {

// Median and its standard error: 1.2533 sd / sqrt(n / 2), the large-sample value for a normal
// with half the lines independent (Hann windows with half overlap correlate neighbouring lines).
std::pair<double, double> median_and_se(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  const double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  double mean = 0.0, var = 0.0;
  for (double x : v) mean += x / double(n);
  for (double x : v) var += (x - mean) * (x - mean) / double(n - 1);
  return {median, 1.2533 * std::sqrt(2.0 * var / double(n))};
}

AmplitudePart analyse_part(const Experiment& measured, const ReplayedLoop& nominal, const Segment& s,
                           const AmplitudeOptions& o) {
  ident::WelchFrfOptions w;
  w.sample_time = measured.sample_time;
  w.segment_samples = o.segment_samples;
  if (!s.left_out.empty()) w.left_out.assign(s.left_out.begin() + s.begin, s.left_out.begin() + s.end);
  const Eigen::MatrixXd r = measured.r_deviation().middleRows(s.begin, s.size());
  const ident::WelchFrf m = ident::estimate_welch_frf(r, measured.u_deviation().middleRows(s.begin, s.size()),
                                                      measured.y_deviation().middleRows(s.begin, s.size()), w);
  const ident::WelchFrf n =
      ident::estimate_welch_frf(r, nominal.u.middleRows(s.begin, s.size()), nominal.y.middleRows(s.begin, s.size()), w);
  AmplitudePart p;
  p.samples = s;
  p.excitation_rms = std::sqrt(r.squaredNorm() / double(r.size()));
  const Eigen::Index q = m.plant.rows(), k = m.plant.cols();
  p.log_ratio.setZero(q, k);
  p.log_ratio_se.setConstant(q, k, INFINITY);
  p.lines.setZero(q, k);
  for (Eigen::Index i = 0; i < q; ++i)
    for (Eigen::Index j = 0; j < k; ++j) {
      std::vector<double> v;
      for (Eigen::Index l = 0; l < m.plant.lines(); ++l)
        if (m.input_coherence.row(l).minCoeff() >= o.min_coherence &&
            m.plant.variance[std::size_t(l)](i, j) <=
                o.max_relative_variance * std::norm(m.plant.value[std::size_t(l)](i, j)))
          v.push_back(std::log(std::abs(m.plant.value[std::size_t(l)](i, j) / n.plant.value[std::size_t(l)](i, j))));
      p.lines(i, j) = int(v.size());
      if (v.size() >= 3) std::tie(p.log_ratio(i, j), p.log_ratio_se(i, j)) = median_and_se(v);
    }
  return p;
}

}  // namespace

AmplitudeDependence amplitude_dependence(const Experiment& measured, const ReplayedLoop& nominal,
                                         const std::vector<bool>& left_out, const AmplitudeOptions& options) {
  const Eigen::Index N = measured.samples();
  if (nominal.y.rows() != N || nominal.u.rows() != N || options.parts < 2 ||
      (!left_out.empty() && std::ssize(left_out) != N))
    throw Error(
        "audit: amplitude dependence needs the nominal replay of the whole record (and a mask of its samples) and at "
        "least 2 parts");
  AmplitudeDependence out;
  const Eigen::Index length = N / options.parts;
  if (length < 3 * options.segment_samples) {
    out.reason = "parts of " + std::to_string(length) + " samples are shorter than three Welch windows of " +
                 std::to_string(options.segment_samples);
    return out;
  }
  try {
    for (int p = 0; p < options.parts; ++p)
      out.parts.push_back(analyse_part(measured, nominal, {p * length, (p + 1) * length, left_out}, options));
  } catch (const Error& e) {
    out.parts.clear();
    out.reason = std::string("a part's frequency response cannot be estimated: ") + e.what();
    return out;
  }
  for (std::size_t p = 0; p < out.parts.size(); ++p) {
    if (out.parts[p].excitation_rms < out.parts[std::size_t(out.lowest)].excitation_rms) out.lowest = Eigen::Index(p);
    if (out.parts[p].excitation_rms > out.parts[std::size_t(out.highest)].excitation_rms) out.highest = Eigen::Index(p);
  }
  const AmplitudePart &low = out.parts[std::size_t(out.lowest)], &high = out.parts[std::size_t(out.highest)];
  out.spread = low.excitation_rms > 0.0 ? high.excitation_rms / low.excitation_rms : INFINITY;
  if (!(out.spread >= options.min_spread)) {
    out.reason = "the excitation amplitude hardly varies (highest / lowest part rms " + std::to_string(out.spread) +
                 ", at least " + std::to_string(options.min_spread) + " is needed)";
    return out;
  }
  out.determinable = true;
  out.z = (high.log_ratio - low.log_ratio).array() /
          (high.log_ratio_se.array().square() + low.log_ratio_se.array().square()).sqrt();
  out.max_abs_z = out.z.cwiseAbs().maxCoeff();  // a pair without lines has se inf: z 0
  out.dependent = out.max_abs_z > options.z_threshold;
  return out;
}

}  // namespace ambid::diag
