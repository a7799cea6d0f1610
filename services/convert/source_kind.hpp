#pragma once
// The plant source kind of PlantSourceCommand and PlantSourceState: its names on the command
// line and in configs (sim, replay, rig), and the diagnostics' view of it.
#include <string>
#include <string_view>

#include "diagnostics/estimate.hpp"
#include "services/bus/messages.hpp"

namespace ambid::convert {

// Throws Error naming the text and the known kinds.
bus::SourceKind parse_source_kind(const std::string& text);
std::string_view source_kind_name(bus::SourceKind kind);
diag::Source to_source(bus::SourceKind kind);

}  // namespace ambid::convert
