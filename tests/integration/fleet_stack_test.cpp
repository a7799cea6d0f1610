// A plant id served by two identifiers (issue 14): fleets are divided by the identifiers'
// "plants" lists; a plant listed in two of them is reported by both (log and Health), never
// silently served twice, also with the identifiers on different vendors. Domain 223.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "fleet_support.hpp"

namespace ambid::testing {
namespace fleet_stack_test {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(FleetStack, APlantServedByTwoIdentifiersIsReported) {
  constexpr int domain = 223;
  Stack stack("fleet_twice", domain);
  start_identifier(stack, "identifier-a", plant_list(1, 2), domain, "cyclone");
  start_identifier(stack, "identifier-b", plant_list(2, 3), domain, "fastdds");
  for (int k = 1; k <= 3; ++k) start_plant(stack, k, domain);
  std::this_thread::sleep_for(std::chrono::seconds(6));
  for (const char* name : {"identifier-a", "identifier-b"}) {
    const std::string log = stack.log(name);
    EXPECT_THAT(log, HasSubstr("plant bearing-2 is served twice")) << log;
    EXPECT_THAT(log, Not(HasSubstr("plant bearing-1 is served twice"))) << log;
    EXPECT_THAT(log, Not(HasSubstr("plant bearing-3 is served twice"))) << log;
  }
  // Health says so, on the process's node and the plant's.
  const CommandResult status = stack.ambid("status --wait 2 --plant-id bearing-2");
  EXPECT_THAT(status.output, HasSubstr("served twice")) << status.output;
}

}  // namespace fleet_stack_test
}  // namespace ambid::testing
