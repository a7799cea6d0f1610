#pragma once
// The identifier daemon's one computation: a window of closed-loop samples of the
// amb1dof_voltage bearing -> its physical model, by the deadbeat realisation with its known
// controller (identifier/amb1dof_deadbeat.hpp), as an IdentifiedModel message.
//
// The controller's integrator state at the first sample of a window is not on the bus; the
// window is identified with it taken as zero. That error is a constant shift of the
// reconstructed velocity, which the offset term of the realisation (estimate_offset, on by
// default) absorbs exactly: x[k+1] = A x + B u + c holds for x + d with c' = c + d - A d.
#include <cstdint>
#include <string>

#include "core/experiment.hpp"
#include "identifier/deadbeat_realization.hpp"
#include "services/bus/messages.hpp"

namespace ambid::daemons {

inline constexpr const char* kDeadbeatMethod = "amb1dof_deadbeat";

// Throws Error (InsufficientData for unexciting data) naming what the window lacks.
bus::IdentifiedModel identify_window(const Experiment& window, const std::string& plant_id, std::uint64_t seq,
                                     const ident::DeadbeatOptions& options = {});

}  // namespace ambid::daemons
