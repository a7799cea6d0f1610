#include "services/bus/make_bus.hpp"

#include <string>

#include "core/error.hpp"
#include "services/bus/cyclone/cyclone_bus.hpp"
#include "services/bus/fastdds/fastdds_bus.hpp"

namespace ambid::bus {

std::unique_ptr<Bus> make_bus(std::string_view vendor, int domain, std::string_view profile) {
  if (domain < 0 || domain > max_domain) {
    throw Error("DDS domain " + std::to_string(domain) + " is outside 0.." + std::to_string(max_domain));
  }
  if (profile.empty()) throw Error("empty DDS network profile (use \"loopback\" or an XML file)");
  if (vendor == "fastdds") return make_fastdds_bus(domain, profile);
  if (vendor == "cyclone") return make_cyclone_bus(domain, profile);
  throw Error("unknown DDS vendor \"" + std::string(vendor) + "\" (expected fastdds or cyclone)");
}

}  // namespace ambid::bus
