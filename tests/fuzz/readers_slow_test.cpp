// The readers' fuzz targets (readers_test.cpp) with 40 000 inputs each.
#include <gtest/gtest.h>

#include "fuzz/readers.hpp"

namespace ambid::fuzz {
namespace readers_slow_test {

constexpr int kIterations = 40000;

TEST(FuzzLong, ExperimentCsv) { EXPECT_GT(fuzz_experiment_csv(kIterations).refused, 0); }
TEST(FuzzLong, ExperimentSidecar) { EXPECT_GT(fuzz_experiment_sidecar(kIterations).refused, 0); }
TEST(FuzzLong, ModelJson) { EXPECT_GT(fuzz_model_json(kIterations).refused, 0); }
TEST(FuzzLong, ScenarioJson) { EXPECT_GT(fuzz_scenario_json(kIterations).refused, 0); }
TEST(FuzzLong, RigFrame) { EXPECT_GT(fuzz_rig_frame(kIterations).refused, 0); }

}  // namespace readers_slow_test
}  // namespace ambid::fuzz
