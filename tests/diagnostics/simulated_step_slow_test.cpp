// simulated_step_test.cpp over more seeds, both signs and larger sizes: every case an ERROR
// of the stepped parameter's fault and channel within 6 windows and nothing else named.
// Closed-loop on 0.25 s noisy windows scatters ~5 % in R1, R2, so 20 % is a step of ~4
// sigma_eff: the CUSUM (k ~0.5 raised for the 30-window baseline, h = 12) needs about
// 4 windows on average (two_sided_cusum_arl), some runs 5; kw scatters far less (1 window).
#include <gtest/gtest.h>

#include "diagnostics/simulated_step.hpp"

namespace ambid::diag {
namespace simulated_step_slow_test {

TEST(SimulatedStepSlow, ErrorNamesTheFaultOverSeedsSignsAndSizes) {
  for (const testing::StepCase& c : testing::step_cases())
    for (double relative : {-0.2, 0.2, 0.3})
      for (std::uint64_t seed : {5100u, 5200u, 5300u}) testing::check_step(c, relative, seed, 6);
}

}  // namespace simulated_step_slow_test
}  // namespace ambid::diag
