#pragma once
// The names of the plant source kinds on the command line and in configs: sim, replay, rig.
#include <string>
#include <string_view>

#include "services/bus/messages.hpp"

namespace ambid::daemons {

// Throws Error naming the text and the known kinds.
bus::SourceKind parse_source_kind(const std::string& text);
std::string_view source_kind_name(bus::SourceKind kind);

}  // namespace ambid::daemons
