#include "identifier/frequency_domain/frf_levels.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "identifier/frf_welch.hpp"

namespace ambid::ident {
namespace {

// The columns of `m` over `span`, each less its straight line through the span (least squares
// on the orthogonal columns 1 and k - mean k), written into the same rows of `out`.
void detrend_level_span(const Eigen::MatrixXd& m, const SettledSpan& span, Eigen::MatrixXd& out) {
  const Eigen::Index n = span.samples;
  const Eigen::VectorXd k = Eigen::VectorXd::LinSpaced(n, -0.5 * double(n - 1), 0.5 * double(n - 1));
  const double kk = k.squaredNorm();
  for (Eigen::Index c = 0; c < m.cols(); ++c) {
    const Eigen::VectorXd v = m.col(c).segment(span.first, n);
    const double slope = kk > 0.0 ? k.dot(v) / kk : 0.0;
    out.col(c).segment(span.first, n) = v.array() - v.mean() - slope * k.array();
  }
}

double level_span_mean(const Eigen::VectorXd& v, const std::vector<SettledSpan>& spans) {
  double sum = 0.0;
  Eigen::Index n = 0;
  for (const SettledSpan& s : spans) {
    sum += v.segment(s.first, s.samples).sum();
    n += s.samples;
  }
  return sum / double(n);
}

LevelStructuredFit fit_structure_at_level(const Experiment& e, const FrfStructure& structure,
                                          const std::vector<bool>& clamped, const SettledLevel& level) {
  LevelStructuredFit out;
  out.spans = level.spans;
  out.samples = level.samples();
  for (std::size_t c = 0; c < e.y_names.size(); ++c)
    out.operating_point[e.y_names[c]] = level_span_mean(e.y.col(Eigen::Index(c)), level.spans);
  for (std::size_t c = 0; c < e.u_names.size(); ++c)
    out.operating_point[e.u_names[c]] = level_span_mean(e.u.col(Eigen::Index(c)), level.spans);

  Eigen::Index longest = 0;
  for (const SettledSpan& s : level.spans) longest = std::max(longest, s.samples);
  out.segment_samples = 64;
  while (out.segment_samples * 4 <= longest) out.segment_samples *= 2;
  if (out.segment_samples * 2 > longest) {
    out.note = "its longest settled span (" + std::to_string(longest) + " samples) holds no two Welch segments of 64";
    return out;
  }
  const Eigen::Index n = e.samples();
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(n, e.r.cols()), u = Eigen::MatrixXd::Zero(n, e.u.cols()),
                  y = Eigen::MatrixXd::Zero(n, e.y.cols());
  std::vector<bool> left_out(std::size_t(n), true);
  for (const SettledSpan& s : level.spans) {
    detrend_level_span(e.r, s, r);
    detrend_level_span(e.u, s, u);
    detrend_level_span(e.y, s, y);
    for (Eigen::Index k = s.first; k < s.first + s.samples; ++k)
      left_out[std::size_t(k)] = !clamped.empty() && clamped[std::size_t(k)];
  }
  WelchFrfOptions w;
  w.sample_time = e.sample_time;
  w.segment_samples = out.segment_samples;
  w.overlap = 0.75;
  w.first_sample = level.spans.front().first;
  w.left_out = std::move(left_out);
  try {
    const WelchFrf welch = estimate_welch_frf(r, u, y, w);
    out.segments = welch.segments;
    Experiment header = e;  // the structure's start at the level's own point
    header.operating_point = out.operating_point;
    out.fit = fit_structured_frf(header, welch.plant, structure);
  } catch (const Error& err) {
    out.note = err.what();
  }
  return out;
}

// Every fitted level's derived quantities at `point` (through structure.transport) and their
// variances (central differences of derived o transport, J P J'), pooled by inverse variance.
std::optional<PooledStructure> pool_levels_at(const std::vector<LevelStructuredFit>& levels, const FrfStructure& s,
                                              const std::map<std::string, double>& point) {
  std::vector<Eigen::VectorXd> values, variances;
  for (const LevelStructuredFit& l : levels) {
    if (!l.fit || l.fit->covariance.size() == 0) continue;
    const auto at_point = [&](const Eigen::VectorXd& theta) {
      return s.derived(s.transport(theta, l.operating_point, point));
    };
    const Eigen::VectorXd& theta = l.fit->value;
    const Eigen::VectorXd d = at_point(theta);
    Eigen::MatrixXd J(d.size(), theta.size());
    for (Eigen::Index c = 0; c < theta.size(); ++c) {
      const double h = 1e-6 * std::max(std::abs(theta(c)), 1e-12);
      Eigen::VectorXd up = theta, down = theta;
      up(c) += h;
      down(c) -= h;
      J.col(c) = (at_point(up) - at_point(down)) / (2 * h);
    }
    values.push_back(d);
    variances.push_back((J * l.fit->covariance * J.transpose()).diagonal());
  }
  if (values.size() < 2) return std::nullopt;
  PooledStructure out;
  out.levels = int(values.size());
  out.derived_names = s.derived_names;
  const Eigen::Index n = values.front().size();
  out.derived_value.resize(n);
  out.derived_sigma.resize(n);
  out.birge_ratio.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    double weights = 0.0, sum = 0.0;
    for (std::size_t l = 0; l < values.size(); ++l) {
      if (!(variances[l](k) > 0.0)) return std::nullopt;
      weights += 1.0 / variances[l](k);
      sum += values[l](k) / variances[l](k);
    }
    const double mean = sum / weights;
    double chi2 = 0.0;
    for (std::size_t l = 0; l < values.size(); ++l) chi2 += std::pow(values[l](k) - mean, 2) / variances[l](k);
    out.derived_value(k) = mean;
    out.birge_ratio(k) = std::sqrt(chi2 / double(values.size() - 1));
    out.derived_sigma(k) = std::max(1.0, out.birge_ratio(k)) / std::sqrt(weights);
  }
  return out;
}

}  // namespace

LevelStructuredAnalysis fit_structure_per_level(const Experiment& e, const FrfStructure& structure,
                                                const std::vector<bool>& clamped, const SettledLevelOptions& options) {
  if (structure.level_signal.empty()) throw Error("frf per level: the structure names no level signal");
  const auto at = std::find(e.y_names.begin(), e.y_names.end(), structure.level_signal);
  if (at == e.y_names.end())
    throw Error("frf per level: the experiment has no output '" + structure.level_signal + "' to find its levels on");
  if (e.r.cols() == 0) throw Error("frf per level: the experiment records no excitation r");
  if (!clamped.empty() && std::ssize(clamped) != e.samples())
    throw Error("frf per level: the clamp mask has " + std::to_string(clamped.size()) + " entries for " +
                std::to_string(e.samples()) + " samples");
  const Eigen::Index column = at - e.y_names.begin();
  const SettledLevels found = find_settled_levels(e.y.col(column), e.sample_time, options);
  LevelStructuredAnalysis out;
  out.level_signal = structure.level_signal;
  out.merge = found.merge;
  for (const SettledLevel& level : found.levels)
    out.levels.push_back(fit_structure_at_level(e, structure, clamped, level));
  if (std::none_of(out.levels.begin(), out.levels.end(), [](const LevelStructuredFit& l) { return l.fit.has_value(); }))
    throw InsufficientData("frf per level: no settled level of '" + structure.level_signal + "' (" +
                           std::to_string(found.levels.size()) + " found) gave a structured fit" +
                           (out.levels.empty() ? std::string() : ": " + out.levels.front().note));
  try {
    if (structure.transport) out.pooled = pool_levels_at(out.levels, structure, e.operating_point);
  } catch (const Error& err) {  // e.g. an operating point without a value the law needs
    out.pooled_note = err.what();
  }
  const auto op = e.operating_point.find(structure.level_signal);
  if (op == e.operating_point.end()) return out;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t l = 0; l < out.levels.size(); ++l) {
    const double d = std::abs(out.levels[l].operating_point.at(structure.level_signal) - op->second);
    if (out.levels[l].fit && d < out.merge && d < nearest) nearest = d, out.at_operating_point = l;
  }
  return out;
}

}  // namespace ambid::ident
