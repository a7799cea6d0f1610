#pragma once
// IdentifiedModel message -> the diagnostics' window of estimates (the diagnostics daemon's
// side of identified_model.hpp; apart so the identifier's conversions need no diagnostics).
#include "diagnostics/estimate.hpp"
#include "services/bus/messages.hpp"

namespace ambid::convert {

// The monitored physical parameters of the model's plant family (diagnostics/plant_families.hpp)
// as a window; the others (kr1_emf, ...) are left out. Throws Error naming the plant model
// when diagnostics monitors no parameters of its family.
diag::EstimateWindow estimate_window(const bus::IdentifiedModel& model, diag::Source source);

}  // namespace ambid::convert
