#pragma once
// A Cyclone DDS domain created with an explicit configuration (dds_create_domain), so neither
// CYCLONEDDS_URI nor vendor defaults apply. A domain id exists once per process: participants on
// the same id share it (and must ask for the same configuration); the last one deletes it.
#include <string>

namespace ambid::bus::cyclone {

class DomainRef {
 public:
  // Throws Error when Cyclone refuses the configuration, or when the domain already exists in
  // this process with a different configuration.
  DomainRef(int id, const std::string& config);
  ~DomainRef();
  DomainRef(const DomainRef&) = delete;
  DomainRef& operator=(const DomainRef&) = delete;

 private:
  int id_;
};

}  // namespace ambid::bus::cyclone
