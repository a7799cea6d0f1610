#pragma once
// A frequency-response analysis (identifier/frf_analysis.hpp) as a FrequencyResponse message:
// the plant FRF of every output/input pair, the input-sensitivity peaks with their ISO 14839-3
// zones, and the worst zone.
#include <cstdint>
#include <string>

#include "identifier/frf_analysis.hpp"
#include "services/bus/messages.hpp"

namespace ambid::convert {

// Throws Error when the FRF has more lines or values than the message bounds allow.
bus::FrequencyResponse to_message(const ident::FrfReport& report, const std::string& plant_id, std::uint64_t seq,
                                  double time);

}  // namespace ambid::convert
