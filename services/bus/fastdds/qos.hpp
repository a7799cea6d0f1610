#pragma once
// The QoS table (services/bus/qos.hpp) in Fast DDS terms. Built from the compiled-in defaults,
// never from XML-affected defaults, so a stray DEFAULT_FASTRTPS_PROFILES.xml changes nothing.
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

#include "services/bus/qos.hpp"

namespace ambid::bus::fastdds {

eprosima::fastdds::dds::DataWriterQos writer_qos(Profile profile);
eprosima::fastdds::dds::DataReaderQos reader_qos(Profile profile);

}  // namespace ambid::bus::fastdds
