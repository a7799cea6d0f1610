#include "services/report/scale.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace ambid::report {

Scale::Scale(double lo, double hi, double pixel_lo, double pixel_hi, bool log)
    : lo_(log && lo > 0.0 ? std::log10(lo) : lo),
      hi_(log && hi > 0.0 ? std::log10(hi) : hi),
      pixel_lo_(pixel_lo),
      pixel_hi_(pixel_hi),
      log_(log) {
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi) || (log && lo <= 0.0)) {
    std::ostringstream message;
    message << "cannot scale the " << (log ? "log " : "") << "range [" << lo << ", " << hi << "]";
    throw Error(message.str());
  }
}

bool Scale::drawable(double value) const { return std::isfinite(value) && (!log_ || value > 0.0); }

double Scale::to_pixel(double value) const {
  const double v = log_ ? std::log10(value) : value;
  return pixel_lo_ + (v - lo_) / (hi_ - lo_) * (pixel_hi_ - pixel_lo_);
}

}  // namespace ambid::report
