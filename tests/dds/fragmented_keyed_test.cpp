// Large keyed samples from a Cyclone writer to a Fast DDS reader (issue 14, a fleet split across
// vendors): models of several plants, from 1 kB to 131 kB, so that with the loopback profile
// some travel whole and the largest in DATA_FRAG fragments (Cyclone's FragmentSize 62000), on
// the transient-local keep-last topic the identifiers use. Every message the Fast reader takes
// must be one that was written, whole, under its own plant id, and the last model of every
// plant must arrive.
// What it guards: with Cyclone's default fragments (1344 bytes) a Fast DDS 2.9.1 identifier
// reading a Cyclone identifier's models lost track of its instances (6.8 million "Change not
// found on this key, something is wrong" in 45 s, 8 bearings: fleet_stack_slow_test.cpp). This
// test did not show that failure with the former profile (5 runs): the eight-bearing fleet is
// the reproduction; this one checks that large keyed samples, whole or in fragments, still
// cross between the vendors intact. Domain 226.
#include <map>
#include <thread>

#include <gtest/gtest.h>

#include "dds/harness.hpp"

namespace ambid::bus::test {
namespace fragmented_keyed_test {

constexpr int kPlants = 4;
constexpr int kRounds = 40;

// Model `round` of plant `plant`: a discrete model of order n, 4 n^2 doubles (n = 64: 131 kB),
// every value naming its plant and round.
IdentifiedModel model(int plant, int round) {
  static constexpr std::uint32_t orders[] = {2, 64, 8, 40, 3, 45};
  const std::uint32_t n = orders[std::size_t(plant + round) % std::size(orders)];
  IdentifiedModel m = small<IdentifiedModel>(round + 1);
  m.plant_id = "bearing-" + std::to_string(plant);
  const auto matrix = [&](double offset) {
    std::vector<double> values(std::size_t(n) * n);
    for (std::size_t k = 0; k < values.size(); ++k) values[k] = 1000.0 * plant + round + offset + 1e-6 * double(k);
    return Matrix{n, n, values};
  };
  m.discrete = {matrix(0.1), matrix(0.2), matrix(0.3), matrix(0.4)};
  return m;
}

TEST(FragmentedKeyed, LargeModelsFromCycloneReachAFastReaderUnderTheirOwnKeys) {
  constexpr int domain = 226;
  const auto cyclone = make_bus("cyclone", domain);
  const auto fast = make_bus("fastdds", domain);
  const auto reader = fast->reader<IdentifiedModel>();
  const auto writer = cyclone->writer<IdentifiedModel>();
  ASSERT_TRUE(eventually([&] { return matched(*writer, *reader); }));

  std::map<std::string, std::uint64_t> last_seq;  // per plant, of the messages taken
  int taken = 0, wrong = 0;
  const auto take = [&] {
    for (const IdentifiedModel& m : reader->take()) {
      ++taken;
      const int plant = std::stoi(m.plant_id.substr(m.plant_id.find('-') + 1));
      const int round = int(m.seq) - 1;
      const bool known = plant >= 0 && plant < kPlants && round >= 0 && round < kRounds;
      if (!known || !(m == model(plant, round)) || m.seq <= last_seq[m.plant_id]) {
        if (++wrong <= 5) ADD_FAILURE() << "unexpected model " << m.plant_id << " seq " << m.seq;
        continue;
      }
      last_seq[m.plant_id] = m.seq;
    }
  };
  for (int round = 0; round < kRounds; ++round) {
    for (int plant = 0; plant < kPlants; ++plant) writer->write(model(plant, round));
    take();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_TRUE(eventually([&] {
    take();
    for (int plant = 0; plant < kPlants; ++plant)
      if (last_seq["bearing-" + std::to_string(plant)] != std::uint64_t(kRounds)) return false;
    return true;
  })) << "taken "
      << taken;
  EXPECT_EQ(wrong, 0);
  EXPECT_GE(taken, kPlants * 8) << "fewer models than one history depth per plant";
}

}  // namespace fragmented_keyed_test
}  // namespace ambid::bus::test
