#pragma once
// An identified model <-> IdentifiedModel message: the identifier daemon publishes the model of
// a window; the diagnostics daemon takes the monitored physical parameters out of it.
#include <cstdint>
#include <string>

#include "core/experiment.hpp"
#include "diagnostics/estimate.hpp"
#include "identifier/identify_window.hpp"
#include "services/bus/messages.hpp"

namespace ambid::convert {

// The model and estimates `method` identified from `window` (time: its last sample; window: its
// length in seconds).
bus::IdentifiedModel to_message(const ident::WindowIdentification& identified, const Experiment& window,
                                const std::string& plant_id, std::uint64_t seq, const std::string& method);
// The monitored physical parameters of a model (diagnostics/fault_isolation.hpp) as a window;
// the others (kr1_emf, ...) are left out.
diag::EstimateWindow estimate_window(const bus::IdentifiedModel& model, diag::Source source);

}  // namespace ambid::convert
