// The service end to end with the real daemons as processes (`ambid daemon identifier` and
// `ambid daemon diagnostics`, spawned like tests/integration/stack_support.hpp does), the
// benchmark itself playing the plant: it publishes the plant daemon's batches (500 samples,
// services/convert/plant_samples.hpp) of records simulated from
// tests/integration/scenarios/quiet-bearing.json and quiet-coil1-hot.json (1 nm / 1 uA noise, 1 s records; seed +
// record number, as the plant's sim source), on the
// loopback profile.
//   BM_PlantToIdentifier/<vendor>: sustained samples per second plant -> identifier: records
//     of 1 s published as fast as the identifier keeps up (at most two records ahead of the
//     models it has published, so nothing is lost to the readers' KEEP_LAST history); items =
//     samples published, `windows_per_s` = IdentifiedModel messages received per second.
//     Compare BM_BusSamples (bus_throughput_bench) for the raw vendor rate of the same payload.
//   BM_SampleToAlert/<vendor>: sample-to-alert latency: nominal records at 10x real time (the
//     stack's pace) until the baseline is learned, then records with R1 +20 %; the latency is the
//     wall time from writing the first faulty batch to receiving the ERROR alert about R1.
//     One fresh stack (trend store) per iteration; counters: median and max over the runs, the
//     plant time the detection took, and the R1 the ERROR carried.
// 0 = fastdds, 1 = cyclone (bench, identifier and diagnostics on the same vendor).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "integration/stack_support.hpp"
#include "plant_sim/scenario.hpp"
#include "services/bus/make_bus.hpp"
#include "services/convert/plant_description.hpp"
#include "services/convert/plant_samples.hpp"
#include "services/daemons/scenario_json.hpp"

namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
using ambid::convert::sample_batch;

constexpr Eigen::Index kBatch = 500;
constexpr int kWindowsPerRecord = 3;  // 1 s records: 0.25 s settling, three 0.25 s windows

const char* vendor(std::int64_t i) { return i == 0 ? "fastdds" : "cyclone"; }

std::vector<ambid::Experiment> records(const std::string& scenario, int count) {
  const ambid::sim::ScenarioOptions o =
      ambid::daemons::read_scenario_file(std::string(AMBID_SOURCE_DIR) + "/tests/integration/scenarios/" + scenario);
  std::vector<ambid::Experiment> out;
  for (int k = 0; k < count; ++k) {
    ambid::sim::ScenarioOptions ok = o;
    ok.seed = o.seed + std::uint64_t(k);
    out.push_back(ambid::sim::simulate_scenario(ok));
  }
  return out;
}

const std::vector<ambid::Experiment>& nominal() {
  static const auto r = records("quiet-bearing.json", 16);
  return r;
}
const std::vector<ambid::Experiment>& hot() {
  static const auto r = records("quiet-coil1-hot.json", 4);
  return r;
}

// The plant's side of the bus: batches of records with a continuous clock, as the plant daemon.
class Plant {
 public:
  // The nominal and the hot records share one description (the sidecar keeps nominal values).
  explicit Plant(ambid::bus::Bus& bus)
      : samples_(bus.writer<ambid::bus::PlantSamples>()),
        descriptions_(bus.writer<ambid::bus::PlantDescription>()),
        description_(ambid::convert::describe(nominal().front(), "bearing-1")) {
    descriptions_->write(description_);
  }
  ambid::bus::Writer<ambid::bus::PlantSamples>& writer() { return *samples_; }
  // Publishes batch `seq` of `record`; returns the plant time after it.
  double publish(const ambid::Experiment& record, std::uint64_t seq) {
    const Eigen::Index begin = Eigen::Index(seq) * kBatch;
    if (seq == 0) offset_ = clock_ - record.t(0);
    ambid::bus::PlantSamples batch = sample_batch(record, begin, kBatch, "bearing-1", seq, offset_);
    batch.description_id = description_.description_id;
    samples_->write(batch);
    clock_ = record.t(begin + kBatch - 1) + offset_ + record.sample_time;
    return clock_;
  }
  double clock() const { return clock_; }

 private:
  std::unique_ptr<ambid::bus::Writer<ambid::bus::PlantSamples>> samples_;
  std::unique_ptr<ambid::bus::Writer<ambid::bus::PlantDescription>> descriptions_;
  ambid::bus::PlantDescription description_;
  double clock_ = 0.0, offset_ = 0.0;
};

std::uint64_t batches(const ambid::Experiment& e) { return std::uint64_t(e.samples() / kBatch); }

template <class Done>
bool wait_for(ambid::bus::Bus& bus, std::chrono::milliseconds limit, Done done) {
  const auto end = Clock::now() + limit;
  while (!done()) {
    if (Clock::now() > end) return false;
    bus.wait(5ms);
  }
  return true;
}

void BM_PlantToIdentifier(benchmark::State& state) {
  const int domain = 191 + int(state.range(0));
  ambid::testing::Stack stack(std::string("bench_throughput_") + vendor(state.range(0)), domain,
                              {{"identifier", vendor(state.range(0))}});
  stack.start("identifier");
  auto bus = ambid::bus::make_bus(vendor(state.range(0)), domain);
  Plant plant(*bus);
  auto models = bus->reader<ambid::bus::IdentifiedModel>();
  if (!wait_for(*bus, 20000ms, [&] { return plant.writer().matched() > 0; })) {
    state.SkipWithError("the identifier did not match");
    return;
  }
  std::this_thread::sleep_for(1s);  // discovery both ways
  std::uint64_t published = 0, received = 0, record = 0;
  const auto& r = nominal();
  for (auto _ : state) {
    const ambid::Experiment& e = r[record++ % r.size()];
    for (std::uint64_t seq = 0; seq < batches(e); ++seq) plant.publish(e, seq);
    published += std::uint64_t(e.samples());
    const std::uint64_t expected = record * kWindowsPerRecord;
    if (!wait_for(*bus, 10000ms, [&] {
          received += models->take().size();
          return received + 2 * kWindowsPerRecord >= expected;
        })) {
      state.SkipWithError("the identifier fell behind by more than 2 records for 10 s");
      break;
    }
  }
  wait_for(*bus, 10000ms, [&] {
    received += models->take().size();
    return received >= record * kWindowsPerRecord;
  });
  state.SetItemsProcessed(std::int64_t(published));
  state.counters["windows_per_s"] = benchmark::Counter(double(received), benchmark::Counter::kIsRate);
  state.counters["windows_lost"] = double(record * kWindowsPerRecord - std::min(received, record * kWindowsPerRecord));
}
BENCHMARK(BM_PlantToIdentifier)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(5.0)->UseRealTime();

void BM_SampleToAlert(benchmark::State& state) {
  constexpr double speed = 10.0;  // plant seconds per wall second, the stack's pace
  std::vector<double> latency_ms, detection_plant_s, r1_read;
  int run = 0;
  for (auto _ : state) {
    const std::string v = vendor(state.range(0));
    const int domain = 193 + int(state.range(0));
    ambid::testing::Stack stack("bench_latency_" + v + "_" + std::to_string(run++), domain,
                                {{"identifier", v}, {"diagnostics", v}});
    stack.start("diagnostics");
    stack.start("identifier");
    auto bus = ambid::bus::make_bus(v, domain);
    Plant plant(*bus);
    auto alerts = bus->reader<ambid::bus::Alert>();
    if (!wait_for(*bus, 20000ms, [&] { return plant.writer().matched() > 0; })) {
      state.SkipWithError("the identifier did not match");
      break;
    }
    std::this_thread::sleep_for(1s);
    std::optional<ambid::bus::Alert> error;
    Clock::time_point error_at{};
    auto poll_alerts = [&] {
      for (const auto& a : alerts->take())
        if (!error && a.level == ambid::bus::AlertLevel::error && a.parameter == "R1") {
          error = a;
          error_at = Clock::now();
        }
    };
    // Waits on the bus (alerts taken as they arrive) until the plant clock is due.
    const auto start = Clock::now();
    auto paced = [&] {
      const auto due =
          start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(plant.clock() / speed));
      for (auto now = Clock::now(); now < due; now = Clock::now()) {
        bus->wait(1ms);
        poll_alerts();
      }
    };
    for (const ambid::Experiment& e : nominal())  // 16 records: 48 windows, 40 of them learn
      for (std::uint64_t seq = 0; seq < batches(e); ++seq, paced()) plant.publish(e, seq);
    if (error) {
      state.SkipWithError("an ERROR about R1 before the fault");
      break;
    }
    const double fault_time = plant.clock();
    Clock::time_point first_faulty{};
    for (const ambid::Experiment& e : hot()) {
      for (std::uint64_t seq = 0; seq < batches(e) && !error; ++seq, paced()) {
        plant.publish(e, seq);
        if (first_faulty == Clock::time_point{}) first_faulty = Clock::now();
      }
    }
    wait_for(*bus, 5000ms, [&] {
      poll_alerts();
      return error.has_value();
    });
    if (!error) {
      state.SkipWithError("no ERROR alert about R1 within 4 s of faulty plant time + 5 s");
      break;
    }
    latency_ms.push_back(std::chrono::duration<double, std::milli>(error_at - first_faulty).count());
    detection_plant_s.push_back(error->time - fault_time);
    r1_read.push_back(error->value);
    state.SetIterationTime(latency_ms.back() / 1000.0);
  }
  if (latency_ms.empty()) return;
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  };
  state.counters["latency_median_ms"] = median(latency_ms);
  state.counters["latency_max_ms"] = *std::max_element(latency_ms.begin(), latency_ms.end());
  state.counters["plant_time_median_s"] = median(detection_plant_s);
  state.counters["R1_read_min"] = *std::min_element(r1_read.begin(), r1_read.end());
  state.counters["R1_read_max"] = *std::max_element(r1_read.begin(), r1_read.end());
}
BENCHMARK(BM_SampleToAlert)->Arg(0)->Arg(1)->Iterations(5)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
