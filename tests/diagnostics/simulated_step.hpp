#pragma once
// The step check of the simulated sequences: a relative step of one true parameter from
// window kStepAt on, through an engine learning 30 windows; ERROR on that parameter with its
// fault and channel within a given number of windows, and no WARN or ERROR naming any other
// fault or channel.
#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace ambid::diag::testing {

struct StepCase {
  std::string parameter;
  std::string fault;
  int channel;
};
void PrintTo(const StepCase& c, std::ostream* os);  // gtest: the parameter

// R1, R2 (coil_resistance 1, 2), kw1, kw2 (amplifier_gain 1, 2).
const std::vector<StepCase>& step_cases();

// Runs the sequence (seed: SimulatedBearing::seed) and reports failures through gtest; the
// ERROR must come within `windows` windows from the first changed one, both included.
void check_step(const StepCase& c, double relative, std::uint64_t seed, std::size_t windows);

}  // namespace ambid::diag::testing
