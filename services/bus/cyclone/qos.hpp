#pragma once
// The QoS table (services/bus/qos.hpp) in Cyclone DDS terms, for writers and readers alike.
#include <memory>

#include <dds/dds.h>

#include "services/bus/qos.hpp"

namespace ambid::bus::cyclone {

using QosPtr = std::unique_ptr<dds_qos_t, decltype(&dds_delete_qos)>;

QosPtr endpoint_qos(Profile profile);

}  // namespace ambid::bus::cyclone
