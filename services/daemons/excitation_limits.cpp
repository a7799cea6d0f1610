#include "services/daemons/excitation_limits.hpp"

#include <algorithm>
#include <vector>

namespace ambid::daemons {

std::string excitation_violation(const bus::ExcitationCommand& c, const ExcitationLimits& limits) {
  static const std::vector<std::string> kinds{"prbs", "multisine", "chirp", "stepped_sine", "none"};
  if (std::find(kinds.begin(), kinds.end(), c.kind) == kinds.end())
    return "unknown excitation kind '" + c.kind.substr(0, bus::limits::name_length) +
           "' (known: prbs, multisine, chirp, stepped_sine, none)";
  if (!(c.amplitude >= 0 && c.amplitude <= limits.max_amplitude))
    return "amplitude " + std::to_string(c.amplitude) + " V outside 0.." + std::to_string(limits.max_amplitude) + " V";
  for (double f : c.frequencies)
    if (!(f > 0 && f <= limits.max_frequency))
      return "frequency " + std::to_string(f) + " Hz outside (0, " + std::to_string(limits.max_frequency) + "] Hz";
  return {};
}

ExcitationRequest excitation_request(const bus::ExcitationCommand& c) {
  if (c.frequencies.empty()) return {c.kind, c.amplitude, 0.0, 0.0};
  const auto [lo, hi] = std::minmax_element(c.frequencies.begin(), c.frequencies.end());
  return {c.kind, c.amplitude, *lo, *hi};
}

}  // namespace ambid::daemons
