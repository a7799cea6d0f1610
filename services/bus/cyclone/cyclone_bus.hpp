#pragma once
// The Cyclone DDS backend (C API), library ambid_bus_cyclone. No Cyclone header here:
// make_bus.cpp includes this and the Fast DDS backend's header in one translation unit.
#include <memory>
#include <string_view>

#include "services/bus/bus.hpp"

namespace ambid::bus {

std::unique_ptr<Bus> make_cyclone_bus(int domain, std::string_view profile);

}  // namespace ambid::bus
