#pragma once
// Opens the bus of a vendor chosen by name (--dds fastdds|cyclone). The one place that links
// both backends (library ambid_bus_vendors); code that only handles messages needs bus.hpp or
// messages.hpp and no vendor library.
#include <memory>
#include <string_view>

#include "services/bus/bus.hpp"

namespace ambid::bus {

// vendor: "fastdds" or "cyclone"; domain: 0..max_domain; profile: loopback_profile or an XML
// file (see bus.hpp). Throws Error naming what was wrong.
std::unique_ptr<Bus> make_bus(std::string_view vendor, int domain, std::string_view profile = loopback_profile);

}  // namespace ambid::bus
