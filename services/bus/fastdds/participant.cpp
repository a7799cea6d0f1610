#include "services/bus/fastdds/participant.hpp"

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <memory>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include "core/error.hpp"
#include "services/bus/bus.hpp"

namespace ambid::bus::fastdds {
namespace {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;

// Participants per domain reachable through the initial peer 127.0.0.1 (ports of participant
// ids 0..n-1); deploy/dds/cyclone-loopback.xml has MaxAutoParticipantIndex n - 1.
constexpr std::uint32_t max_participants = 32;

// Whether nobody on this host holds UDP port `port` of 127.0.0.1.
bool port_free(int port) {
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return false;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const bool bound = bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
  close(fd);
  return bound;
}

// The lowest participant id whose unicast ports (7410 / 7411 + 250 domain + 2 id) are free, as
// Cyclone's ParticipantIndex auto picks. Fast DDS would count ids up for the life of the process,
// out of the range that peers probe, after max_participants participants.
std::uint32_t free_participant_id(int domain) {
  for (std::uint32_t id = 0; id < max_participants; ++id) {
    const int port = 7410 + 250 * domain + 2 * static_cast<int>(id);
    if (port_free(port) && port_free(port + 1)) return id;
  }
  throw Error("no free Fast DDS participant id on domain " + std::to_string(domain) + ": " +
              std::to_string(max_participants) + " participants run on this host");
}

// UDP on 127.0.0.1 only, no multicast, unicast discovery through the well-known ports of this
// host (deploy/dds/fastdds-loopback.xml says the same in XML). Starts from the compiled-in
// defaults, never a copy of an XML-affected default (pitfall P3).
dds::DomainParticipantQos loopback_qos(int domain) {
  dds::DomainParticipantQos qos;
  qos.name("ambid");
  qos.wire_protocol().participant_id = static_cast<std::int32_t>(free_participant_id(domain));
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  udp->interfaceWhiteList.emplace_back("127.0.0.1");
  udp->maxInitialPeersRange = max_participants;
  qos.transport().use_builtin_transports = false;
  qos.transport().user_transports.push_back(udp);
  Locator_t localhost;  // port 0: the well-known ports of the domain
  localhost.kind = LOCATOR_KIND_UDPv4;
  IPLocator::setIPv4(localhost, 127, 0, 0, 1);
  // A metatraffic unicast locator of our own is what turns off the multicast listener.
  qos.wire_protocol().builtin.metatrafficUnicastLocatorList.push_back(localhost);
  qos.wire_protocol().builtin.initialPeersList.push_back(localhost);
  return qos;
}

dds::DomainParticipantQos file_qos(const std::string& path) {
  auto* factory = dds::DomainParticipantFactory::get_instance();
  if (factory->load_XML_profiles_file(path) != ReturnCode_t::RETCODE_OK) {
    throw Error("Fast DDS cannot load the profiles file " + path);
  }
  dds::DomainParticipantQos qos;
  if (factory->get_participant_qos_from_profile("ambid", qos) != ReturnCode_t::RETCODE_OK) {
    throw Error("Fast DDS profiles file " + path + " has no participant profile \"ambid\"");
  }
  return qos;
}

}  // namespace

Participant::Participant(int domain, std::string_view profile) {
  // It silently makes this participant a discovery-server client, which Cyclone cannot reach.
  if (std::getenv("ROS_DISCOVERY_SERVER") != nullptr) {
    throw Error(
        "ROS_DISCOVERY_SERVER is set: Fast DDS would become a discovery-server client "
        "that Cyclone DDS participants cannot discover; unset it");
  }
  const dds::DomainParticipantQos qos =
      profile == loopback_profile ? loopback_qos(domain) : file_qos(std::string(profile));
  auto* factory = dds::DomainParticipantFactory::get_instance();
  participant_ = factory->create_participant(static_cast<dds::DomainId_t>(domain), qos);
  if (participant_ == nullptr) {
    throw Error("Fast DDS refused to create a participant on domain " + std::to_string(domain) + " with profile " +
                std::string(profile));
  }
  publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
  if (publisher_ == nullptr || subscriber_ == nullptr) {
    participant_->delete_contained_entities();
    factory->delete_participant(participant_);
    throw Error("Fast DDS refused to create a publisher or subscriber");
  }
}

Participant::~Participant() {
  participant_->delete_contained_entities();
  dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

dds::Topic* Participant::topic(const char* name, dds::TypeSupport (*make_type)()) {
  const std::lock_guard lock(mutex_);
  if (auto it = topics_.find(name); it != topics_.end()) return it->second;
  dds::TypeSupport type = make_type();
  if (type.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
    throw Error("Fast DDS refused to register the type " + type.get_type_name());
  }
  dds::Topic* topic = participant_->create_topic(name, type.get_type_name(), dds::TOPIC_QOS_DEFAULT);
  if (topic == nullptr) throw Error(std::string("Fast DDS refused to create the topic ") + name);
  topics_.emplace(name, topic);
  return topic;
}

}  // namespace ambid::bus::fastdds
