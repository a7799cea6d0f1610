#include "services/bus/cyclone/qos.hpp"

namespace ambid::bus::cyclone {
namespace {

dds_duration_t duration(std::chrono::milliseconds ms) { return ms.count() == 0 ? DDS_INFINITY : DDS_MSECS(ms.count()); }

}  // namespace

QosPtr endpoint_qos(Profile profile) {
  const Qos& q = qos(profile);
  QosPtr p(dds_create_qos(), &dds_delete_qos);
  dds_qos_t* qos = p.get();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, duration(max_blocking_time));
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, q.depth);
  dds_qset_resource_limits(qos, max_instances * q.depth, max_instances, q.depth);
  if (q.transient_local) {
    dds_qset_durability(qos, DDS_DURABILITY_TRANSIENT_LOCAL);
    // Cyclone keeps durability_service.history (default KEEP_LAST 1) for late joiners, not the
    // writer history (pitfall P5).
    dds_qset_durability_service(qos, 0, DDS_HISTORY_KEEP_LAST, q.depth, max_instances * q.depth, max_instances,
                                q.depth);
  } else {
    dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
  }
  dds_qset_deadline(qos, duration(q.deadline));
  dds_qset_liveliness(qos, DDS_LIVELINESS_AUTOMATIC, duration(q.liveliness));
  // What Fast DDS 2.9 speaks (pitfall P1); @final types default to it, this makes it explicit.
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos, 1, &xcdr1);
  return p;
}

}  // namespace ambid::bus::cyclone
