#pragma once
// How the identifier daemon makes a hole in its samples (sample_gaps.hpp) visible: a log line,
// the counter ambid_samples_missed_total, Health WARN and a WARN alert history_gap (parameter
// "samples", time the plant time the samples resumed, value the seconds missed). Samples that
// arrived but were dropped unidentified for good (their plant description never came,
// described_windows.hpp) are reported the same way.
#include <memory>
#include <string>

#include "services/bus/bus.hpp"
#include "services/daemons/daemon_runtime.hpp"
#include "services/daemons/sample_gaps.hpp"

namespace ambid::daemons {

class SampleGapReport {
 public:
  SampleGapReport(bus::Bus& bus, DaemonRuntime& runtime, std::string plant_id);
  // Checks the batch (SampleGaps::check) and reports the gap before it, if any.
  void check(const bus::PlantSamples& batch);
  // Reports `samples` received from plant time `from` to `to` and dropped for `reason`.
  void dropped(std::size_t samples, double from, double to, const std::string& reason);

 private:
  DaemonRuntime& runtime_;
  std::string plant_id_;
  std::unique_ptr<bus::Writer<bus::Alert>> alerts_;
  prometheus::Counter& missed_;
  SampleGaps gaps_;

  void raise(std::size_t samples, double from, double to, const std::string& message);
};

}  // namespace ambid::daemons
