#pragma once
// The bus: one DDS participant of either vendor, and typed writers and readers on it. Daemons
// see only this header and messages.hpp; the vendor is a runtime choice (--dds fastdds|cyclone,
// make_bus.hpp) and any mix of vendors interoperates on one domain. Topics and QoS: topics.hpp,
// qos.hpp. This header needs no vendor library; make_bus.hpp links both.
//
//   auto bus = ambid::bus::make_bus("cyclone", 7);
//   auto alerts = bus->writer<ambid::bus::Alert>();
//   alerts->write(alert);              // bounds checked first (validate.hpp)
//   auto models = bus->reader<ambid::bus::IdentifiedModel>();
//   while (running) { bus->wait(100ms); for (auto& m : models->take()) ...; models->events(); }
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>

#include "services/bus/activity.hpp"
#include "services/bus/endpoint.hpp"
#include "services/bus/messages.hpp"
#include "services/bus/topics.hpp"

namespace ambid::bus {

// Built-in network profile: UDP on 127.0.0.1 only, no multicast, unicast discovery of the
// participants of this host (deploy/dds/README.md). Any other profile is the path of a vendor
// XML file (a Cyclone configuration, or Fast DDS profiles with a participant profile "ambid").
inline constexpr std::string_view loopback_profile = "loopback";

// Domain ids map to UDP ports 7400 + 250 * domain + ...; larger ids overflow the port range.
inline constexpr int max_domain = 232;

namespace detail {

// One pair of factory functions per message type of BusMessages (topics.hpp); VendorBus
// (vendor_bus.hpp) implements them all for a backend.
template <class Message>
class EndpointFactory {
 public:
  virtual ~EndpointFactory() = default;

 protected:
  virtual std::unique_ptr<Writer<Message>> create_writer(std::type_identity<Message>) = 0;
  virtual std::unique_ptr<Reader<Message>> create_reader(std::type_identity<Message>) = 0;
};

template <class List>
class EndpointFactories;

template <class... Messages>
class EndpointFactories<TypeList<Messages...>> : public EndpointFactory<Messages>... {
 protected:
  using EndpointFactory<Messages>::create_writer...;
  using EndpointFactory<Messages>::create_reader...;
};

}  // namespace detail

class Bus : public detail::EndpointFactories<BusMessages> {
 public:
  Bus(const Bus&) = delete;
  Bus& operator=(const Bus&) = delete;

  const std::string& vendor() const { return vendor_; }
  int domain() const { return domain_; }

  // Endpoints on Topic<Message>::name with the QoS of Topic<Message>::profile. They keep the
  // participant alive, so they may outlive the Bus object. Throws Error when the middleware
  // refuses to create one.
  template <class Message>
  std::unique_ptr<Writer<Message>> writer() {
    return create_writer(std::type_identity<Message>{});
  }
  template <class Message>
  std::unique_ptr<Reader<Message>> reader() {
    return create_reader(std::type_identity<Message>{});
  }

  // Returns true as soon as an endpoint of this bus received data or a status event since the
  // previous call, false after the timeout. Meant for one waiting thread.
  bool wait(std::chrono::milliseconds timeout);

 protected:
  Bus(std::string vendor, int domain);
  const std::shared_ptr<Activity>& activity() const { return activity_; }

 private:
  std::string vendor_;
  int domain_;
  std::shared_ptr<Activity> activity_ = std::make_shared<Activity>();
  std::uint64_t seen_ = 0;
};

}  // namespace ambid::bus
