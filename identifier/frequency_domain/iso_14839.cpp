#include "identifier/iso_14839.hpp"

#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace ambid::ident {

IsoZone iso14839_zone(double peak_db, const IsoZoneLimits& limits) {
  if (std::isnan(peak_db)) throw Error("ISO 14839-3 zone: the peak sensitivity is NaN");
  if (!std::isfinite(limits.ab_db) || !std::isfinite(limits.bc_db) || !std::isfinite(limits.cd_db) ||
      !(limits.ab_db < limits.bc_db && limits.bc_db < limits.cd_db))
    throw Error("ISO 14839-3 zone: limits must be finite and increasing, got " + std::to_string(limits.ab_db) + ", " +
                std::to_string(limits.bc_db) + ", " + std::to_string(limits.cd_db) + " dB");
  if (peak_db < limits.ab_db) return IsoZone::A;
  if (peak_db < limits.bc_db) return IsoZone::B;
  if (peak_db < limits.cd_db) return IsoZone::C;
  return IsoZone::D;
}

std::string to_string(IsoZone zone) {
  switch (zone) {
    case IsoZone::A:
      return "A";
    case IsoZone::B:
      return "B";
    case IsoZone::C:
      return "C";
    case IsoZone::D:
      return "D";
  }
  return "?";
}

double magnitude_db(double magnitude) {
  if (!(magnitude >= 0.0)) throw Error("magnitude in dB: magnitude must be >= 0, got " + std::to_string(magnitude));
  if (magnitude == 0.0) return -std::numeric_limits<double>::infinity();
  return 20.0 * std::log10(magnitude);
}

}  // namespace ambid::ident
