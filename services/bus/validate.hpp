#pragma once
// Checks a message against the IDL bounds and its own layout before it is written, so an
// oversized string or sequence is refused with a clear error instead of being truncated or
// rejected somewhere on the wire (neither vendor checks bounds on write).
#include "core/error.hpp"
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
void validate(const PlantSamples& m);
void validate(const ExcitationCommand& m);
void validate(const PlantSourceCommand& m);
void validate(const PlantSourceState& m);
void validate(const IdentifiedModel& m);
void validate(const FrequencyResponse& m);
void validate(const Alert& m);
void validate(const Health& m);

}  // namespace ambid::bus
