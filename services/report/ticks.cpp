#include "services/report/ticks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/error.hpp"

namespace ambid::report {
namespace {

void check_bounds(double lo, double hi, bool log) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi) {
    std::ostringstream message;
    message << "axis range [" << lo << ", " << hi << "] is not a finite, ordered interval";
    throw Error(message.str());
  }
  if (log && lo <= 0.0) {
    std::ostringstream message;
    message << "log axis range [" << lo << ", " << hi << "] must be positive";
    throw Error(message.str());
  }
}

// 1, 2 or 5 times a power of ten, the smallest such step giving at most target_count intervals.
double nice_step(double span, int target_count) {
  const double raw = span / std::max(1, target_count);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double factor : {1.0, 2.0, 5.0}) {
    if (factor * magnitude >= raw * (1.0 - 1e-9)) return factor * magnitude;
  }
  return 10.0 * magnitude;
}

std::string linear_label(double value, double step) {
  if (std::abs(value) < step * 1e-6) value = 0.0;  // no "-0" or "1e-17"
  char text[32];
  const double magnitude = std::max(std::abs(value), step);
  if (magnitude >= 1e6 || step < 1e-4) {
    std::snprintf(text, sizeof text, "%g", value);
  } else {
    const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
  }
  return text;
}

std::string log_label(double value) {
  const double exponent = std::log10(value);
  char text[32];
  if (exponent >= -3.5 && exponent < 5.5) {
    std::snprintf(text, sizeof text, "%g", value);
  } else if (std::abs(exponent - std::round(exponent)) < 1e-9) {
    std::snprintf(text, sizeof text, "1e%d", static_cast<int>(std::round(exponent)));
  } else {
    std::snprintf(text, sizeof text, "%.0e", value);
  }
  return text;
}

// A zero-width span becomes a small interval around the value.
void widen(double& lo, double& hi) {
  if (hi > lo) return;
  const double half = lo == 0.0 ? 1.0 : 0.1 * std::abs(lo);
  lo -= half;
  hi += half;
}

Ticks linear_ticks_between(double lo, double hi, double step, double first) {
  Ticks ticks;
  ticks.range = {lo, hi};
  const double tolerance = 1e-9 * step;
  for (double value = first; value <= hi + tolerance; value += step) {
    ticks.major.push_back(value);
    ticks.labels.push_back(linear_label(value, step));
  }
  return ticks;
}

}  // namespace

Ticks linear_ticks(double lo, double hi, int target_count) {
  check_bounds(lo, hi, false);
  widen(lo, hi);
  const double step = nice_step(hi - lo, target_count);
  const double first = std::floor(lo / step + 1e-9) * step;
  const double last = std::ceil(hi / step - 1e-9) * step;
  return linear_ticks_between(first, last, step, first);
}

Ticks linear_ticks_fixed(double lo, double hi, int target_count) {
  check_bounds(lo, hi, false);
  if (hi == lo) throw Error("fixed axis range has zero width at " + std::to_string(lo));
  const double step = nice_step(hi - lo, target_count);
  return linear_ticks_between(lo, hi, step, std::ceil(lo / step - 1e-9) * step);
}

Ticks linear_ticks_with_step(double lo, double hi, double step) {
  check_bounds(lo, hi, false);
  if (!(step > 0.0) || !std::isfinite(step) || (hi - lo) / step > 1000.0) {
    std::ostringstream message;
    message << "tick step " << step << " does not fit the axis range [" << lo << ", " << hi << "]";
    throw Error(message.str());
  }
  return linear_ticks_between(lo, hi, step, std::ceil(lo / step - 1e-9) * step);
}

Ticks log_ticks(double lo, double hi) {
  check_bounds(lo, hi, true);
  int first = static_cast<int>(std::floor(std::log10(lo) + 1e-9));
  int last = static_cast<int>(std::ceil(std::log10(hi) - 1e-9));
  if (last == first) ++last;
  return log_ticks_fixed(std::pow(10.0, first), std::pow(10.0, last));
}

Ticks log_ticks_fixed(double lo, double hi) {
  check_bounds(lo, hi, true);
  if (hi == lo) throw Error("fixed log axis range has zero width at " + std::to_string(lo));
  Ticks ticks;
  ticks.range = {lo, hi};
  const double tolerance = 1e-9;
  const int first = static_cast<int>(std::floor(std::log10(lo) + tolerance));
  const int last = static_cast<int>(std::ceil(std::log10(hi) - tolerance));
  // Label every decade, or every n-th one when there are many.
  const int decade_step = std::max(1, (last - first + 9) / 10);
  const auto inside = [&](double value) { return value >= lo * (1.0 - tolerance) && value <= hi * (1.0 + tolerance); };
  for (int exponent = first; exponent <= last; ++exponent) {
    const double decade = std::pow(10.0, exponent);
    if (inside(decade) && exponent % decade_step == 0) {
      ticks.major.push_back(decade);
    } else if (inside(decade)) {
      ticks.minor.push_back(decade);
    }
    for (int digit = 2; digit <= 9; ++digit) {
      if (inside(digit * decade)) ticks.minor.push_back(digit * decade);
    }
  }
  // Less than a decade shown: label 2 and 5 times the decades too, so the axis can be read.
  if (ticks.major.size() < 2) {
    std::vector<double> minor;
    for (const double value : ticks.minor) {
      const double digit = value / std::pow(10.0, std::floor(std::log10(value) + tolerance));
      const bool labelled = std::abs(digit - 2.0) < 1e-6 || std::abs(digit - 5.0) < 1e-6;
      (labelled ? ticks.major : minor).push_back(value);
    }
    ticks.minor = minor;
    std::sort(ticks.major.begin(), ticks.major.end());
  }
  for (const double value : ticks.major) ticks.labels.push_back(log_label(value));
  return ticks;
}

}  // namespace ambid::report
