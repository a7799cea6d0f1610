#pragma once
// Hidden-effect cases for the audit tests: an effect of the catalogue at a randomly drawn
// moderate magnitude (seeded), simulated in closed loop with sensor noise while the sidecar
// stays nominal.
#include <cstdint>
#include <string>

#include "core/experiment.hpp"
#include "plant_sim/effects.hpp"

namespace ambid::diag::testing {

// Draws the effect's switching parameters from its moderate band (random sign where both are
// physical), its channel (1 or 2) and its shape parameters (frequencies, damping).
sim::Effect draw_effect(const std::string& name, std::uint64_t seed);

// PRBS of 0.3 V on both inputs, position noise 2 nm, current noise 20 uA (std); no effect
// when `effect.name` is empty.
Experiment simulate_hidden(const sim::Effect& effect, double duration, std::uint64_t seed);

// The size of an effect: its switching parameter, or the force amplitude of a harmonic.
double effect_size(const sim::Effect& effect);

}  // namespace ambid::diag::testing
