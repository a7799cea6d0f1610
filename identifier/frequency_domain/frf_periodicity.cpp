#include "identifier/frequency_domain/frf_periodicity.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "identifier/frequency_domain/frf_dft.hpp"

namespace ambid::ident {
namespace {

// Absolute tolerance of each reference over the span.
Eigen::VectorXd tolerances(const Eigen::MatrixXd& r, Eigen::Index first, Eigen::Index span, double relative) {
  return relative * r.middleRows(first, span).cwiseAbs().colwise().maxCoeff().transpose();
}

// Stops at the first mismatch, so a shift that is not a period costs a few samples only.
bool repeats(const Eigen::MatrixXd& r, Eigen::Index first, Eigen::Index span, Eigen::Index shift,
             const Eigen::VectorXd& tol) {
  for (Eigen::Index n = first; n + shift < first + span; ++n)
    for (Eigen::Index c = 0; c < r.cols(); ++c)
      if (!(std::abs(r(n + shift, c) - r(n, c)) <= tol(c))) return false;
  return true;
}

void check(const Eigen::MatrixXd& r, const PeriodicityOptions& o) {
  if (!r.allFinite()) throw Error("periodicity: the references r are not finite");
  if (!(o.tolerance > 0.0 && o.tolerance < 1.0))
    throw Error("periodicity: tolerance must be in (0, 1), got " + std::to_string(o.tolerance));
  if (!(o.line_threshold > 0.0 && o.line_threshold < 1.0))
    throw Error("periodicity: line_threshold must be in (0, 1), got " + std::to_string(o.line_threshold));
}

}  // namespace

bool repeats_with_shift(const Eigen::MatrixXd& r, Eigen::Index first, Eigen::Index span, Eigen::Index shift,
                        double tolerance) {
  if (first < 0 || span < 0 || first + span > r.rows() || shift < 1)
    throw Error("periodicity: shift " + std::to_string(shift) + " over samples [" + std::to_string(first) + ", " +
                std::to_string(first + span) + ") does not fit a record of " + std::to_string(r.rows()) + " samples");
  return repeats(r, first, span, shift, tolerances(r, first, span, tolerance));
}

Periodicity detect_periodicity(const Eigen::MatrixXd& r, const PeriodicityOptions& o) {
  check(r, o);
  Periodicity out;
  Eigen::Index first = 0, end = r.rows();
  while (first < end && r.row(first).isZero(0.0)) ++first;
  while (end > first && r.row(end - 1).isZero(0.0)) --end;
  out.first_sample = first;
  out.span_samples = end - first;
  const Eigen::VectorXd tol = tolerances(r, first, out.span_samples, o.tolerance);
  for (Eigen::Index L = 1; 2 * L <= out.span_samples; ++L) {
    if (repeats(r, first, out.span_samples, L, tol)) {
      out.period_samples = L;
      break;
    }
  }
  if (!out.periodic()) return out;
  const Eigen::Index N = out.period_samples;
  out.periods = out.span_samples / N;

  std::vector<Eigen::Index> candidates;
  for (Eigen::Index k = 1; 2 * k < N; ++k) candidates.push_back(k);
  out.lines.resize(static_cast<std::size_t>(r.cols()));
  if (candidates.empty()) return out;
  const Eigen::MatrixXd amplitude = period_phasors(r, first, N, 1, candidates).front().cwiseAbs();
  for (Eigen::Index c = 0; c < r.cols(); ++c) {
    const double strongest = amplitude.col(c).maxCoeff();
    if (!(strongest > 0.0)) continue;
    for (std::size_t i = 0; i < candidates.size(); ++i)
      if (amplitude(static_cast<Eigen::Index>(i), c) >= o.line_threshold * strongest)
        out.lines[static_cast<std::size_t>(c)].push_back(candidates[i]);
  }
  for (const auto& channel : out.lines) out.all_lines.insert(out.all_lines.end(), channel.begin(), channel.end());
  std::sort(out.all_lines.begin(), out.all_lines.end());
  out.all_lines.erase(std::unique(out.all_lines.begin(), out.all_lines.end()), out.all_lines.end());
  return out;
}

}  // namespace ambid::ident
