#pragma once
// An identified model -> IdentifiedModel message: the identifier daemon publishes the model of
// a window (the diagnostics daemon's side: estimate_window.hpp).
#include <cstdint>
#include <string>

#include "core/experiment.hpp"
#include "identifier/identify_window.hpp"
#include "services/bus/messages.hpp"

namespace ambid::convert {

// The model and estimates `method` identified from `window` (time: its last sample; window: its
// length in seconds).
bus::IdentifiedModel to_message(const ident::WindowIdentification& identified, const Experiment& window,
                                const std::string& plant_id, std::uint64_t seq, const std::string& method);
}  // namespace ambid::convert
