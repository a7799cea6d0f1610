#pragma once
// diag::Alert -> Alert message, and the operator's name of an alert level.
#include <string_view>

#include "diagnostics/alert.hpp"
#include "services/bus/messages.hpp"

namespace ambid::convert {

// channel: 0 when the alert has none; baseline: 0 while it is being learned; the message is cut
// to the bound of its field.
bus::Alert to_message(const diag::Alert& alert);
std::string_view level_name(bus::AlertLevel level);  // "OK", "WARN", "ERROR", "STALE"

}  // namespace ambid::convert
