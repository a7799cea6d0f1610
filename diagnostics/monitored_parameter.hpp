#pragma once
// A physical parameter a plant family's diagnostics watch, and the fault it stands for when it
// moves alone (its "role"): each family lists its own (plant_families.hpp), in the order an
// estimate window carries them.
#include <optional>
#include <string_view>

namespace ambid::diag {

// The fault a parameter has when it moved alone, and the words for it in a message.
struct ParameterRole {
  std::string_view fault;
  std::optional<int> channel;
  std::string_view subject;  // "coil 1 resistance"
};

struct MonitoredParameter {
  std::string_view parameter;
  ParameterRole role;
};

}  // namespace ambid::diag
