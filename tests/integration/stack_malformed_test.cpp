// Malformed input to running daemons: refused, counted in their Health (the `rejected`
// counter that `ambid status` shows), never a crash; good input afterwards is still served.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <optional>
#include <string>
#include <thread>

#include "plant_sim/scenario.hpp"
#include "services/bus/make_bus.hpp"
#include "services/convert/plant_description.hpp"
#include "stack_support.hpp"

namespace ambid::testing {
namespace stack_malformed_test {

using namespace std::chrono_literals;

template <class Predicate>
bool wait_for(bus::Bus& b, std::chrono::seconds limit, Predicate done) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (done()) return true;
    b.wait(100ms);
  }
  return done();
}

// One good batch of 500 samples of the nominal simulation, naming its plant description.
bus::PlantSamples good_batch(const Experiment& e, std::uint64_t seq) {
  bus::PlantSamples b;
  b.plant_id = "bearing-1";
  b.description_id = convert::describe(e, "bearing-1").description_id;
  b.seq = seq;
  b.t0 = e.t(Eigen::Index(seq) * 500);
  b.sample_time = e.sample_time;
  b.count = 500;
  b.y_names = e.y_names;
  b.u_names = e.u_names;
  b.r_names = e.r_names;
  for (Eigen::Index k = Eigen::Index(seq) * 500; k < Eigen::Index(seq + 1) * 500; ++k) {
    for (Eigen::Index j = 0; j < e.y.cols(); ++j) b.y.push_back(e.y(k, j));
    for (Eigen::Index j = 0; j < e.u.cols(); ++j) b.u.push_back(e.u(k, j));
    for (Eigen::Index j = 0; j < e.r.cols(); ++j) b.r.push_back(e.r(k, j));
  }
  return b;
}

TEST(StackMalformed, IdentifierRejectsAndCountsBadSamplesThenIdentifiesGoodOnes) {
  Stack stack("stack_malformed", 175);
  stack.start("identifier", {"--metrics-port", "19175"});
  auto b = bus::make_bus("fastdds", 175);
  auto samples = b->writer<bus::PlantSamples>();
  auto models = b->reader<bus::IdentifiedModel>();
  auto health = b->reader<bus::Health>();
  ASSERT_TRUE(wait_for(*b, 10s, [&] { return samples->matched() > 0; }));

  sim::ScenarioOptions o;
  o.duration = 0.6;
  const Experiment e = sim::simulate_scenario(o);
  auto descriptions = b->writer<bus::PlantDescription>();  // transient-local: waits for the identifier
  descriptions->write(convert::describe(e, "bearing-1"));
  // Our writer matching the identifier does not mean the identifier matched us yet (discovery
  // is asymmetric, and a volatile reader drops what came before): offer one batch (a tenth of
  // a window, never identified) until the identifier's Health counts it, then count from there.
  std::optional<bus::Health> last;
  // The daemon writes one Health per node (itself and each plant) with the same counts; take()
  // may return them grouped by instance, so the newest is the one with the latest time.
  auto identifier_health = [&] {
    for (auto& h : health->take())
      if (h.role == "identifier" && (!last || h.time >= last->time)) last = h;
    return last.has_value();
  };
  bool counted = false;
  for (int attempt = 0; attempt < 20 && !counted; ++attempt) {
    samples->write(good_batch(e, 0));
    counted = wait_for(*b, 2s, [&] { return identifier_health() && last->received > 0; });
  }
  ASSERT_TRUE(counted) << stack.log("identifier");
  std::this_thread::sleep_for(1500ms);  // the next Health (1 s period) has every offered batch
  identifier_health();
  const std::uint64_t received_before = last->received;
  // Oversized or inconsistent: the bus refuses to send it at all.
  bus::PlantSamples oversized = good_batch(e, 0);
  oversized.y.resize(bus::limits::max_batch_values + 1, 0.0);
  EXPECT_THROW(samples->write(oversized), bus::InvalidMessage);
  // Well-formed on the wire but wrong for the plant: the identifier refuses them.
  bus::PlantSamples nan = good_batch(e, 0);
  nan.y[5] = std::nan("");
  bus::PlantSamples names = good_batch(e, 0);
  names.y_names[0] = "z";
  bus::PlantSamples rate = good_batch(e, 0);
  rate.sample_time = 1e-3;
  for (const auto* bad : {&nan, &names, &rate}) samples->write(*bad);
  // Then 0.5 s of good samples: 0.25 s settling, one 0.25 s window.
  for (std::uint64_t seq = 0; seq < 10; ++seq) samples->write(good_batch(e, seq));

  std::vector<bus::IdentifiedModel> got;
  ASSERT_TRUE(wait_for(*b, 20s, [&] {
    for (auto& m : models->take()) got.push_back(m);
    return !got.empty();
  })) << stack.log("identifier");
  EXPECT_EQ(got[0].plant_id, "bearing-1");
  EXPECT_NEAR(got[0].window, 0.25, 1e-9);
  ASSERT_TRUE(wait_for(*b, 5s, [&] {
    identifier_health();
    return last->received == received_before + 13;
  })) << last->received - received_before;
  EXPECT_EQ(last->errors, 3u);
  EXPECT_EQ(last->published, 1u);
  // The same counts in the Prometheus metrics.
  const std::string metrics = http_get(19175, "/metrics");
  EXPECT_THAT(metrics, ::testing::HasSubstr("ambid_messages_rejected_total{role=\"identifier\"} 3"));
  EXPECT_THAT(metrics, ::testing::HasSubstr("ambid_messages_received_total{role=\"identifier\"} " +
                                            std::to_string(received_before + 13)));
  EXPECT_THAT(metrics, ::testing::HasSubstr("ambid_identification_seconds_count{role=\"identifier\"} 1"));
  EXPECT_THAT(metrics, ::testing::HasSubstr("ambid_samples_received_total{role=\"identifier\"} " +
                                            std::to_string((received_before + 13) * 500)));
  EXPECT_THAT(metrics,
              ::testing::HasSubstr("ambid_samples_dropped_total{reason=\"rejected\",role=\"identifier\"} 1500"));
  EXPECT_THAT(metrics, ::testing::HasSubstr("ambid_samples_dropped_total{reason=\"gap\",role=\"identifier\"} 0"));
  // A sequence gap: 7 batches (0.25 s settling, 1000 samples buffered), then batch 8 without 7:
  // the 1000 buffered samples are dropped and counted.
  for (std::uint64_t seq = 0; seq < 7; ++seq) samples->write(good_batch(e, seq));
  samples->write(good_batch(e, 8));
  ASSERT_TRUE(wait_for(*b, 5s, [&] {
    identifier_health();
    return last->received == received_before + 21;
  })) << last->received - received_before;
  const std::string after_gap = http_get(19175, "/metrics");
  EXPECT_THAT(after_gap, ::testing::HasSubstr("ambid_samples_dropped_total{reason=\"gap\",role=\"identifier\"} 1000"));
  EXPECT_THAT(after_gap,
              ::testing::HasSubstr("ambid_samples_dropped_total{reason=\"unidentified\",role=\"identifier\"} 0"));
  EXPECT_THAT(stack.log("identifier"),
              ::testing::HasSubstr("1000 samples dropped: batch 8 does not follow the previous one"));
  const std::string log = stack.log("identifier");
  EXPECT_THAT(log, ::testing::HasSubstr("a sample value is not finite"));
  EXPECT_THAT(log, ::testing::HasSubstr("signal names differ"));
  EXPECT_THAT(log, ::testing::HasSubstr("sample time 0.001"));
}

TEST(StackMalformed, PlantRefusesExcitationOutsideItsLimits) {
  Stack stack("stack_excitation", 176);
  stack.start("plant");
  auto b = bus::make_bus("cyclone", 176);
  auto commands = b->writer<bus::ExcitationCommand>();
  auto health = b->reader<bus::Health>();
  ASSERT_TRUE(wait_for(*b, 10s, [&] { return commands->matched() > 0; }));
  std::this_thread::sleep_for(1s);
  bus::ExcitationCommand c;
  c.plant_id = "bearing-1";
  c.kind = "multisine";
  c.amplitude = 5.0;  // limit 0.5 V
  c.seq = 1;
  commands->write(c);
  c.amplitude = 0.1;
  c.frequencies = {10.0, 5000.0};  // limit 2000 Hz
  c.seq = 2;
  commands->write(c);
  c.kind = "square";
  c.frequencies = {};
  c.seq = 3;
  commands->write(c);
  std::optional<bus::Health> last;
  ASSERT_TRUE(wait_for(*b, 10s, [&] {
    for (auto& h : health->take())
      if (h.role == "plant" && (!last || h.time >= last->time)) last = h;
    return last && last->errors == 3;
  })) << stack.log("plant");
  EXPECT_EQ(last->level, bus::AlertLevel::warn);
  const std::string log = stack.log("plant");
  EXPECT_THAT(log, ::testing::HasSubstr("amplitude 5.000000 V outside 0..0.500000 V"));
  EXPECT_THAT(log, ::testing::HasSubstr("frequency 5000.000000 Hz outside"));
  EXPECT_THAT(log, ::testing::HasSubstr("unknown excitation kind 'square'"));
}

}  // namespace stack_malformed_test
}  // namespace ambid::testing

namespace ambid::testing {
namespace stack_malformed_test {

// A method the identifier does not know is refused at start, naming the known ones; the
// daemon exits 1 before it joins the bus (domain 196).
TEST(StackMalformed, IdentifierRefusesAnUnknownMethodAtStart) {
  const auto dir = cli_test::fresh_dir("stack_unknown_method");
  std::ofstream(dir / "identifier.json") << R"({"method": "least-squares"})";
  const CommandResult r =
      run_ambid("daemon identifier --dds cyclone --domain 196 --config " + (dir / "identifier.json").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("unknown method 'least-squares'"));
  EXPECT_THAT(r.output, ::testing::HasSubstr("closed-loop"));
}

// The continuous estimator's keys belong to rpem; on a batch method they are refused by name.
TEST(StackMalformed, IdentifierRefusesRecursiveKeysForABatchMethod) {
  const auto dir = cli_test::fresh_dir("stack_batch_carry");
  std::ofstream(dir / "identifier.json") << R"({"method": "pem", "carry": 0.5})";
  const CommandResult r =
      run_ambid("daemon identifier --dds cyclone --domain 196 --config " + (dir / "identifier.json").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("publish_rate, forgetting and carry are for method rpem only"));
}

}  // namespace stack_malformed_test
}  // namespace ambid::testing
