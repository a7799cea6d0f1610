#pragma once
// The plant daemon's check of an ExcitationCommand from the bus before its source sees it
// (plant config keys max_amplitude, max_frequency), and the request its source gets.
#include <string>

#include "services/bus/messages.hpp"
#include "services/daemons/plant_source.hpp"

namespace ambid::daemons {

struct ExcitationLimits {
  double max_amplitude = 0.5;     // V
  double max_frequency = 2000.0;  // Hz
};

// Empty when the command is within the limits, else why it is refused.
std::string excitation_violation(const bus::ExcitationCommand& command, const ExcitationLimits& limits);

// The request of a command within the limits: kind, amplitude and the band of its frequencies.
ExcitationRequest excitation_request(const bus::ExcitationCommand& command);

}  // namespace ambid::daemons
