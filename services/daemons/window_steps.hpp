#pragma once
// How a daemon reports what its DescribedWindows did with each description and batch: the
// ambid_samples_dropped_total{reason} counters (rejected, gap, record_end, no_description,
// description_change), the rejected-message counter, log lines and Health.
#include <string>
#include <vector>

#include "services/daemons/daemon_runtime.hpp"
#include "services/daemons/described_windows.hpp"

namespace ambid::daemons {

class WindowSteps {
 public:
  // help: the help text of ambid_samples_dropped_total in this daemon.
  WindowSteps(DaemonRuntime& runtime, const std::string& help);

  // plant: for a daemon serving several plants, the plant id its log lines and Health start with.
  void report(const std::vector<DescribedWindows::Step>& steps, const std::string& plant = {});
  // windows.describe(d), reported; a description that does not hold up is logged, counted as
  // rejected and sets Health WARN.
  void describe(DescribedWindows& windows, const bus::PlantDescription& d, const std::string& plant = {});

 private:
  DaemonRuntime& runtime_;
  prometheus::Counter &rejected_, &gap_, &record_end_, &no_description_, &description_change_;
  bool waiting_logged_ = false;
};

}  // namespace ambid::daemons
