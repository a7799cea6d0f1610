#include "identifier/frequency_domain/settled_levels.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace ambid::ident {
namespace {

void check_settled_level_options(const Eigen::VectorXd& signal, double sample_time, const SettledLevelOptions& o) {
  const std::string who = "settled levels: ";
  if (!(sample_time > 0.0) || !std::isfinite(sample_time))
    throw Error(who + "sample time must be > 0, got " + std::to_string(sample_time));
  if (!(o.window > 0.0) || !(o.step >= 0.0) || !(o.settle >= 0.0) || !(o.merge >= 0.0) || o.min_samples < 1)
    throw Error(who + "window must be > 0, step, settle and merge >= 0, min_samples >= 1");
  if (!signal.allFinite()) throw Error(who + "the signal has a non-finite sample");
}

// The sample of the largest |difference of means| in each run where it exceeds step / 2,
// kept when that largest difference reaches step.
std::vector<Eigen::Index> settled_step_samples(const Eigen::VectorXd& s, Eigen::Index w, double step) {
  const Eigen::Index n = s.size();
  Eigen::VectorXd prefix(n + 1);
  prefix(0) = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) prefix(k + 1) = prefix(k) + s(k);
  std::vector<Eigen::Index> steps;
  Eigen::Index best = -1;
  double best_size = 0.0;
  for (Eigen::Index k = w; k + w <= n; ++k) {
    const double d = std::abs((prefix(k + w) - prefix(k)) - (prefix(k) - prefix(k - w))) / double(w);
    if (d > step / 2) {
      if (d > best_size) best_size = d, best = k;
      continue;
    }
    if (best >= 0 && best_size >= step) steps.push_back(best);
    best = -1;
    best_size = 0.0;
  }
  if (best >= 0 && best_size >= step) steps.push_back(best);
  return steps;
}

}  // namespace

Eigen::Index SettledLevel::samples() const {
  Eigen::Index n = 0;
  for (const SettledSpan& s : spans) n += s.samples;
  return n;
}

SettledLevels find_settled_levels(const Eigen::VectorXd& signal, double sample_time, const SettledLevelOptions& o) {
  check_settled_level_options(signal, sample_time, o);
  const Eigen::Index n = signal.size();
  const Eigen::Index w = std::max<Eigen::Index>(2, std::lround(o.window / sample_time));
  const Eigen::Index settle = std::lround(o.settle / sample_time);
  SettledLevels out;
  if (o.step > 0.0) {
    out.step = o.step;
  } else if (n > 0) {
    Eigen::VectorXd magnitude = signal.cwiseAbs();
    std::nth_element(magnitude.data(), magnitude.data() + n / 2, magnitude.data() + n);
    out.step = 0.02 * magnitude(n / 2);
  }
  out.merge = o.merge > 0.0 ? o.merge : out.step / 2;
  out.steps = out.step > 0.0 ? settled_step_samples(signal, w, out.step) : std::vector<Eigen::Index>{};

  // The settled span of every visit, then the visits gathered into levels by their means.
  std::vector<Eigen::Index> bounds{0};
  bounds.insert(bounds.end(), out.steps.begin(), out.steps.end());
  bounds.push_back(n);
  for (std::size_t v = 0; v + 1 < bounds.size(); ++v) {
    const Eigen::Index first = bounds[v] + settle;
    const Eigen::Index end = v + 2 < bounds.size() ? bounds[v + 1] - w : n;
    if (end - first < 2) continue;
    const SettledSpan span{first, end - first};
    const double mean = signal.segment(first, span.samples).mean();
    auto level = std::find_if(out.levels.begin(), out.levels.end(),
                              [&](const SettledLevel& l) { return std::abs(l.mean - mean) < out.merge; });
    if (level == out.levels.end()) {
      out.levels.push_back(SettledLevel{mean, {span}});
      continue;
    }
    const double before = double(level->samples());
    level->spans.push_back(span);
    level->mean = (level->mean * before + mean * double(span.samples)) / (before + double(span.samples));
  }
  std::erase_if(out.levels, [&](const SettledLevel& l) { return l.samples() < o.min_samples; });
  return out;
}

}  // namespace ambid::ident
