// The plant description: its content id, the header it stands for, and windows read with the
// description their batches name (described_windows.hpp), against simulated lqr and pid loops.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "plant_sim/scenario.hpp"
#include "services/convert/plant_description.hpp"
#include "services/convert/plant_samples.hpp"
#include "services/daemons/described_windows.hpp"
#include "services/daemons/description_change.hpp"
#include "services/daemons/identify_window.hpp"

namespace ambid::daemons {
namespace plant_description_test {

using convert::describe;
using Event = DescribedWindows::Event;

Experiment header(const std::string& controller, double R1 = 17.5) {
  sim::ScenarioOptions o;
  o.controller = controller;
  o.duration = 0.2;
  Experiment h = sim::build_scenario(o).header;
  h.plant.parameters["R1"] = R1;
  return h;
}

TEST(PlantDescription, IdIsAHashOfTheContentAndTheHeaderComesBackExactly) {
  const Experiment lqr = header("lqr");
  const bus::PlantDescription d = describe(lqr, "bearing-1");
  ASSERT_EQ(d.description_id.size(), 16u);
  EXPECT_EQ(describe(lqr, "bearing-2").description_id, d.description_id);  // not the plant id
  EXPECT_NE(describe(header("pid"), "bearing-1").description_id, d.description_id);
  EXPECT_NE(describe(header("lqr", 17.5 * (1 + 1e-15)), "bearing-1").description_id, d.description_id);
  const Experiment back = convert::experiment_header(d);
  EXPECT_EQ(back.plant.parameters, lqr.plant.parameters);
  EXPECT_EQ(back.operating_point, lqr.operating_point);
  EXPECT_EQ(back.r_names, lqr.r_names);
  ASSERT_TRUE(back.controller);
  EXPECT_EQ(back.controller->A, lqr.controller->A);  // bit for bit
  EXPECT_EQ(back.controller->B, lqr.controller->B);
  EXPECT_EQ(back.controller->D, lqr.controller->D);
}

TEST(PlantDescription, ControllerLimitsTravelAndBadContentIsRefused) {
  Experiment h = header("pid");
  h.controller->output_limits = {{0.0, 10.5}, Limit{}};  // the second input unclamped
  const bus::PlantDescription d = describe(h, "b");
  EXPECT_EQ(d.controller.output_limits.rows, 2u);
  const Experiment back = convert::experiment_header(d);
  ASSERT_EQ(back.controller->output_limits.size(), 2u);
  EXPECT_EQ(back.controller->output_limits[0].lo, 0.0);
  EXPECT_EQ(back.controller->output_limits[0].hi, 10.5);
  EXPECT_TRUE(std::isinf(back.controller->output_limits[1].lo) && std::isinf(back.controller->output_limits[1].hi));
  EXPECT_TRUE(back.controller->state_limits.empty());

  bus::PlantDescription tampered = d;
  tampered.parameters[0].value *= 2;
  EXPECT_THROW(
      try { convert::experiment_header(tampered); } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("does not match its content"), std::string::npos) << e.what();
        throw;
      },
      Error);
  bus::PlantDescription wrong = d;
  wrong.controller.matrices.b.cols += 1;  // B no longer matches the inputs
  wrong.controller.matrices.b.values.resize(wrong.controller.matrices.b.rows * wrong.controller.matrices.b.cols);
  wrong.description_id = convert::description_id(wrong);
  EXPECT_THROW(convert::experiment_header(wrong), Error);
  bus::PlantDescription unvalidated = d;  // as a writer that skipped validate() might send it
  unvalidated.controller.matrices.a.values.pop_back();
  unvalidated.description_id = convert::description_id(unvalidated);
  EXPECT_THROW(
      try { convert::experiment_header(unvalidated); } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("controller.A holds"), std::string::npos) << e.what();
        throw;
      },
      Error);
}

TEST(DescribedWindows, BatchesWaitForTheirDescriptionAndAnotherDescriptionRestartsTheWindow) {
  sim::ScenarioOptions o;
  o.duration = 0.2;
  const Experiment lqr = sim::simulate_scenario(o);
  o.controller = "pid";
  const Experiment pid = sim::simulate_scenario(o);
  const bus::PlantDescription dl = describe(lqr, "b"), dp = describe(pid, "b");
  auto batch = [](const Experiment& e, const bus::PlantDescription& d, std::uint64_t seq) {
    bus::PlantSamples b = convert::sample_batch(e, Eigen::Index(seq) * 100, 100, "b", seq, 0.0);
    b.description_id = d.description_id;
    return b;
  };
  DescribedWindows w({.window = 0.03, .settle = 0.0, .max_waiting_batches = 2});
  EXPECT_EQ(w.add(batch(lqr, dl, 0)).at(0).event, Event::waiting);
  EXPECT_EQ(w.add(batch(lqr, dl, 1)).at(0).event, Event::waiting);
  const auto dropped = w.add(batch(lqr, dl, 2));  // the third: the oldest goes
  ASSERT_EQ(dropped.size(), 2u);
  EXPECT_EQ(dropped[1].event, Event::dropped_no_description);
  EXPECT_EQ(dropped[1].samples, 100u);
  EXPECT_NEAR(dropped[1].from, lqr.t(0), 1e-12);  // batch 0: samples 0..99, plant time of 100 samples
  EXPECT_NEAR(dropped[1].to, lqr.t(0) + 100 * lqr.sample_time, 1e-12);
  const auto released = w.describe(dl);  // batches 1 and 2 go to a window of the lqr loop
  EXPECT_EQ(released.at(0).event, Event::description_change);
  EXPECT_EQ(w.buffered(), 200);
  EXPECT_FALSE(w.full());
  const auto swapped = w.add(batch(pid, dp, 0));  // not yet described: waits
  EXPECT_EQ(swapped.at(0).event, Event::waiting);
  const auto changed = w.describe(dp);
  ASSERT_GE(changed.size(), 1u);
  EXPECT_EQ(changed[0].event, Event::description_change);
  EXPECT_EQ(changed[0].samples, 200u);  // the lqr samples never share a window with pid ones
  EXPECT_EQ(w.current()->description_id, dp.description_id);
  EXPECT_EQ(w.add(batch(pid, dp, 1)).at(0).event, Event::added);
  EXPECT_EQ(w.add(batch(pid, dp, 2)).at(0).event, Event::added);
  ASSERT_TRUE(w.full());
  const Experiment window = w.take();
  EXPECT_EQ(window.controller->A, pid.controller->A);
  EXPECT_EQ(window.y, pid.y.topRows(300));
  bus::PlantDescription bad = dl;
  bad.description_id = "0000000000000000";
  EXPECT_THROW(w.describe(bad), Error);
}

// Why the description travels: a window of the pid loop read with the lqr controller (what a
// daemon with a local scenario file did) is nonsense; read with its own description it is right.
TEST(DescribedWindows, AWindowReadWithItsOwnControllerIdentifiesTheBearingAnotherDoesNot) {
  sim::ScenarioOptions o;
  o.controller = "pid";
  o.amplitude = 1.0;
  o.position_noise = 1e-9;
  o.current_noise = 1e-6;
  o.duration = 0.5;
  const Experiment pid = sim::simulate_scenario(o);
  auto r1 = [&](const Experiment& header) {
    convert::SampleWindow window(header, 2500, 2500);
    for (std::uint64_t seq = 0; seq < 10; ++seq)
      window.add(convert::sample_batch(pid, Eigen::Index(seq) * 500, 500, "b", seq, 0.0));
    // closed-loop reads r -> y through the controller (pem needs it only for a starting point)
    for (const auto& p : identify_window(window.take(), "b", 0, window_identify_options("closed-loop")).physical)
      if (p.name == "R1") return p.value;
    return 0.0;
  };
  EXPECT_NEAR(r1(convert::experiment_header(describe(pid, "b"))), 17.5, 0.05 * 17.5);
  const Experiment lqr = header("lqr");
  double wrong = 0.0;
  try {
    wrong = r1(lqr);
  } catch (const Error&) {
    wrong = -1.0;  // or refused outright
  }
  RecordProperty("R1_with_the_wrong_controller", std::to_string(wrong));
  EXPECT_FALSE(std::abs(wrong - 17.5) < 0.25 * 17.5) << "R1 read with the wrong controller: " << wrong;
}

TEST(DescriptionChange, ControllerKeepsTheBearingParametersMakeAnother) {
  const bus::PlantDescription lqr = describe(header("lqr"), "b"), pid = describe(header("pid"), "b"),
                              hot = describe(header("pid", 21.0), "b");
  EXPECT_EQ(classify(nullptr, lqr), DescriptionChange::first);
  EXPECT_EQ(classify(&lqr, lqr), DescriptionChange::same);
  EXPECT_EQ(classify(&lqr, pid), DescriptionChange::controller);
  EXPECT_EQ(classify(&pid, hot), DescriptionChange::bearing);
  EXPECT_EQ(bearing_difference(pid, hot), "R1 17.5 -> 21");
}

}  // namespace plant_description_test
}  // namespace ambid::daemons
