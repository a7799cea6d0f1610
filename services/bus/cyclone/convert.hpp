#pragma once
// Conversion between the bus messages and the C types idlc generated from idl/ambid.idl.
// to_cyclone fills a zeroed C sample with buffers from dds_alloc; CSample frees them.
// Messages are validated before they get here, so every string and sequence fits its bound.
#include <dds/dds.h>

#include "idl/ambid.h"  // Cyclone's, not Fast DDS's (idl/fastdds/ambid.h)
#include "services/bus/messages.hpp"

namespace ambid::bus::cyclone {

// The generated C type and topic descriptor of each message.
template <class Message>
struct Generated;

template <>
struct Generated<PlantSamples> {
  using Data = ambid_PlantSamples;
  static constexpr const dds_topic_descriptor_t* descriptor = &ambid_PlantSamples_desc;
};
template <>
struct Generated<ExcitationCommand> {
  using Data = ambid_ExcitationCommand;
  static constexpr const dds_topic_descriptor_t* descriptor = &ambid_ExcitationCommand_desc;
};
template <>
struct Generated<PlantSourceCommand> {
  using Data = ambid_PlantSourceCommand;
  static constexpr const dds_topic_descriptor_t* descriptor = &ambid_PlantSourceCommand_desc;
};
template <>
struct Generated<PlantSourceState> {
  using Data = ambid_PlantSourceState;
  static constexpr const dds_topic_descriptor_t* descriptor = &ambid_PlantSourceState_desc;
};
template <>
struct Generated<IdentifiedModel> {
  using Data = ambid_IdentifiedModel;
  static constexpr const dds_topic_descriptor_t* descriptor = &ambid_IdentifiedModel_desc;
};
template <>
struct Generated<FrequencyResponse> {
  using Data = ambid_FrequencyResponse;
  static constexpr const dds_topic_descriptor_t* descriptor = &ambid_FrequencyResponse_desc;
};
template <>
struct Generated<Alert> {
  using Data = ambid_Alert;
  static constexpr const dds_topic_descriptor_t* descriptor = &ambid_Alert_desc;
};
template <>
struct Generated<Health> {
  using Data = ambid_Health;
  static constexpr const dds_topic_descriptor_t* descriptor = &ambid_Health_desc;
};

// A zeroed C sample that frees its buffers when it goes.
template <class Message>
struct CSample {
  CSample() = default;
  CSample(const CSample&) = delete;
  CSample& operator=(const CSample&) = delete;
  ~CSample() { dds_sample_free(&data, Generated<Message>::descriptor, DDS_FREE_CONTENTS); }
  typename Generated<Message>::Data data{};
};

void to_cyclone(const PlantSamples& in, ambid_PlantSamples& out);
void to_cyclone(const ExcitationCommand& in, ambid_ExcitationCommand& out);
void to_cyclone(const PlantSourceCommand& in, ambid_PlantSourceCommand& out);
void to_cyclone(const PlantSourceState& in, ambid_PlantSourceState& out);
void to_cyclone(const IdentifiedModel& in, ambid_IdentifiedModel& out);
void to_cyclone(const FrequencyResponse& in, ambid_FrequencyResponse& out);
void to_cyclone(const Alert& in, ambid_Alert& out);
void to_cyclone(const Health& in, ambid_Health& out);

PlantSamples from_cyclone(const ambid_PlantSamples& in);
ExcitationCommand from_cyclone(const ambid_ExcitationCommand& in);
PlantSourceCommand from_cyclone(const ambid_PlantSourceCommand& in);
PlantSourceState from_cyclone(const ambid_PlantSourceState& in);
IdentifiedModel from_cyclone(const ambid_IdentifiedModel& in);
FrequencyResponse from_cyclone(const ambid_FrequencyResponse& in);
Alert from_cyclone(const ambid_Alert& in);
Health from_cyclone(const ambid_Health& in);

}  // namespace ambid::bus::cyclone
