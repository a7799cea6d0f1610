// simulated_step_test.cpp over more seeds, both signs and larger sizes: every case an ERROR
// of the stepped parameter's fault and channel within 3 windows and nothing else named.
#include <gtest/gtest.h>

#include "diagnostics/simulated_step.hpp"

namespace ambid::diag {
namespace {

TEST(SimulatedStepSlow, ErrorNamesTheFaultOverSeedsSignsAndSizes) {
  for (const testing::StepCase& c : testing::step_cases())
    for (double relative : {-0.2, 0.2, 0.3})
      for (std::uint64_t seed : {5100u, 5200u, 5300u}) testing::check_step(c, relative, seed);
}

}  // namespace
}  // namespace ambid::diag
