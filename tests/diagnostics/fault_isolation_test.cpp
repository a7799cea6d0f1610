// Fault isolation against the model-derived closed-loop signatures (fault_signatures.hpp):
// deviation vectors built from a known fault (its signature times a change, plus seeded noise)
// must be named after that fault, and changes no fault explains after their own parameter.
#include "diagnostics/fault_isolation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.hpp"
#include "diagnostics/identified_estimates.hpp"
#include "diagnostics/plant_families.hpp"

namespace ambid::diag {
namespace fault_isolation_test {

constexpr double kSigma = 0.003;  // relative one-sigma of every deviation

Deviation moved(const std::string& parameter, double relative) { return {parameter, relative, kSigma}; }

const FaultHypothesis& hypothesis(const std::string& subject) {
  for (const FaultHypothesis& h : default_fault_hypotheses())
    if (h.subject == subject) return h;
  throw Error("no hypothesis " + subject);
}

// Every monitored parameter: `change` times the signature of each fault given, plus noise; a
// parameter counts as moved when its change is beyond 4 sigma (what the detectors would raise).
std::vector<Deviation> deviations(const std::vector<std::pair<std::string, double>>& faults, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, kSigma);
  std::vector<Deviation> out;
  for (const std::string& p : monitored_parameters("amb1dof_voltage")) {
    double relative = noise(rng);
    for (const auto& [subject, change] : faults) relative += change * hypothesis(subject).signature.at(p);
    out.push_back({p, relative, kSigma, std::abs(relative) > 4 * kSigma});
  }
  return out;
}

std::string describe(const std::vector<Deviation>& d) {
  std::string text;
  for (const Deviation& x : d) text += " " + x.parameter + (x.moved ? "*" : "") + "=" + std::to_string(x.relative);
  return text;
}

// The heart of it: each fault, at several sizes and both signs, is named for every parameter
// that moved, though it moves several (R1 +20 % also moves ks by about -8 %).
TEST(FaultIsolation, EveryFaultIsNamedFromItsFullSignature) {
  std::uint64_t seed = 1;
  for (const FaultHypothesis& h : default_fault_hypotheses()) {
    for (double change : {-0.2, -0.05, 0.05, 0.1, 0.2}) {
      const std::vector<Deviation> d = deviations({{h.subject, change}}, seed++);
      const std::vector<Isolation> r = isolate(d);
      std::size_t count = 0;
      for (const Deviation& x : d) count += x.moved ? 1 : 0;
      ASSERT_EQ(r.size(), count) << h.subject << describe(d);
      for (const Isolation& i : r) {
        EXPECT_EQ(i.fault, h.fault) << h.subject << " " << change << ": " << i.parameter << describe(d);
        EXPECT_EQ(i.channel, h.channel) << h.subject << " " << change << ": " << i.parameter << describe(d);
        EXPECT_EQ(i.subject, h.subject) << h.subject << " " << change << ": " << i.parameter;
      }
    }
  }
}

// R1 +20 % in the loop: the alert on R1 names coil 1 alone, those on ks, kr1, kr2 name coil 1
// and the parameter (shared).
TEST(FaultIsolation, HotCoilNamesCoilOneForTheCurrentsItMoved) {
  const std::vector<Deviation> d = deviations({{"coil 1 resistance", 0.2}}, 77);
  const std::vector<Isolation> r = isolate(d);
  ASSERT_EQ(r.size(), 4u) << describe(d);  // R1, kr1, kr2, ks
  for (const Isolation& i : r) {
    EXPECT_EQ(i.fault, "coil_resistance");
    EXPECT_EQ(i.channel, 1);
    EXPECT_EQ(i.shared, i.parameter != "R1") << i.parameter;
  }
}

// A change no fault predicts (R1 alone, the currents unmoved) is not forced onto a fault: it
// keeps its own, and so does each unexplained part.
TEST(FaultIsolation, UnexplainedChangeKeepsItsOwnFault) {
  std::vector<Deviation> d = deviations({}, 5);
  d[0] = moved("R1", 0.2);
  std::vector<Isolation> r = isolate(d);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].fault, "coil_resistance");
  EXPECT_EQ(r[0].channel, 1);
  EXPECT_FALSE(r[0].shared);
  // kr1 and kr2 opposite: neither the sensor gain (alike) nor one force factor explains it.
  d = deviations({}, 6);
  d[4] = moved("kr1", 0.05);
  d[5] = moved("kr2", -0.05);
  r = isolate(d);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].fault, "force_factor");
  EXPECT_EQ(r[0].channel, 1);
  EXPECT_EQ(r[1].fault, "force_factor");
  EXPECT_EQ(r[1].channel, 2);
}

TEST(FaultIsolation, TwoIndependentFaultsAreBothNamed) {
  // Coil 1 resistance +20 % and the sensor gain +15 % at once: R1 and ks (moved by the
  // currents alone) are coil 1, kr1 and kr2 (the sensor's +15 % outweighs the currents' -4 %)
  // the sensor.
  for (std::uint64_t seed = 10; seed < 30; ++seed) {
    const std::vector<Deviation> d =
        deviations({{"coil 1 resistance", 0.2}, {"position sensor gain (kr1, kr2 alike)", 0.15}}, seed);
    const std::vector<Isolation> r = isolate(d);
    for (const Isolation& i : r) {
      if (i.parameter == "R1" || i.parameter == "ks") {
        EXPECT_EQ(i.fault, "coil_resistance") << i.parameter << describe(d);
        EXPECT_EQ(i.channel, 1) << i.parameter;
      } else {
        EXPECT_EQ(i.fault, "sensor_gain") << i.parameter << describe(d);
        EXPECT_EQ(i.channel, std::nullopt) << i.parameter;
      }
    }
    EXPECT_EQ(r.size(), 4u) << describe(d);
  }
}

// With only the moved parameters given, each alone is its own fault (ties among the faults
// that predict it go to the one it stands for).
TEST(FaultIsolation, OneParameterAloneNamesItsOwnFault) {
  struct Case {
    const char* parameter;
    const char* fault;
    std::optional<int> channel;
    const char* subject;
  };
  for (const Case c :
       {Case{"R1", "coil_resistance", 1, "coil 1 resistance"}, Case{"R2", "coil_resistance", 2, "coil 2 resistance"},
        Case{"kw1", "amplifier_gain", 1, "amplifier 1 gain"}, Case{"kw2", "amplifier_gain", 2, "amplifier 2 gain"},
        Case{"kr1", "force_factor", 1, "coil 1 force factor"}, Case{"kr2", "force_factor", 2, "coil 2 force factor"},
        Case{"ks", "air_gap", {}, "air gap"}}) {
    const std::vector<Isolation> r = isolate({moved(c.parameter, 0.2)});
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].parameter, c.parameter);
    EXPECT_EQ(r[0].fault, c.fault) << c.parameter;
    EXPECT_EQ(r[0].channel, c.channel) << c.parameter;
    EXPECT_EQ(r[0].subject, c.subject) << c.parameter;
    EXPECT_EQ(r[0].shared, std::string(c.parameter) == "ks") << c.parameter;
    EXPECT_TRUE(is_known_fault(r[0].fault));
  }
  EXPECT_TRUE(isolate({}).empty());
  EXPECT_TRUE(isolate({{"R1", 0.001, kSigma, false}}).empty());
}

TEST(FaultIsolation, Vocabulary) {
  for (const char* f :
       {"coil_resistance", "amplifier_gain", "amplifier_bandwidth", "eddy_current", "sensor_delay", "sensor_gain",
        "flexible_mode", "magnetic_saturation", "air_gap", "rotor_mass", "harmonic_disturbance", "force_factor"})
    EXPECT_TRUE(is_known_fault(f)) << f;
  EXPECT_FALSE(is_known_fault("shorted_turns"));
  for (const FaultHypothesis& h : default_fault_hypotheses()) EXPECT_TRUE(is_known_fault(h.fault)) << h.subject;
}

TEST(FaultIsolation, RefusesBadInput) {
  EXPECT_THROW(isolate({moved("m", 0.1)}), Error);
  EXPECT_THROW(isolate({moved("R1", 0.1), moved("R1", 0.1)}), Error);
  EXPECT_THROW(isolate({{"R1", std::nan(""), 0.0}}), Error);
  EXPECT_THROW(parameter_role("amb1dof_voltage", "v5"), Error);
  IsolationConfig bad;
  bad.sigma_slack = 0.0;
  EXPECT_THROW(isolate({moved("R1", 0.1)}, bad), Error);
  bad = {};
  bad.hypotheses = {{"shorted_turns", 1, "coil 1 turns", {"kr1"}, {}}};
  EXPECT_THROW(isolate({moved("R1", 0.1)}, bad), Error);
}

}  // namespace fault_isolation_test
}  // namespace ambid::diag
