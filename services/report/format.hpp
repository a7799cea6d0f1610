#pragma once
// Short human-readable numbers for titles and labels ("455", "0.0123", "1.2e+06").
#include <string>

namespace ambid::report {

// `significant` significant digits (printf %g): no trailing zeros, exponent only when needed.
std::string format_number(double value, int significant = 3);

}  // namespace ambid::report
