#pragma once
// Checks a message against the IDL bounds and its own layout before it is written, so an
// oversized string or sequence is refused with a clear error instead of being truncated or
// rejected somewhere on the wire (neither vendor checks bounds on write).
#include "core/error.hpp"
#include "services/bus/message_list.hpp"
#include "services/bus/messages.hpp"

namespace ambid::bus {

// Names the field, its size, the bound or the expected size, and (abbreviated) the value.
class InvalidMessage : public Error {
 public:
  using Error::Error;
};

// Each throws InvalidMessage when a string is longer than its bound or holds a NUL, a sequence
// is longer than its bound, a flattened array does not match its dimensions, or an enum value
// is out of range.
#define AMBID_BUS_VALIDATE(Message, topic_name, qos_profile) void validate(const Message& m);
AMBID_BUS_MESSAGES(AMBID_BUS_VALIDATE)
#undef AMBID_BUS_VALIDATE

}  // namespace ambid::bus
