#pragma once
// The one list of the bus's message types. Each entry names the message (its struct in
// messages.hpp and its IDL struct ambid::NAME in idl/ambid.idl), its topic (the same name for
// both vendors) and its QoS profile (qos.hpp). The topic table and the type list (topics.hpp),
// the bus's writer and reader factories (bus.hpp, vendor_bus.hpp), the validate() overloads and
// both backends' generated-type tables and conversion declarations all expand this list.
// Adding a message: its IDL struct, its struct in messages.hpp, its validate() and its two
// vendor conversions (fastdds/convert.cpp, cyclone/convert.cpp), and one line here.
//
// An X-macro rather than a template list because the backends need the vendor type names
// (ambid::NAMEPubSubType, ambid_NAME_desc), which only token pasting can derive.
#define AMBID_BUS_MESSAGES(X)                                   \
  X(PlantSamples, "ambid/plant_samples", samples)               \
  X(PlantDescription, "ambid/plant_description", description)   \
  X(ExcitationCommand, "ambid/excitation_command", commands)    \
  X(PlantSourceCommand, "ambid/plant_source_command", commands) \
  X(PlantSourceState, "ambid/plant_source_state", state)        \
  X(IdentifiedModel, "ambid/identified_model", state)           \
  X(FrequencyResponse, "ambid/frequency_response", state)       \
  X(Alert, "ambid/alert", state)                                \
  X(Health, "ambid/health", health)
