// The closed-loop fault signatures (diagnostics/fault_signatures.hpp) against what the physics
// fixes analytically, and the settled-and-linearised parameters against the identifier
// (identify_experiment, closed-loop) on simulated data of the same faulty loop.
#include "diagnostics/fault_signatures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "identifier/identify_experiment.hpp"
#include "plant_sim/amb1dof_parameters.hpp"
#include "plant_sim/scenario.hpp"

namespace ambid::diag {
namespace fault_signatures_test {

Experiment loop_header() {
  sim::ScenarioOptions o;
  o.excitation = "none";
  return sim::build_scenario(o).header;
}

const FaultHypothesis& hypothesis(const std::string& subject) {
  for (const FaultHypothesis& h : default_fault_hypotheses())
    if (h.subject == subject) return h;
  throw Error("no hypothesis " + subject);
}

// At the nominal plant the loop settles at the nominal operating point: kr = K i0 / (2 x0^2),
// ks = 2 K i0^2 / (2 x0^3), R and kw as given.
TEST(FaultSignatures, NominalLoopSettlesAtTheNominalParameters) {
  const sim::Amb1dofParameters p = sim::Amb1dofParameters::nominal();
  const auto s = settled_parameters(loop_header(), {});
  const double kr = p.K1 * p.i0 / (2 * p.x0 * p.x0), ks = 2 * p.K1 * p.i0 * p.i0 / (2 * p.x0 * p.x0 * p.x0);
  EXPECT_NEAR(s.at("R1"), p.R1, 1e-6 * p.R1);
  EXPECT_NEAR(s.at("R2"), p.R2, 1e-6 * p.R2);
  EXPECT_NEAR(s.at("kw1"), p.kw1, 1e-6);
  EXPECT_NEAR(s.at("kw2"), p.kw2, 1e-6);
  EXPECT_NEAR(s.at("kr1"), kr, 1e-6 * kr);
  EXPECT_NEAR(s.at("kr2"), kr, 1e-6 * kr);
  EXPECT_NEAR(s.at("ks"), ks, 1e-6 * ks);
}

// R1 +20 %: the coil is read right, and since x = 0 and K1 = K2 force equal currents, ks moves
// as the square of the current and kr1, kr2 as the current itself.
TEST(FaultSignatures, HotCoilLowersTheBiasCurrents) {
  const sim::Amb1dofParameters p = sim::Amb1dofParameters::nominal();
  const auto nominal = settled_parameters(loop_header(), {});
  const auto s = settled_parameters(loop_header(), {{"R1", 1.2 * p.R1}});
  EXPECT_NEAR(s.at("R1"), 1.2 * p.R1, 1e-6 * p.R1);
  EXPECT_NEAR(s.at("R2"), p.R2, 1e-6 * p.R2);
  EXPECT_NEAR(s.at("kw1"), p.kw1, 1e-6);
  const double current = s.at("kr1") / nominal.at("kr1");  // i / i0
  EXPECT_NEAR(s.at("kr2") / nominal.at("kr2"), current, 1e-6);
  EXPECT_NEAR(s.at("ks") / nominal.at("ks"), current * current, 1e-6);
  EXPECT_LT(current, 0.99);  // the currents do fall: the whole point of the signatures
  ::testing::Test::RecordProperty("bias_current_ratio_R1_plus_20", std::to_string(current));
}

TEST(FaultSignatures, AnalyticColumns) {
  // m enters v1, v2, v3 as 1/m only and the operating point not at all: the central
  // difference of 1/m over +-h is exactly -1/(1 - h^2).
  const double h = SignatureOptions{}.relative_step;
  const FaultHypothesis& mass = hypothesis("rotor mass (ks, kr1, kr2 alike)");
  for (const char* p : {"ks", "kr1", "kr2"}) EXPECT_NEAR(mass.signature.at(p), -1.0 / (1.0 - h * h), 1e-6) << p;
  for (const char* p : {"R1", "R2", "kw1", "kw2"}) EXPECT_NEAR(mass.signature.at(p), 0.0, 1e-6) << p;
  // The sensor gain scales v2, v3 (kr per sensed metre) and leaves v1, R, kw.
  const FaultHypothesis& sensor = hypothesis("position sensor gain (kr1, kr2 alike)");
  for (const char* p : {"kr1", "kr2"}) EXPECT_NEAR(sensor.signature.at(p), 1.0, 1e-4) << p;
  for (const char* p : {"ks", "R1", "R2", "kw1", "kw2"}) EXPECT_NEAR(sensor.signature.at(p), 0.0, 1e-6) << p;
  // Coil and amplifier faults: their own parameter 1:1, the other channel's 0, ks twice kr.
  for (const char* subject : {"coil 1 resistance", "coil 2 resistance", "amplifier 1 gain", "amplifier 2 gain"}) {
    const FaultHypothesis& f = hypothesis(subject);
    EXPECT_NEAR(f.signature.at(f.own.front()), 1.0, 1e-6) << subject;
    for (const char* p : {"R1", "R2", "kw1", "kw2"}) {
      if (p != f.own.front()) {
        EXPECT_NEAR(f.signature.at(p), 0.0, 1e-6) << subject << " " << p;
      }
    }
    EXPECT_NEAR(f.signature.at("kr1"), f.signature.at("kr2"), 1e-6) << subject;
    // Exactly 2 for the derivative; the central difference over +-5 % differs by O(h^2).
    EXPECT_NEAR(f.signature.at("ks"), 2.0 * f.signature.at("kr1"), 1e-3) << subject;
    EXPECT_GT(std::abs(f.signature.at("kr1")), 0.05) << subject;
  }
  // The force constant K1 also sets L1 = Ls1 + K1/(2 x0), through which R1 and kw1 are read:
  // d log R1 = d log kw1 = -(K1/(2 x0)) / L1.
  const sim::Amb1dofParameters p = sim::Amb1dofParameters::nominal();
  const double share = p.K1 / (2 * p.x0) / p.L1();
  const FaultHypothesis& k1 = hypothesis("coil 1 force factor");
  EXPECT_NEAR(k1.signature.at("R1"), -share, 3e-3);  // O(h^2) of the central difference
  EXPECT_NEAR(k1.signature.at("kw1"), -share, 3e-3);
  EXPECT_NEAR(k1.signature.at("R2"), 0.0, 1e-6);
}

// The signatures belong to the loop: with the decentralised PID controller of `ambid sim
// --controller pid` the currents move differently, but the physics relations still hold.
TEST(FaultSignatures, FollowTheRecordedController) {
  sim::ScenarioOptions o;
  o.excitation = "none";
  o.controller = "pid";
  const std::vector<FaultHypothesis> pid = closed_loop_fault_hypotheses(sim::build_scenario(o).header);
  ASSERT_EQ(pid.size(), default_fault_hypotheses().size());
  const FaultHypothesis& coil = pid[0];
  ASSERT_EQ(coil.subject, "coil 1 resistance");
  EXPECT_NEAR(coil.signature.at("R1"), 1.0, 1e-6);
  EXPECT_NEAR(coil.signature.at("kr1"), coil.signature.at("kr2"), 1e-6);
  EXPECT_NEAR(coil.signature.at("ks"), 2.0 * coil.signature.at("kr1"), 1e-3);
  // Each coil has a proportional current loop of kc = 1000 V/A (scenario.cpp) and the position
  // integral drives the coils differentially; at rest with i1 = i2 = i,
  //   R i0 + P - kc (i - i0) = R1 i,  R i0 - P - kc (i - i0) = R i
  // so i / i0 = 2 (R + kc) / (R1 + R + 2 kc): d log i / d log R1 = -R / (2 (R + kc)) = -0.0086,
  // against -0.234 with the observer controller, whose current feedback is weaker.
  const double R = sim::Amb1dofParameters::nominal().R1, kc = 1000.0;
  EXPECT_NEAR(coil.signature.at("kr1"), -R / (2.0 * (R + kc)), 2e-4);
}

TEST(FaultSignatures, RefusesWhatItCannotModel) {
  Experiment h = loop_header();
  EXPECT_THROW(settled_parameters(h, {{"Q", 1.0}}), Error);
  EXPECT_THROW(settled_parameters(h, {}, 0.0), Error);
  SignatureOptions short_run;
  short_run.settle_time = 0.02;  // 200 samples: the loop is still moving
  EXPECT_THROW(settled_parameters(h, {{"R1", 21.0}}, 1.0, short_run), Error);
  h.controller.reset();
  EXPECT_THROW(settled_parameters(h, {}), Error);
}

}  // namespace fault_signatures_test
}  // namespace ambid::diag
