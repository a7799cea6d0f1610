#pragma once
// Which topic carries which message, under which QoS profile, and the list of every message
// type; both generated from message_list.hpp. Topic names are the same for both vendors; type
// names are the IDL's ("ambid::PlantSamples", ...).
#include "services/bus/message_list.hpp"
#include "services/bus/messages.hpp"
#include "services/bus/qos.hpp"

namespace ambid::bus {

template <class... Messages>
struct TypeList {};

template <class Message>
struct Topic;

#define AMBID_BUS_TOPIC(Message, topic_name, qos_profile)    \
  template <>                                                \
  struct Topic<Message> {                                    \
    static constexpr const char* name = topic_name;          \
    static constexpr Profile profile = Profile::qos_profile; \
  };
AMBID_BUS_MESSAGES(AMBID_BUS_TOPIC)
#undef AMBID_BUS_TOPIC

namespace detail {
template <class First, class... Rest>
using Tail = TypeList<Rest...>;
}  // namespace detail

// Every message type of the bus, in the order of message_list.hpp (each entry expands to
// ", Message"; the leading void absorbs the first comma).
#define AMBID_BUS_TYPE(Message, topic_name, qos_profile) , Message
using BusMessages = detail::Tail<void AMBID_BUS_MESSAGES(AMBID_BUS_TYPE)>;
#undef AMBID_BUS_TYPE

}  // namespace ambid::bus
