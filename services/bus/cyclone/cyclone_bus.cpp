#include "services/bus/cyclone/cyclone_bus.hpp"

#include "services/bus/cyclone/endpoints.hpp"
#include "services/bus/cyclone/participant.hpp"
#include "services/bus/vendor_bus.hpp"

namespace ambid::bus {

std::unique_ptr<Bus> make_cyclone_bus(int domain, std::string_view profile) {
  using CycloneBus = VendorBus<cyclone::Participant, cyclone::CycloneWriter, cyclone::CycloneReader>;
  return std::make_unique<CycloneBus>("cyclone", domain, profile);
}

}  // namespace ambid::bus
