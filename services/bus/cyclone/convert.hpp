#pragma once
// Conversion between the bus messages and the C types idlc generated from idl/ambid.idl.
// to_cyclone fills a zeroed C sample with buffers from dds_alloc; CSample frees them.
// Messages are validated before they get here, so every string and sequence fits its bound.
#include <dds/dds.h>

#include "idl/ambid.h"  // Cyclone's, not Fast DDS's (idl/fastdds/ambid.h)
#include "services/bus/message_list.hpp"
#include "services/bus/messages.hpp"

namespace ambid::bus::cyclone {

// The generated C type and topic descriptor of each message, and the conversions to and from it
// (convert.cpp), for every message of message_list.hpp.
template <class Message>
struct Generated;

#define AMBID_CYCLONE_MESSAGE(Message, topic_name, qos_profile)                          \
  template <>                                                                            \
  struct Generated<Message> {                                                            \
    using Data = ambid_##Message;                                                        \
    static constexpr const dds_topic_descriptor_t* descriptor = &ambid_##Message##_desc; \
  };                                                                                     \
  void to_cyclone(const Message& in, ambid_##Message& out);                              \
  Message from_cyclone(const ambid_##Message& in);
AMBID_BUS_MESSAGES(AMBID_CYCLONE_MESSAGE)
#undef AMBID_CYCLONE_MESSAGE

// A zeroed C sample that frees its buffers when it goes.
template <class Message>
struct CSample {
  CSample() = default;
  CSample(const CSample&) = delete;
  CSample& operator=(const CSample&) = delete;
  ~CSample() { dds_sample_free(&data, Generated<Message>::descriptor, DDS_FREE_CONTENTS); }
  typename Generated<Message>::Data data{};
};

}  // namespace ambid::bus::cyclone
