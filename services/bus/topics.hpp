#pragma once
// Which topic carries which message, under which QoS profile. Topic names are the same for both
// vendors; type names are the IDL's ("ambid::PlantSamples", ...).
#include "services/bus/messages.hpp"
#include "services/bus/qos.hpp"

namespace ambid::bus {

template <class Message>
struct Topic;

template <>
struct Topic<PlantSamples> {
  static constexpr const char* name = "ambid/plant_samples";
  static constexpr Profile profile = Profile::samples;
};
template <>
struct Topic<ExcitationCommand> {
  static constexpr const char* name = "ambid/excitation_command";
  static constexpr Profile profile = Profile::commands;
};
template <>
struct Topic<PlantSourceCommand> {
  static constexpr const char* name = "ambid/plant_source_command";
  static constexpr Profile profile = Profile::commands;
};
template <>
struct Topic<PlantSourceState> {
  static constexpr const char* name = "ambid/plant_source_state";
  static constexpr Profile profile = Profile::state;
};
template <>
struct Topic<IdentifiedModel> {
  static constexpr const char* name = "ambid/identified_model";
  static constexpr Profile profile = Profile::state;
};
template <>
struct Topic<FrequencyResponse> {
  static constexpr const char* name = "ambid/frequency_response";
  static constexpr Profile profile = Profile::state;
};
template <>
struct Topic<Alert> {
  static constexpr const char* name = "ambid/alert";
  static constexpr Profile profile = Profile::state;
};
template <>
struct Topic<Health> {
  static constexpr const char* name = "ambid/health";
  static constexpr Profile profile = Profile::health;
};

}  // namespace ambid::bus
