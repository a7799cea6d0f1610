#include "diagnostics/fault_isolation.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"

namespace ambid::diag {
namespace {

Deviation moved(const std::string& parameter, double relative) { return {parameter, relative, 0.002}; }

TEST(FaultIsolation, OneParameterNamesItsOwnFault) {
  struct Case {
    const char* parameter;
    const char* fault;
    std::optional<int> channel;
  };
  for (const Case c : {Case{"R1", "coil_resistance", 1}, Case{"R2", "coil_resistance", 2},
                       Case{"kw1", "amplifier_gain", 1}, Case{"kw2", "amplifier_gain", 2},
                       Case{"kr1", "force_factor", 1}, Case{"kr2", "force_factor", 2}, Case{"ks", "air_gap", {}}}) {
    const std::vector<Isolation> r = isolate({moved(c.parameter, 0.2)});
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].parameter, c.parameter);
    EXPECT_EQ(r[0].fault, c.fault);
    EXPECT_EQ(r[0].channel, c.channel);
    EXPECT_FALSE(r[0].shared);
    EXPECT_TRUE(is_known_fault(r[0].fault));
  }
  EXPECT_EQ(isolate({moved("R1", 0.2)})[0].subject, "coil 1 resistance");
}

TEST(FaultIsolation, CommonModeOfForceFactorsIsTheSensorGain) {
  const std::vector<Isolation> r = isolate({moved("kr1", 0.05), moved("kr2", 0.055)});
  ASSERT_EQ(r.size(), 2u);
  for (const Isolation& i : r) {
    EXPECT_EQ(i.fault, "sensor_gain");
    EXPECT_EQ(i.channel, std::nullopt);
    EXPECT_TRUE(i.shared);
  }
  EXPECT_EQ(r[1].parameter, "kr2");
}

TEST(FaultIsolation, OppositeOrUnequalChangesAreSeparateFaults) {
  for (const auto& [d1, d2] : {std::pair{0.05, -0.05}, std::pair{0.05, 0.15}}) {
    const std::vector<Isolation> r = isolate({moved("kr1", d1), moved("kr2", d2)});
    EXPECT_EQ(r[0].fault, "force_factor");
    EXPECT_EQ(r[0].channel, 1);
    EXPECT_EQ(r[1].fault, "force_factor");
    EXPECT_EQ(r[1].channel, 2);
  }
}

TEST(FaultIsolation, BothChannelsAlikeHaveNoChannel) {
  const std::vector<Isolation> coils = isolate({moved("R1", 0.12), moved("R2", 0.10)});
  EXPECT_EQ(coils[0].fault, "coil_resistance");
  EXPECT_EQ(coils[0].channel, std::nullopt);
  const std::vector<Isolation> amps = isolate({moved("kw2", -0.1), moved("kw1", -0.1)});
  EXPECT_EQ(amps[0].fault, "amplifier_gain");
  EXPECT_EQ(amps[0].channel, std::nullopt);
}

TEST(FaultIsolation, MechanicalSignatures) {
  // v1, v2, v3 all scale with 1/m.
  std::vector<Isolation> r = isolate({moved("ks", -0.1), moved("kr1", -0.1), moved("kr2", -0.1)});
  for (const Isolation& i : r) EXPECT_EQ(i.fault, "rotor_mass");
  // A wider gap: dlog ks = 1.5 dlog kr.
  r = isolate({moved("kr1", -0.04), moved("ks", -0.06), moved("kr2", -0.04)});
  for (const Isolation& i : r) EXPECT_EQ(i.fault, "air_gap");
}

TEST(FaultIsolation, IndependentFaultsStaySeparate) {
  // Coil 1 resistance and a sensor gain at once: each named, nothing else.
  const std::vector<Isolation> r = isolate({moved("R1", 0.2), moved("kr1", 0.05), moved("kr2", 0.05)});
  EXPECT_EQ(r[0].fault, "coil_resistance");
  EXPECT_EQ(r[0].channel, 1);
  EXPECT_EQ(r[1].fault, "sensor_gain");
  EXPECT_EQ(r[2].fault, "sensor_gain");
  EXPECT_TRUE(isolate({}).empty());
}

TEST(FaultIsolation, Vocabulary) {
  for (const char* f : {"coil_resistance", "amplifier_gain", "amplifier_bandwidth", "eddy_current", "sensor_delay",
                        "sensor_gain", "flexible_mode", "magnetic_saturation", "air_gap", "rotor_mass",
                        "harmonic_disturbance", "force_factor"})
    EXPECT_TRUE(is_known_fault(f)) << f;
  EXPECT_FALSE(is_known_fault("shorted_turns"));
}

TEST(FaultIsolation, RefusesBadInput) {
  EXPECT_THROW(isolate({moved("m", 0.1)}), Error);
  EXPECT_THROW(isolate({moved("R1", 0.1), moved("R1", 0.1)}), Error);
  EXPECT_THROW(isolate({{"R1", std::nan(""), 0.0}}), Error);
  EXPECT_THROW(parameter_role("v5"), Error);
}

}  // namespace
}  // namespace ambid::diag
