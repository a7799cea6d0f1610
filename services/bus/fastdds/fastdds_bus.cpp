#include "services/bus/fastdds/fastdds_bus.hpp"

#include "services/bus/fastdds/endpoints.hpp"
#include "services/bus/fastdds/participant.hpp"
#include "services/bus/vendor_bus.hpp"

namespace ambid::bus {

std::unique_ptr<Bus> make_fastdds_bus(int domain, std::string_view profile) {
  using FastBus = VendorBus<fastdds::Participant, fastdds::FastWriter, fastdds::FastReader>;
  return std::make_unique<FastBus>("fastdds", domain, profile);
}

}  // namespace ambid::bus
