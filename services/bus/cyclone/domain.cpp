#include "services/bus/cyclone/domain.hpp"

#include <map>
#include <mutex>

#include <dds/dds.h>

#include "core/error.hpp"

namespace ambid::bus::cyclone {
namespace {

struct Domain {
  dds_entity_t handle;
  std::string config;
  int users;
};

std::mutex registry_mutex;
std::map<int, Domain> registry;

}  // namespace

DomainRef::DomainRef(int id, const std::string& config) : id_(id) {
  const std::lock_guard lock(registry_mutex);
  if (auto it = registry.find(id); it != registry.end()) {
    if (it->second.config != config) {
      throw Error("Cyclone DDS domain " + std::to_string(id) +
                  " already exists in this process with another configuration");
    }
    ++it->second.users;
    return;
  }
  const dds_entity_t handle = dds_create_domain(static_cast<dds_domainid_t>(id), config.c_str());
  if (handle < 0) {
    throw Error("Cyclone DDS refused to create domain " + std::to_string(id) + ": " + dds_strretcode(handle));
  }
  registry.emplace(id, Domain{handle, config, 1});
}

DomainRef::~DomainRef() {
  const std::lock_guard lock(registry_mutex);
  auto it = registry.find(id_);
  if (--it->second.users == 0) {
    dds_delete(it->second.handle);
    registry.erase(it);
  }
}

}  // namespace ambid::bus::cyclone
