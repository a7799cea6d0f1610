#include "services/bus/cyclone/participant.hpp"

#include <filesystem>

#include "core/error.hpp"
#include "services/bus/bus.hpp"
#include "services/bus/cyclone/loopback_config.hpp"

namespace ambid::bus::cyclone {
namespace {

std::string config(std::string_view profile) {
  if (profile == loopback_profile) return loopback_config;
  const std::filesystem::path path(profile);
  if (!std::filesystem::is_regular_file(path)) {
    throw Error("no Cyclone DDS configuration file " + path.string());
  }
  return "file://" + std::filesystem::absolute(path).string();
}

}  // namespace

Participant::Participant(int domain, std::string_view profile)
    : domain_(domain, config(profile)),
      participant_(dds_create_participant(static_cast<dds_domainid_t>(domain), nullptr, nullptr)) {
  if (participant_ < 0) {
    throw Error("Cyclone DDS refused to create a participant on domain " + std::to_string(domain) + ": " +
                dds_strretcode(participant_));
  }
}

Participant::~Participant() { dds_delete(participant_); }

dds_entity_t Participant::topic(const char* name, const dds_topic_descriptor_t* descriptor) {
  const std::lock_guard lock(mutex_);
  if (auto it = topics_.find(name); it != topics_.end()) return it->second;
  const dds_entity_t topic = dds_create_topic(participant_, descriptor, name, nullptr, nullptr);
  if (topic < 0) {
    throw Error(std::string("Cyclone DDS refused to create the topic ") + name + ": " + dds_strretcode(topic));
  }
  topics_.emplace(name, topic);
  return topic;
}

}  // namespace ambid::bus::cyclone
