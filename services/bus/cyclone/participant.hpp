#pragma once
// One Cyclone DDS participant and the topics created on it so far. Endpoints hold it by
// shared_ptr; the last one out deletes it (and with it everything it contains).
#include <map>
#include <mutex>
#include <string>
#include <string_view>

#include <dds/dds.h>

#include "services/bus/cyclone/convert.hpp"
#include "services/bus/cyclone/domain.hpp"
#include "services/bus/topics.hpp"

namespace ambid::bus::cyclone {

class Participant {
 public:
  // profile: loopback_profile (deploy/dds/cyclone-loopback.xml, compiled in) or a Cyclone XML
  // configuration file. Throws Error when Cyclone refuses.
  Participant(int domain, std::string_view profile);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  dds_entity_t handle() const { return participant_; }

  // The topic that carries Message, created on first use.
  template <class Message>
  dds_entity_t topic() {
    return topic(Topic<Message>::name, Generated<Message>::descriptor);
  }

 private:
  dds_entity_t topic(const char* name, const dds_topic_descriptor_t* descriptor);

  DomainRef domain_;  // outlives the participant
  dds_entity_t participant_;
  std::mutex mutex_;
  std::map<std::string, dds_entity_t, std::less<>> topics_;
};

}  // namespace ambid::bus::cyclone
