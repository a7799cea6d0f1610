#pragma once
// An identified model <-> IdentifiedModel message: the identifier daemon publishes the model of
// a window; the diagnostics daemon takes the monitored physical parameters out of it.
#include <cstdint>
#include <string>

#include "core/experiment.hpp"
#include "core/model_file.hpp"
#include "diagnostics/estimate.hpp"
#include "services/bus/messages.hpp"

namespace ambid::convert {

// The model `method` identified from `window` (time: its last sample; window: its length in
// seconds). Sigmas the method does not report are 0; throws Error when it reports some but not
// all of them.
bus::IdentifiedModel to_message(const Model& model, const Experiment& window, const std::string& plant_id,
                                std::uint64_t seq, const std::string& method);
// The monitored physical parameters of a model (diagnostics/fault_isolation.hpp) as a window;
// the others (kr1_emf, ...) are left out.
diag::EstimateWindow estimate_window(const bus::IdentifiedModel& model, diag::Source source);

}  // namespace ambid::convert
