// The identifier daemon's computation on windows cut from a simulated stream, against the
// simulation's true parameters.
#include "services/daemons/identify_window.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "plant_sim/scenario.hpp"
#include "services/convert/plant_samples.hpp"

namespace ambid::daemons {
using convert::sample_batch;
using convert::SampleWindow;

namespace identify_window_test {

double physical(const bus::IdentifiedModel& m, const std::string& name) {
  for (const auto& e : m.physical)
    if (e.name == name) return e.value;
  ADD_FAILURE() << name << " missing";
  return 0.0;
}

// The second 0.25 s window of a simulated record, cut from its batches as the daemon does.
Experiment second_window(const sim::ScenarioOptions& o) {
  const Experiment record = sim::simulate_scenario(o);
  SampleWindow window(sim::build_scenario(o).header, 2500);
  for (std::uint64_t seq = 0; seq < 20; ++seq)
    EXPECT_NE(window.add(sample_batch(record, Eigen::Index(seq) * 500, 500, "p", seq, 0.0)).outcome,
              SampleWindow::Outcome::rejected);
  window.take();  // the first 0.25 s
  return window.take();
}

sim::ScenarioOptions one_second(std::map<std::string, double> truth = {}) {
  sim::ScenarioOptions o;
  o.duration = 1.0;
  o.true_parameters = std::move(truth);
  return o;
}

// A window from the middle of a record, where the controller's integrators are far from zero,
// identified with them taken as zero by the closed-loop method (which needs no controller
// state): the coil resistances come out within 0.1 % of the truth, nominal and with coil 1
// 20 % hot (the off-nominal case deadbeat reads as +9.9 %).
TEST(IdentifyWindow, ClosedLoopMidRecordWindowGivesTrueCoilResistances) {
  for (const double r1 : {17.5, 21.0}) {
    const Experiment w = second_window(one_second({{"R1", r1}}));
    EXPECT_NEAR(w.t(0), 0.25, 1e-9);
    const bus::IdentifiedModel m = identify_window(w, "p", 1, window_identify_options("closed-loop"));
    EXPECT_NEAR(physical(m, "R1") / r1, 1.0, 1e-3);
    EXPECT_NEAR(physical(m, "R2") / 17.5, 1.0, 1e-3);
    EXPECT_NEAR(m.time, w.t(2499), 1e-12);
    EXPECT_NEAR(m.window, 0.25, 1e-12);
    EXPECT_EQ(m.method, "closed-loop");
    EXPECT_EQ(m.physical.size(), 9u);
    for (const auto& e : m.physical) EXPECT_EQ(e.sigma, 0.0) << e.name << ": closed-loop reports no sigma";
  }
}

// deadbeat on the same nominal window: the offset term absorbs the zero integrator state, and
// it reports sigmas.
TEST(IdentifyWindow, DeadbeatMidRecordWindowGivesTrueCoilResistancesWithSigmas) {
  const sim::ScenarioOptions o = one_second();
  const Experiment w = second_window(o);
  const bus::IdentifiedModel m = identify_window(w, "p", 1, window_identify_options("deadbeat"));
  for (const char* name : {"R1", "R2"})
    EXPECT_NEAR(physical(m, name) / sim::build_scenario(o).header.plant.parameters.at(name), 1.0, 1e-3) << name;
  EXPECT_EQ(m.method, "deadbeat");
  for (const auto& e : m.physical) EXPECT_GT(e.sigma, 0.0) << e.name;
}

TEST(IdentifyWindow, UnknownMethodIsRefusedNamingTheKnownOnes) {
  try {
    window_identify_options("least-squares");
    FAIL() << "accepted an unknown method";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown method 'least-squares'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("closed-loop"), std::string::npos) << e.what();
  }
  EXPECT_THROW(window_identify_options("closed-loop", -1), Error);
}

TEST(SampleWindow, RejectsMalformedAndRestartsOnGaps) {
  sim::ScenarioOptions o;
  o.duration = 0.1;
  const sim::Scenario scenario = sim::build_scenario(o);
  const Experiment record = sim::simulate_scenario(o);
  SampleWindow window(scenario.header, 300);
  EXPECT_EQ(window.add(sample_batch(record, 0, 100, "p", 0, 0.0)).outcome, SampleWindow::Outcome::added);
  bus::PlantSamples bad = sample_batch(record, 100, 100, "p", 1, 0.0);
  bad.y.pop_back();
  EXPECT_EQ(window.add(bad).outcome, SampleWindow::Outcome::rejected);
  bad = sample_batch(record, 100, 100, "p", 1, 0.0);
  bad.u[7] = std::nan("");
  EXPECT_EQ(window.add(bad).outcome, SampleWindow::Outcome::rejected);
  EXPECT_EQ(window.buffered(), 100);
  // Batch 2 after batch 0: batch 1 was lost, the window starts again from batch 2.
  EXPECT_EQ(window.add(sample_batch(record, 200, 100, "p", 2, 0.0)).outcome, SampleWindow::Outcome::restarted);
  EXPECT_EQ(window.buffered(), 100);
  EXPECT_EQ(window.add(sample_batch(record, 300, 100, "p", 3, 0.0)).outcome, SampleWindow::Outcome::added);
  EXPECT_EQ(window.add(sample_batch(record, 400, 200, "p", 4, 0.0)).outcome, SampleWindow::Outcome::added);
  ASSERT_TRUE(window.full());
  const Experiment w = window.take();
  EXPECT_EQ(w.samples(), 300);
  EXPECT_DOUBLE_EQ(w.t(0), record.t(200));
  EXPECT_EQ(w.y.row(299), record.y.row(499));
  EXPECT_EQ(window.buffered(), 100);
}

}  // namespace identify_window_test
}  // namespace ambid::daemons

namespace ambid::daemons {
namespace identify_window_test {

TEST(SampleWindow, DropsTheSettlingSamplesOfEveryRecord) {
  sim::ScenarioOptions o;
  o.duration = 0.05;
  const Experiment record = sim::simulate_scenario(o);
  SampleWindow window(sim::build_scenario(o).header, 200, 150);
  window.add(sample_batch(record, 0, 100, "p", 0, 0.0));
  window.add(sample_batch(record, 100, 100, "p", 1, 0.0));
  EXPECT_EQ(window.buffered(), 50);
  // A new record (seq 0) drops its first 150 samples again.
  window.add(sample_batch(record, 0, 200, "p", 0, 1.0));
  EXPECT_EQ(window.buffered(), 50);
  EXPECT_EQ(window.add(sample_batch(record, 200, 200, "p", 1, 1.0)).outcome, SampleWindow::Outcome::added);
  const Experiment w = window.take();
  EXPECT_DOUBLE_EQ(w.t(0), record.t(150) + 1.0);
}

}  // namespace identify_window_test
}  // namespace ambid::daemons
