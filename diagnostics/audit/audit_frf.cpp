#include "diagnostics/audit/audit_frf.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "identifier/frf_welch.hpp"

namespace ambid::diag {
namespace {

ident::Frf keep_lines(const ident::Frf& frf, const std::vector<Eigen::Index>& lines) {
  ident::Frf out;
  out.frequency_hz.resize(Eigen::Index(lines.size()));
  for (std::size_t k = 0; k < lines.size(); ++k) {
    out.frequency_hz[Eigen::Index(k)] = frf.frequency_hz[lines[k]];
    out.value.push_back(frf.value[std::size_t(lines[k])]);
    if (frf.has_variance()) out.variance.push_back(frf.variance[std::size_t(lines[k])]);
  }
  return out;
}

ident::Frf ratio(const ident::Frf& numerator, const ident::Frf& denominator) {
  ident::Frf out;
  out.frequency_hz = numerator.frequency_hz;
  for (std::size_t k = 0; k < numerator.value.size(); ++k)
    out.value.push_back(numerator.value[k].cwiseQuotient(denominator.value[k]));
  return out;
}

}  // namespace

AuditFrfs audit_frfs(const Experiment& measured, const ReplayedLoop& nominal, const ReplayedLoop& extended,
                     const Segment& segment, double min_coherence) {
  ident::WelchFrfOptions o;
  o.sample_time = measured.sample_time;
  o.segment_samples = std::min<Eigen::Index>(1024, segment.size() / 3);
  if (!segment.left_out.empty())  // Welch skips the segments holding a sample where a clamp acted
    o.left_out.assign(segment.left_out.begin() + segment.begin, segment.left_out.begin() + segment.end);
  const Eigen::MatrixXd r = measured.r_deviation().middleRows(segment.begin, segment.size());
  auto estimate = [&](const Eigen::MatrixXd& u, const Eigen::MatrixXd& y) {
    return ident::estimate_welch_frf(r, u.middleRows(segment.begin, segment.size()),
                                     y.middleRows(segment.begin, segment.size()), o);
  };
  AuditFrfs out;
  try {
    const ident::WelchFrf m = estimate(measured.u_deviation(), measured.y_deviation());
    const ident::WelchFrf n = estimate(nominal.u, nominal.y);
    const ident::WelchFrf x = estimate(extended.u, extended.y);
    std::vector<Eigen::Index> excited;
    for (Eigen::Index k = 0; k < m.plant.lines(); ++k)
      if (m.input_coherence.row(k).minCoeff() >= min_coherence) excited.push_back(k);
    if (excited.empty()) return out;
    out.measured = keep_lines(m.plant, excited);
    out.nominal = keep_lines(n.plant, excited);
    out.extended = keep_lines(x.plant, excited);
    out.ratio_nominal = ratio(out.measured, out.nominal);
    out.ratio_extended = ratio(out.measured, out.extended);
    out.loop_measured = m.output_from_reference;
    out.loop_nominal = n.output_from_reference;
    out.loop_extended = x.output_from_reference;
  } catch (const Error&) {
    return {};  // too short for Welch averaging, or a singular line: no frequency view
  }
  return out;
}

std::vector<Eigen::Index> determined_lines(const AuditFrfs& frfs, Eigen::Index i, Eigen::Index j,
                                           double max_relative_variance) {
  std::vector<Eigen::Index> lines;
  if (!frfs.measured.has_variance()) return lines;
  for (Eigen::Index k = 0; k < frfs.measured.lines(); ++k)
    if (frfs.measured.variance[std::size_t(k)](i, j) <=
        max_relative_variance * std::norm(frfs.measured.value[std::size_t(k)](i, j)))
      lines.push_back(k);
  return lines;
}

}  // namespace ambid::diag
