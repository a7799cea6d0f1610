#pragma once
// Fuzz targets of every bus message type (services/bus/message_list.hpp), issue 18: a valid
// message of each type is mutated field by field (strings replaced or byte-mutated, numbers
// made non-finite or extreme, enums out of range, sequences emptied, shortened, grown or
// duplicated) and handed to what the service does with it on receipt, as a foreign peer could
// send it (readers do not validate: the middleware checks only the IDL bounds, if at all):
//   PlantSamples        the identifier's gap check and described windows (windows validate)
//   PlantDescription    (every other one with the hash of its mutated content as its id)
//                       the identifier's described windows, the diagnostics' change
//                       classification and (every 10th accepted) its fault signatures
//   ExcitationCommand   the plant daemon's limits, then a sim source's excite()
//   PlantSourceCommand  the plant daemon's source factory (sim and replay; a rig target would
//                       wait 3 s for a HELLO answer per input and is left out)
//   PlantSourceState    the diagnostics' source kind and its name
//   IdentifiedModel     the diagnostics' estimate window (finite values when taken)
//   FrequencyResponse   the write-side bound check (its consumers are the CLI's text)
//   Alert, Health       level names (the CLI), the identifier-failure test of the diagnostics
// Every type also goes through bus::validate. Each input must be taken or refused with
// ambid::Error (InvalidMessage is one), never crash or throw anything else.
#include "fuzz/mutator.hpp"
#include "services/bus/message_list.hpp"
#include "services/bus/messages.hpp"

namespace ambid::fuzz {

template <class Message>
FuzzCount fuzz_bus_message(int iterations);

#define AMBID_FUZZ_DECLARE(Message, topic_name, qos_profile) \
  extern template FuzzCount fuzz_bus_message<bus::Message>(int iterations);
AMBID_BUS_MESSAGES(AMBID_FUZZ_DECLARE)
#undef AMBID_FUZZ_DECLARE

}  // namespace ambid::fuzz
