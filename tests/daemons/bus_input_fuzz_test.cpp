// What arrives from the bus or an operator, mutated (issue 18): sample batches into the
// identifier's window, identified models into the diagnostics' estimate windows, scenario
// files into the plant daemon's sim source. Each is taken or refused with ambid::Error; what is
// taken is valid (finite samples, a window that validates, finite estimates).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/experiment_file.hpp"
#include "core/json_text.hpp"
#include "fuzz/mutator.hpp"
#include "plant_sim/scenario.hpp"
#include "services/convert/estimate_window.hpp"
#include "services/convert/plant_samples.hpp"
#include "services/daemons/scenario_json.hpp"

namespace ambid::daemons {
namespace {

constexpr int kIterations = 400;

// A value that breaks something: non-finite, huge, tiny, negative zero.
double bad_value(std::mt19937_64& random) {
  constexpr double kValues[] = {std::numeric_limits<double>::quiet_NaN(),
                                std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity(),
                                1e308,
                                -1e308,
                                4.9e-324,
                                -0.0,
                                0.0};
  return kValues[std::uniform_int_distribution<std::size_t>(0, std::size(kValues) - 1)(random)];
}

std::string bad_name(std::mt19937_64& random) {
  const std::string kNames[] = {"", "x", "i1", std::string(5000, 'y'), std::string("a\0b", 3), "\xff\xfe"};
  return kNames[std::uniform_int_distribution<std::size_t>(0, std::size(kNames) - 1)(random)];
}

template <class T>
void mutate_vector(std::vector<T>& v, std::mt19937_64& random, const std::function<T()>& bad) {
  std::uniform_int_distribution<int> pick(0, 3);
  switch (pick(random)) {
    case 0:
      if (!v.empty()) v[std::uniform_int_distribution<std::size_t>(0, v.size() - 1)(random)] = bad();
      break;
    case 1:
      if (!v.empty()) v.pop_back();
      break;
    case 2:
      v.push_back(bad());
      break;
    default:
      v.clear();
      break;
  }
}

bus::PlantSamples mutated(bus::PlantSamples b, std::mt19937_64& random) {
  const std::function<double()> value = [&] { return bad_value(random); };
  const std::function<std::string()> name = [&] { return bad_name(random); };
  switch (std::uniform_int_distribution<int>(0, 7)(random)) {
    case 0:
      b.count = std::uniform_int_distribution<std::uint32_t>(0, 2 * b.count + 2)(random);
      break;
    case 1:
      mutate_vector(b.y, random, value);
      break;
    case 2:
      mutate_vector(b.u, random, value);
      break;
    case 3:
      mutate_vector(b.r, random, value);
      break;
    case 4:
      mutate_vector(b.y_names, random, name);
      break;
    case 5:
      b.sample_time = bad_value(random);
      break;
    case 6:
      b.t0 = bad_value(random);
      break;
    default:
      b.seq = std::uniform_int_distribution<std::uint64_t>(0, 1000)(random);
      break;
  }
  return b;
}

TEST(BusInputFuzz, SampleBatchesAreTakenOrRefusedAndWindowsStayValid) {
  sim::ScenarioOptions o;
  o.duration = 0.2;
  o.position_noise = 1e-7;
  o.current_noise = 1e-3;
  const Experiment e = sim::simulate_scenario(o);
  Experiment header = e;
  convert::SampleWindow window(header, 300, 10);
  std::mt19937_64 random(21);
  int refused = 0, windows = 0;
  for (int i = 0; i < kIterations; ++i) {
    const std::uint64_t seq = std::uint64_t(i % 40);
    bus::PlantSamples batch = convert::sample_batch(e, Eigen::Index(seq) * 50, 50, "bearing-1", seq, 0.0);
    if (i % 10 == 0) batch = mutated(batch, random);
    try {
      if (window.add(batch).outcome == convert::SampleWindow::Outcome::rejected) ++refused;
    } catch (const Error&) {
      ++refused;
    }
    while (window.full()) {
      const Experiment w = window.take();
      EXPECT_NO_THROW(w.validate());
      ++windows;
    }
  }
  EXPECT_GT(refused, kIterations / 40);
  EXPECT_GT(windows, 10);
}

bus::IdentifiedModel valid_model() {
  bus::IdentifiedModel m;
  m.plant_id = "bearing-1";
  m.seq = 4;
  m.time = 2.0;
  m.window = 0.25;
  m.plant_model = "amb1dof_voltage";
  m.method = "pem";
  m.sample_time = 1e-4;
  m.physical = {{"R1", 17.5, 0.05},  {"R2", 17.5, 0.05},  {"kw1", 1.0, 0.003}, {"kw2", 1.0, 0.003},
                {"kr1", 490.0, 1.5}, {"kr2", 490.0, 1.5}, {"ks", 1.4e6, 4e3}};
  return m;
}

TEST(BusInputFuzz, IdentifiedModelsGiveFiniteEstimatesOrAreRefused) {
  std::mt19937_64 random(22);
  int refused = 0;
  for (int i = 0; i < kIterations; ++i) {
    bus::IdentifiedModel m = valid_model();
    auto& e = m.physical[std::uniform_int_distribution<std::size_t>(0, m.physical.size() - 1)(random)];
    switch (i % 5) {
      case 0:
        e.value = bad_value(random);
        break;
      case 1:
        e.sigma = bad_value(random);
        break;
      case 2:
        e.name = bad_name(random);
        break;
      case 3:
        m.time = bad_value(random);
        break;
      default:
        m.physical.push_back(m.physical.front());  // a repeated name
        break;
    }
    try {
      // The diagnostics daemon's path: the conversion, then the engine's check of the window.
      const diag::EstimateWindow w = convert::estimate_window(m, diag::Source::sim);
      w.validate();
      EXPECT_TRUE(std::isfinite(w.time));
      for (const diag::ParameterEstimate& p : w.estimates) {
        EXPECT_TRUE(std::isfinite(p.value)) << p.parameter;
        EXPECT_TRUE(std::isfinite(p.sigma) && p.sigma >= 0.0) << p.parameter;
      }
    } catch (const Error&) {
      ++refused;
    }
  }
  EXPECT_GT(refused, kIterations / 10);
}

TEST(BusInputFuzz, ScenarioFilesAreTakenOrRefused) {
  const std::string nominal = read_text_file(std::string(AMBID_SOURCE_DIR) + "/deploy/config/nominal-bearing.json");
  const fuzz::FuzzCount c = fuzz::fuzz({nominal}, kIterations, 23, [](const std::string& text) {
    sim::build_scenario(scenario_from_json(parse_json_text(text)));
  });
  EXPECT_GT(c.refused, kIterations / 10);
}

}  // namespace
}  // namespace ambid::daemons
