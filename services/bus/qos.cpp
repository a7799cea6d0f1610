#include "services/bus/qos.hpp"

#include <array>

namespace ambid::bus {
namespace {

using std::chrono::milliseconds;

// Deadlines: a plant source publishes a batch at least every second, a daemon its Health every
// second; a deadline miss or lost liveliness is what turns a silent source into a STALE alert.
constexpr std::array<Qos, 5> table{{
    {.transient_local = false,
     .depth = 64,
     .deadline = milliseconds{1000},
     .liveliness = milliseconds{2000}},                                       // samples
    {.transient_local = false, .depth = 16},                                  // commands
    {.transient_local = true, .depth = 8, .liveliness = milliseconds{5000}},  // state
    {.transient_local = true, .depth = 1, .deadline = milliseconds{3000}, .liveliness = milliseconds{3000}},  // health
    {.transient_local = true, .depth = 1},  // description
}};

}  // namespace

const Qos& qos(Profile profile) { return table.at(static_cast<std::size_t>(profile)); }

std::string_view name(Profile profile) {
  constexpr std::array<std::string_view, 5> names{"samples", "commands", "state", "health", "description"};
  return names.at(static_cast<std::size_t>(profile));
}

}  // namespace ambid::bus
