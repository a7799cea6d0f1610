#pragma once
// Conversion between the bus messages and the types fastddsgen generated from idl/ambid.idl.
// Messages are validated before they get here, so no bound can truncate.
#include "idl/fastdds/ambidPubSubTypes.h"
#include "services/bus/messages.hpp"

namespace ambid::bus::fastdds {

// The generated data type and TopicDataType of each message.
template <class Message>
struct Generated;

template <>
struct Generated<PlantSamples> {
  using Data = ::ambid::PlantSamples;
  using PubSub = ::ambid::PlantSamplesPubSubType;
};
template <>
struct Generated<ExcitationCommand> {
  using Data = ::ambid::ExcitationCommand;
  using PubSub = ::ambid::ExcitationCommandPubSubType;
};
template <>
struct Generated<PlantSourceCommand> {
  using Data = ::ambid::PlantSourceCommand;
  using PubSub = ::ambid::PlantSourceCommandPubSubType;
};
template <>
struct Generated<PlantSourceState> {
  using Data = ::ambid::PlantSourceState;
  using PubSub = ::ambid::PlantSourceStatePubSubType;
};
template <>
struct Generated<IdentifiedModel> {
  using Data = ::ambid::IdentifiedModel;
  using PubSub = ::ambid::IdentifiedModelPubSubType;
};
template <>
struct Generated<FrequencyResponse> {
  using Data = ::ambid::FrequencyResponse;
  using PubSub = ::ambid::FrequencyResponsePubSubType;
};
template <>
struct Generated<Alert> {
  using Data = ::ambid::Alert;
  using PubSub = ::ambid::AlertPubSubType;
};
template <>
struct Generated<Health> {
  using Data = ::ambid::Health;
  using PubSub = ::ambid::HealthPubSubType;
};

void to_fast(const PlantSamples& in, ::ambid::PlantSamples& out);
void to_fast(const ExcitationCommand& in, ::ambid::ExcitationCommand& out);
void to_fast(const PlantSourceCommand& in, ::ambid::PlantSourceCommand& out);
void to_fast(const PlantSourceState& in, ::ambid::PlantSourceState& out);
void to_fast(const IdentifiedModel& in, ::ambid::IdentifiedModel& out);
void to_fast(const FrequencyResponse& in, ::ambid::FrequencyResponse& out);
void to_fast(const Alert& in, ::ambid::Alert& out);
void to_fast(const Health& in, ::ambid::Health& out);

PlantSamples from_fast(const ::ambid::PlantSamples& in);
ExcitationCommand from_fast(const ::ambid::ExcitationCommand& in);
PlantSourceCommand from_fast(const ::ambid::PlantSourceCommand& in);
PlantSourceState from_fast(const ::ambid::PlantSourceState& in);
IdentifiedModel from_fast(const ::ambid::IdentifiedModel& in);
FrequencyResponse from_fast(const ::ambid::FrequencyResponse& in);
Alert from_fast(const ::ambid::Alert& in);
Health from_fast(const ::ambid::Health& in);

}  // namespace ambid::bus::fastdds
