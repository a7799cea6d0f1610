#pragma once
// Conversion between the bus messages and the types fastddsgen generated from idl/ambid.idl.
// Messages are validated before they get here, so no bound can truncate.
#include "idl/fastdds/ambidPubSubTypes.h"
#include "services/bus/message_list.hpp"
#include "services/bus/messages.hpp"

namespace ambid::bus::fastdds {

// The generated data type and TopicDataType of each message, and the conversions to and from
// it (convert.cpp), for every message of message_list.hpp.
template <class Message>
struct Generated;

#define AMBID_FASTDDS_MESSAGE(Message, topic_name, qos_profile) \
  template <>                                                   \
  struct Generated<Message> {                                   \
    using Data = ::ambid::Message;                              \
    using PubSub = ::ambid::Message##PubSubType;                \
  };                                                            \
  void to_fast(const Message& in, ::ambid::Message& out);       \
  Message from_fast(const ::ambid::Message& in);
AMBID_BUS_MESSAGES(AMBID_FASTDDS_MESSAGE)
#undef AMBID_FASTDDS_MESSAGE

}  // namespace ambid::bus::fastdds
