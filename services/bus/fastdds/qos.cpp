#include "services/bus/fastdds/qos.hpp"

#include <cstdint>

namespace ambid::bus::fastdds {
namespace {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::Duration_t;

Duration_t duration(std::chrono::milliseconds ms) {
  if (ms.count() == 0) return eprosima::fastrtps::c_TimeInfinite;
  return {static_cast<std::int32_t>(ms.count() / 1000), static_cast<std::uint32_t>(ms.count() % 1000) * 1000000u};
}

// What writers and readers share.
template <class EndpointQos>
void apply(const Qos& q, EndpointQos& e) {
  e.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
  e.reliability().max_blocking_time = duration(max_blocking_time);
  e.durability().kind = q.transient_local ? dds::TRANSIENT_LOCAL_DURABILITY_QOS : dds::VOLATILE_DURABILITY_QOS;
  e.history().kind = dds::KEEP_LAST_HISTORY_QOS;
  e.history().depth = q.depth;
  e.resource_limits().max_instances = max_instances;
  e.resource_limits().max_samples_per_instance = q.depth;
  e.resource_limits().max_samples = max_instances * q.depth;
  e.deadline().period = duration(q.deadline);
  e.liveliness().kind = dds::AUTOMATIC_LIVELINESS_QOS;
  e.liveliness().lease_duration = duration(q.liveliness);
  // Messages are bounded but large: allocate payloads as they come, not the bound up front.
  e.endpoint().history_memory_policy = eprosima::fastrtps::rtps::DYNAMIC_REUSABLE_MEMORY_MODE;
  // Fast DDS-only shared memory delivery; the bus is UDP for both vendors.
  e.data_sharing().off();
}

}  // namespace

dds::DataWriterQos writer_qos(Profile profile) {
  const Qos& q = qos(profile);
  dds::DataWriterQos w;
  apply(q, w);
  // A heartbeat piggybacked on a DATA_FRAG makes a Cyclone 0.10 volatile reader that has not
  // yet seen a heartbeat of this writer sync to the heartbeat's last sequence number and drop
  // the sample still in fragments (seen: the first large PlantSamples after a match lost in
  // half the runs). Periodic heartbeats only, as often as Cyclone's own (100 ms).
  w.reliable_writer_qos().disable_heartbeat_piggyback = true;
  w.reliable_writer_qos().times.heartbeatPeriod = duration(std::chrono::milliseconds(100));
  if (q.liveliness.count() != 0) w.liveliness().announcement_period = duration(q.liveliness / 3);
  return w;
}

dds::DataReaderQos reader_qos(Profile profile) {
  dds::DataReaderQos r;
  apply(qos(profile), r);
  return r;
}

}  // namespace ambid::bus::fastdds
