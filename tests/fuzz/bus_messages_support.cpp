#include "fuzz/bus_messages.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <type_traits>
#include <typeinfo>

#include "core/error.hpp"
#include "core/experiment_io.hpp"
#include "diagnostics/fault_signatures.hpp"
#include "fuzz/scratch.hpp"
#include "plant_sim/scenario.hpp"
#include "services/bus/validate.hpp"
#include "services/convert/alert.hpp"
#include "services/convert/estimate_window.hpp"
#include "services/convert/plant_description.hpp"
#include "services/convert/plant_samples.hpp"
#include "services/convert/source_kind.hpp"
#include "services/daemons/described_windows.hpp"
#include "services/daemons/description_change.hpp"
#include "services/daemons/excitation_limits.hpp"
#include "services/daemons/plant_source.hpp"
#include "services/daemons/sample_gaps.hpp"
#include "services/daemons/window_failures.hpp"

namespace ambid::fuzz {
namespace bus_messages_support {

namespace fs = std::filesystem;
using bus::Alert;
using bus::AlertLevel;
using bus::ControllerDescription;
using bus::Estimate;
using bus::ExcitationCommand;
using bus::FrequencyResponse;
using bus::Health;
using bus::IdentifiedModel;
using bus::IsoZone;
using bus::Matrix;
using bus::NamedValue;
using bus::PlantSamples;
using bus::PlantSourceCommand;
using bus::PlantSourceState;
using bus::SensitivityPeak;
using bus::SourceKind;
using bus::StateSpace;

// ---- Field-wise mutation ------------------------------------------------------------------

double bad_value(std::mt19937_64& random) {
  constexpr double kValues[] = {std::numeric_limits<double>::quiet_NaN(),
                                std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity(),
                                1e308,
                                -1e308,
                                4.9e-324,
                                -0.0,
                                0.0,
                                -1.0,
                                1e-12};
  return kValues[std::uniform_int_distribution<std::size_t>(0, std::size(kValues) - 1)(random)];
}

// Visits every field (and the fields of nested structs and sequence entries) of a message,
// counting them; the field numbered `target` is mutated.
class FieldMutator {
 public:
  FieldMutator(std::mt19937_64& random, Mutator& bytes, std::size_t target)
      : random_(random), bytes_(bytes), target_(target) {}
  std::size_t count() const { return count_; }

  void operator()(std::string& s) {
    if (!hit()) return;
    static const std::string kTexts[] = {
        "", std::string(5000, 'y'), std::string("a\0b", 3), "\xff\xfe", "/", "..", "bearing-1"};
    if (pick(2) == 0)
      s = kTexts[pick(std::size(kTexts))];
    else
      s = bytes_.mutate(s);
  }
  void operator()(double& v) {
    if (hit()) v = bad_value(random_);
  }
  void operator()(bool& v) {
    if (hit()) v = !v;
  }
  template <class Integer>
  requires std::is_integral_v<Integer>
  void operator()(Integer& v) {
    if (!hit()) return;
    const auto shifted = [&](std::uint64_t by) { return static_cast<Integer>(static_cast<std::uint64_t>(v) + by); };
    const Integer kValues[] = {
        0,          1,          std::numeric_limits<Integer>::max(), std::numeric_limits<Integer>::min(),
        shifted(1), shifted(7), shifted(std::uint64_t(-1))};
    v = kValues[pick(std::size(kValues))];
  }
  template <class Enum>
  requires std::is_enum_v<Enum>
  void operator()(Enum& v) {
    if (hit()) v = static_cast<Enum>(pick(256));
  }
  template <class T>
  void operator()(std::vector<T>& v) {
    if (hit()) {
      switch (pick(5)) {
        case 0:
          v.clear();
          break;
        case 1:
          if (!v.empty()) v.pop_back();
          break;
        case 2:
          if (!v.empty()) v.push_back(v.front());  // a repeated entry
          break;
        case 3:
          if (!v.empty()) {
            const T first = v.front();
            v.resize(20000, first);  // beyond every bound
          }
          break;
        default:
          v.emplace_back();
          break;
      }
      return;
    }
    for (T& entry : v) (*this)(entry);
  }
  void operator()(NamedValue& v) {
    (*this)(v.name);
    (*this)(v.value);
  }
  void operator()(Estimate& v) {
    (*this)(v.name);
    (*this)(v.value);
    (*this)(v.sigma);
  }
  void operator()(Matrix& m) {
    (*this)(m.rows);
    (*this)(m.cols);
    (*this)(m.values);
  }
  void operator()(StateSpace& s) {
    for (Matrix* m : {&s.a, &s.b, &s.c, &s.d}) (*this)(*m);
  }
  void operator()(SensitivityPeak& p) {
    (*this)(p.output);
    (*this)(p.frequency);
    (*this)(p.magnitude);
    (*this)(p.zone);
  }
  void operator()(ControllerDescription& c) {
    (*this)(c.kind);
    (*this)(c.sample_time);
    (*this)(c.inputs);
    (*this)(c.outputs);
    (*this)(c.matrices);
    (*this)(c.initial_state);
    (*this)(c.output_limits);
    (*this)(c.state_limits);
  }

 private:
  bool hit() { return count_++ == target_; }
  std::size_t pick(std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(random_); }

  std::mt19937_64& random_;
  Mutator& bytes_;
  std::size_t target_;
  std::size_t count_ = 0;
};

// The fields of each message, in IDL order.
template <class V>
void fields(PlantSamples& m, V& v) {
  v(m.plant_id);
  v(m.seq);
  v(m.t0);
  v(m.sample_time);
  v(m.count);
  v(m.description_id);
  v(m.y_names);
  v(m.u_names);
  v(m.r_names);
  v(m.y);
  v(m.u);
  v(m.r);
}
template <class V>
void fields(bus::PlantDescription& m, V& v) {
  v(m.plant_id);
  v(m.description_id);
  v(m.model);
  v(m.parameters);
  v(m.sample_time);
  v(m.y_names);
  v(m.u_names);
  v(m.r_names);
  v(m.operating_point);
  v(m.has_controller);
  v(m.controller);
}
template <class V>
void fields(ExcitationCommand& m, V& v) {
  v(m.plant_id);
  v(m.seq);
  v(m.kind);
  v(m.channels);
  v(m.amplitude);
  v(m.duration);
  v(m.seed);
  v(m.settings);
  v(m.frequencies);
}
template <class V>
void fields(PlantSourceCommand& m, V& v) {
  v(m.plant_id);
  v(m.seq);
  v(m.kind);
  v(m.target);
}
template <class V>
void fields(PlantSourceState& m, V& v) {
  v(m.plant_id);
  v(m.time);
  v(m.kind);
  v(m.target);
  v(m.command_seq);
  v(m.command_accepted);
  v(m.message);
}
template <class V>
void fields(IdentifiedModel& m, V& v) {
  v(m.plant_id);
  v(m.seq);
  v(m.time);
  v(m.window);
  v(m.plant_model);
  v(m.method);
  v(m.sample_time);
  v(m.discrete);
  v(m.continuous);
  v(m.parameters);
  v(m.physical);
  v(m.nrmse);
}
template <class V>
void fields(FrequencyResponse& m, V& v) {
  v(m.plant_id);
  v(m.kind);
  v(m.seq);
  v(m.time);
  v(m.outputs);
  v(m.inputs);
  v(m.frequencies);
  v(m.re);
  v(m.im);
  v(m.peaks);
  v(m.zone);
}
template <class V>
void fields(Alert& m, V& v) {
  v(m.plant_id);
  v(m.fault);
  v(m.channel);
  v(m.time);
  v(m.level);
  v(m.parameter);
  v(m.value);
  v(m.baseline);
  v(m.message);
}
template <class V>
void fields(Health& m, V& v) {
  v(m.node);
  v(m.role);
  v(m.time);
  v(m.level);
  v(m.message);
  v(m.received);
  v(m.published);
  v(m.errors);
}

// One to three fields of `m` mutated.
template <class Message>
Message mutated(Message m, std::mt19937_64& random, Mutator& bytes) {
  const int n = std::uniform_int_distribution<int>(1, 3)(random);
  for (int k = 0; k < n; ++k) {
    FieldMutator counter(random, bytes, std::size_t(-1));
    fields(m, counter);
    FieldMutator mutator(random, bytes, std::uniform_int_distribution<std::size_t>(0, counter.count() - 1)(random));
    fields(m, mutator);
  }
  return m;
}

// ---- Valid messages and what receives them ------------------------------------------------

const std::string kPlant = "bearing-1";

const Scratch& scratch() {
  static const Scratch s("ambid-fuzz-bus-");
  return s;
}

// 0.2 s of the nominal bearing in its LQR loop, and its description.
const Experiment& record() {
  static const Experiment e = [] {
    sim::ScenarioOptions o;
    o.duration = 0.2;
    o.position_noise = 1e-7;
    o.current_noise = 1e-3;
    return sim::simulate_scenario(o);
  }();
  return e;
}

const bus::PlantDescription& description() {
  static const bus::PlantDescription d = convert::describe(record(), kPlant);
  return d;
}

// A short scenario and a short experiment for the source commands.
std::string scenario_file() {
  static const std::string path = [] {
    const std::string p = scratch().file("scenario.json").string();
    std::ofstream(p) << R"({"name": "short", "plant": "amb1dof_voltage", "controller": "lqr", "excitation": "prbs",
      "amplitude": 0.5, "duration": 0.02, "sample_time": 1e-4, "seed": 3})";
    return p;
  }();
  return path;
}

std::string experiment_file() {
  static const std::string path = [] {
    const fs::path stem = scratch().file("replay");
    Experiment e = record();
    write_experiment(e, stem);
    return stem.string();
  }();
  return path;
}

template <class Message>
struct Target;

template <>
struct Target<PlantSamples> {
  std::vector<PlantSamples> corpus() const {
    std::vector<PlantSamples> batches;
    for (std::uint64_t k = 0; k < 40; ++k) {
      batches.push_back(convert::sample_batch(record(), Eigen::Index(k) * 50, 50, kPlant, k, 0.0));
      batches.back().description_id = description().description_id;
    }
    return batches;
  }
  daemons::DescribedWindows windows{{.window = 0.025, .settle = 0.0}};
  daemons::SampleGaps gaps;
  bool described = false;
  void consume(const PlantSamples& m) {
    if (!described) windows.describe(description());
    described = true;
    gaps.check(m);
    for (const auto& step : windows.add(m))
      if (step.event == daemons::DescribedWindows::Event::rejected) throw Error(step.reason);
    while (windows.full()) {
      const Experiment w = windows.take();
      EXPECT_NO_THROW(w.validate());
    }
  }
};

template <>
struct Target<bus::PlantDescription> {
  std::vector<bus::PlantDescription> corpus() const { return {description()}; }
  int inputs = 0, accepted = 0;
  void consume(const bus::PlantDescription& received) {
    // Every other input carries the hash of its mutated content, as a peer that means it
    // would send: the checks behind the id check see it too.
    bus::PlantDescription m = received;
    if (inputs++ % 2 == 0) m.description_id = convert::description_id(m);
    daemons::DescribedWindows windows({.window = 0.025, .settle = 0.0});
    windows.describe(m);
    if (daemons::classify(&description(), m) == daemons::DescriptionChange::bearing)
      daemons::bearing_difference(description(), m);
    // 19 closed-loop runs per call: every 10th accepted description only.
    if (accepted++ % 10 == 0) diag::closed_loop_fault_hypotheses(convert::experiment_header(m));
  }
};

template <>
struct Target<ExcitationCommand> {
  std::vector<ExcitationCommand> corpus() const {
    ExcitationCommand c;
    c.plant_id = kPlant;
    c.seq = 1;
    c.kind = "multisine";
    c.channels = {"u1", "u2"};
    c.amplitude = 0.2;
    c.duration = 1.0;
    c.seed = 3;
    c.frequencies = {10.0, 100.0, 500.0};
    ExcitationCommand p = c;
    p.kind = "prbs";
    p.frequencies = {};
    return {c, p};
  }
  std::unique_ptr<daemons::PlantSource> source = daemons::make_plant_source(SourceKind::sim, scenario_file(), {});
  void consume(const ExcitationCommand& m) {
    if (const std::string refusal = daemons::excitation_violation(m, {}); !refusal.empty()) throw Error(refusal);
    source->excite(daemons::excitation_request(m));
  }
};

template <>
struct Target<PlantSourceCommand> {
  std::vector<PlantSourceCommand> corpus() const {
    return {{kPlant, 1, SourceKind::sim, scenario_file()}, {kPlant, 2, SourceKind::replay, experiment_file()}};
  }
  void consume(const PlantSourceCommand& m) {
    if (m.kind == SourceKind::rig) return;  // see bus_messages.hpp
    daemons::make_plant_source(m.kind, m.target, {});
  }
};

template <>
struct Target<PlantSourceState> {
  std::vector<PlantSourceState> corpus() const {
    return {{kPlant, 2.0, SourceKind::sim, scenario_file(), 1, true, "source swapped"}};
  }
  void consume(const PlantSourceState& m) {
    convert::to_source(m.kind);
    convert::source_kind_name(m.kind);
  }
};

template <>
struct Target<IdentifiedModel> {
  std::vector<IdentifiedModel> corpus() const {
    IdentifiedModel m;
    m.plant_id = kPlant;
    m.seq = 4;
    m.time = 2.0;
    m.window = 0.25;
    m.plant_model = "amb1dof_voltage";
    m.method = "pem";
    m.sample_time = 1e-4;
    m.physical = {{"R1", 17.5, 0.05},  {"R2", 17.5, 0.05},  {"kw1", 1.0, 0.003}, {"kw2", 1.0, 0.003},
                  {"kr1", 490.0, 1.5}, {"kr2", 490.0, 1.5}, {"ks", 1.4e6, 4e3}};
    return {m};
  }
  void consume(const IdentifiedModel& m) {
    const diag::EstimateWindow w = convert::estimate_window(m, diag::Source::sim);
    w.validate();
    EXPECT_TRUE(std::isfinite(w.time));
    for (const diag::ParameterEstimate& p : w.estimates) {
      EXPECT_TRUE(std::isfinite(p.value)) << p.parameter;
      EXPECT_TRUE(std::isfinite(p.sigma) && p.sigma >= 0.0) << p.parameter;
    }
  }
};

template <>
struct Target<FrequencyResponse> {
  std::vector<FrequencyResponse> corpus() const {
    FrequencyResponse f;
    f.plant_id = kPlant;
    f.kind = "input_sensitivity";
    f.seq = 1;
    f.time = 5.0;
    f.outputs = {"u1", "u2"};
    f.inputs = {"r1", "r2"};
    f.frequencies = {1.0, 10.0, 100.0};
    f.re.assign(12, 0.5);
    f.im.assign(12, -0.1);
    f.peaks = {{"u1", 120.0, 2.1, IsoZone::b}};
    f.zone = IsoZone::b;
    return {f};
  }
  void consume(const FrequencyResponse&) {}
};

template <>
struct Target<Alert> {
  std::vector<Alert> corpus() const {
    return {{kPlant, "coil_resistance", 1, 12.0, AlertLevel::warn, "R1", 21.0, 17.5, "coil 1 resistance"}};
  }
  void consume(const Alert& m) { convert::level_name(m.level); }
};

template <>
struct Target<Health> {
  std::vector<Health> corpus() const {
    return {{kPlant + "/identifier", "identifier", 3.0, AlertLevel::warn,
             std::string(daemons::kFailingWindows) + "4 in a row", 10, 8, 2}};
  }
  void consume(const Health& m) {
    daemons::reports_failing_windows(m, kPlant);
    convert::level_name(m.level);
  }
};

}  // namespace bus_messages_support
using namespace bus_messages_support;

template <class Message>
FuzzCount fuzz_bus_message(int iterations) {
  Target<Message> target;
  const std::vector<Message> corpus = target.corpus();
  std::mt19937_64 random(31);
  Mutator bytes(32);
  FuzzCount count;
  for (int i = 0; i < iterations; ++i) {
    const Message m = mutated(corpus[std::size_t(i) % corpus.size()], random, bytes);
    bool refused = false;
    try {
      try {
        target.consume(m);
      } catch (const Error&) {
        refused = true;
      }
      try {
        validate(m);
      } catch (const Error&) {
        refused = true;
      }
    } catch (const std::exception& e) {
      ADD_FAILURE() << typeid(Message).name() << " iteration " << i << ": " << typeid(e).name() << ": " << e.what();
    }
    ++(refused ? count.refused : count.accepted);
  }
  return count;
}

#define AMBID_FUZZ_DEFINE(Message, topic_name, qos_profile) \
  template FuzzCount fuzz_bus_message<bus::Message>(int iterations);
AMBID_BUS_MESSAGES(AMBID_FUZZ_DEFINE)
#undef AMBID_FUZZ_DEFINE

}  // namespace ambid::fuzz
