#pragma once
// ISO 14839-3 (active magnetic bearings, evaluation of stability margin): zones of the peak
// of the sensitivity function.
//
// Limits (peak |S| in dB): A/B 9.5, B/C 12, C/D 14.
// Boundary rule (decided here; the standard gives only the limit values): a limit value belongs
// to the WORSE zone — zone A is peak < 9.5 dB, B is 9.5 <= peak < 12, C is 12 <= peak < 14,
// D is peak >= 14. A peak exactly at a limit therefore never passes as the better zone, which
// is the conservative reading for acceptance.
#include <string>

namespace ambid::ident {

enum class IsoZone { A, B, C, D };

struct IsoZoneLimits {
  double ab_db = 9.5;
  double bc_db = 12.0;
  double cd_db = 14.0;
};

// Throws Error when the peak is NaN or the limits are not finite and increasing.
IsoZone iso14839_zone(double peak_db, const IsoZoneLimits& limits = {});

// "A", "B", "C", "D".
std::string to_string(IsoZone zone);

// 20 log10(magnitude); -inf for 0; Error for a negative or NaN magnitude.
double magnitude_db(double magnitude);

}  // namespace ambid::ident
