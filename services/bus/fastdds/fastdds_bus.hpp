#pragma once
// The Fast DDS backend (C++ API), library ambid_bus_fastdds. No Fast DDS header here:
// make_bus.cpp includes this and the Cyclone backend's header in one translation unit.
#include <memory>
#include <string_view>

#include "services/bus/bus.hpp"

namespace ambid::bus {

std::unique_ptr<Bus> make_fastdds_bus(int domain, std::string_view profile);

}  // namespace ambid::bus
