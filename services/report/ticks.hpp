#pragma once
// Axis ranges and tick positions. Linear axes get "nice" steps (1, 2 or 5 times a power of
// ten); log axes get one major tick per decade and minor ticks at 2..9 times each decade.
#include <string>
#include <vector>

#include "services/report/figure.hpp"

namespace ambid::report {

struct Ticks {
  Range range;                      // the axis extent, rounded out so that it begins and ends on ticks
  std::vector<double> major;        // labelled
  std::vector<double> minor;        // grid only (log axes)
  std::vector<std::string> labels;  // one per major tick
};

// Ticks for data spanning [lo, hi] (lo <= hi, finite; > 0 for log). A zero-width span is
// widened around the value. Throws ambid::Error on a non-finite or (log) non-positive bound.
Ticks linear_ticks(double lo, double hi, int target_count = 6);
Ticks log_ticks(double lo, double hi);

// Ticks at the multiples of `step` (> 0) in [lo, hi], which is kept exactly.
Ticks linear_ticks_with_step(double lo, double hi, double step);

// Like the above, but keeps [lo, hi] exactly (a user-given range) and only places ticks inside.
Ticks linear_ticks_fixed(double lo, double hi, int target_count = 6);
Ticks log_ticks_fixed(double lo, double hi);

}  // namespace ambid::report
