// The readers under a few hundred mutated inputs each (the slow label runs 100 times more):
// every input accepted or refused with ambid::Error, and the mutations reach both outcomes.
#include <gtest/gtest.h>

#include "fuzz/readers.hpp"

namespace ambid::fuzz {
namespace readers_test {

constexpr int kIterations = 400;

void expect_both_outcomes(const FuzzCount& c) {
  EXPECT_EQ(c.accepted + c.refused, kIterations);
  EXPECT_GT(c.refused, kIterations / 10) << "the mutations hardly break the input";
}

TEST(Fuzz, ExperimentCsv) { expect_both_outcomes(fuzz_experiment_csv(kIterations)); }
TEST(Fuzz, ExperimentSidecar) { expect_both_outcomes(fuzz_experiment_sidecar(kIterations)); }
TEST(Fuzz, ModelJson) { expect_both_outcomes(fuzz_model_json(kIterations)); }
TEST(Fuzz, ScenarioJson) { expect_both_outcomes(fuzz_scenario_json(kIterations)); }
TEST(Fuzz, RigFrame) { expect_both_outcomes(fuzz_rig_frame(kIterations)); }

}  // namespace readers_test
}  // namespace ambid::fuzz
