#pragma once
// The one QoS table of the bus, applied alike by both backends to writers and readers, so any
// mix of vendors matches (requested = offered). Every profile is RELIABLE with KEEP_LAST history
// and AUTOMATIC liveliness; writers block at most 100 ms when their history is full.
#include <chrono>
#include <string_view>

namespace ambid::bus {

// samples:  volatile, deadline and liveliness (plant samples)
// commands: volatile (a late joiner must not act on old commands)
// state:    transient-local: a late subscriber gets the current state (models, alerts, ...)
// health:   transient-local, deadline and liveliness
// description: transient-local, keep-last 1 per instance: a late subscriber gets the current
//           plant description of every plant, and only that
// Which message uses which profile: message_list.hpp.
enum class Profile { samples, commands, state, health, description };

struct Qos {
  bool transient_local = false;             // else VOLATILE
  int depth = 1;                            // KEEP_LAST per instance; for transient-local also the depth a
                                            // late joiner gets (Cyclone durability_service, pitfall P5)
  std::chrono::milliseconds deadline{0};    // per instance; 0: none
  std::chrono::milliseconds liveliness{0};  // AUTOMATIC lease; 0: infinite
};

inline constexpr std::chrono::milliseconds max_blocking_time{100};
// Resource limits of every endpoint: instances (keys) per topic; depth samples each.
inline constexpr int max_instances = 1024;

const Qos& qos(Profile profile);
std::string_view name(Profile profile);

}  // namespace ambid::bus
