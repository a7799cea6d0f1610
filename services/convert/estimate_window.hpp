#pragma once
// IdentifiedModel message -> the diagnostics' window of estimates (the diagnostics daemon's
// side of identified_model.hpp; apart so the identifier's conversions need no diagnostics).
#include "diagnostics/estimate.hpp"
#include "services/bus/messages.hpp"

namespace ambid::convert {

// The monitored physical parameters of a model (diagnostics/fault_isolation.hpp) as a window;
// the others (kr1_emf, ...) are left out.
diag::EstimateWindow estimate_window(const bus::IdentifiedModel& model, diag::Source source);

}  // namespace ambid::convert
