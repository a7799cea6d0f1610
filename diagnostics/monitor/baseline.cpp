#include "diagnostics/monitor/baseline.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace ambid::diag {
namespace {

double median(std::vector<double> x) {
  const std::size_t mid = x.size() / 2;
  std::nth_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(mid), x.end());
  const double upper = x[mid];
  if (x.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(mid)));
}

void require_spread(double value, const char* name) {
  if (!(value >= 0.0) || !std::isfinite(value))
    throw Error(std::string("baseline: ") + name + " must be non-negative and finite, got " + std::to_string(value));
}

}  // namespace

std::string_view to_string(BaselineOrigin origin) { return origin == BaselineOrigin::learned ? "learned" : "given"; }

BaselineOrigin parse_baseline_origin(std::string_view text) {
  if (text == "learned") return BaselineOrigin::learned;
  if (text == "given") return BaselineOrigin::given;
  throw Error("unknown baseline origin '" + std::string(text) + "' (expected learned or given)");
}

void Baseline::validate() const {
  if (mean == 0.0 || !std::isfinite(mean))
    throw Error("baseline: mean must be non-zero and finite (changes are relative to it), got " + std::to_string(mean));
  require_spread(extra_spread, "extra spread");
  require_spread(mean_sigma, "mean sigma");
  require_spread(reported_sigma, "reported sigma");
}

double Baseline::sigma_eff(double sigma) const { return std::hypot(std::max(sigma, reported_sigma), extra_spread); }

Baseline given_baseline(double mean, double extra_spread) {
  Baseline b;
  b.mean = mean;
  b.extra_spread = extra_spread;
  b.validate();
  return b;
}

Baseline learn_baseline(std::span<const double> values, std::span<const double> sigmas) {
  if (values.size() != sigmas.size())
    throw Error("baseline: " + std::to_string(values.size()) + " values but " + std::to_string(sigmas.size()) +
                " sigmas");
  if (values.size() < kMinLearningWindows)
    throw InsufficientData("baseline: learning needs at least " + std::to_string(kMinLearningWindows) +
                           " windows, got " + std::to_string(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) throw Error("baseline: value " + std::to_string(i) + " is not finite");
    if (!(sigmas[i] >= 0.0) || !std::isfinite(sigmas[i]))
      throw Error("baseline: sigma " + std::to_string(i) + " must be non-negative and finite, got " +
                  std::to_string(sigmas[i]));
  }
  const double n = static_cast<double>(values.size());
  Baseline b;
  b.origin = BaselineOrigin::learned;
  b.windows = values.size();
  double sum = 0.0;
  for (double v : values) sum += v;
  b.mean = sum / n;
  std::vector<double> abs_dev;
  const double med = median({values.begin(), values.end()});
  for (double v : values) abs_dev.push_back(std::abs(v - med));
  const double observed = 1.4826 * median(abs_dev);
  b.reported_sigma = median({sigmas.begin(), sigmas.end()});
  if (b.reported_sigma == 0.0 && values.size() < kMinSpreadLearningWindows)
    throw InsufficientData(
        "baseline: the estimates report no sigma, so the scatter of the windows is the whole "
        "sigma_eff; learning it needs at least " +
        std::to_string(kMinSpreadLearningWindows) + " windows, got " + std::to_string(values.size()));
  if (b.reported_sigma == 0.0 && !(observed > 0.0))
    throw InsufficientData("baseline: the estimates report no sigma and the " + std::to_string(values.size()) +
                           " windows do not scatter (median absolute deviation 0): no sigma_eff can be learned");
  b.extra_spread = std::sqrt(std::max(0.0, observed * observed - b.reported_sigma * b.reported_sigma));
  b.mean_sigma = std::max(observed, b.reported_sigma) / std::sqrt(n);
  b.validate();
  return b;
}

}  // namespace ambid::diag
