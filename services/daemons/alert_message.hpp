#pragma once
// Diagnostics alerts and estimate windows <-> bus messages.
#include <optional>
#include <string>
#include <vector>

#include "diagnostics/alert.hpp"
#include "diagnostics/estimate.hpp"
#include "services/bus/messages.hpp"

namespace ambid::daemons {

// channel: 0 when the alert has none; baseline: 0 while it is being learned.
bus::Alert to_message(const diag::Alert& alert);
// The monitored physical parameters of a model (diagnostics/fault_isolation.hpp) as a window;
// the others (kr1_emf, ...) are left out.
diag::EstimateWindow estimate_window(const bus::IdentifiedModel& model, diag::Source source);
diag::Source to_source(bus::SourceKind kind);
std::string_view level_name(bus::AlertLevel level);  // "OK", "WARN", "ERROR", "STALE"

}  // namespace ambid::daemons
