#pragma once
// Offline diagnosis (`ambid diagnose`): a time-ordered sequence of estimate windows of one or
// more plants runs through the diagnostics engine, the first `baseline_windows` windows of each
// parameter forming its learned baseline (baseline.hpp: the mean, and the scatter the reported
// sigmas do not explain, both from those windows). Everything goes to a fresh trend store.
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "diagnostics/alert.hpp"
#include "diagnostics/diagnostics_engine.hpp"
#include "diagnostics/estimate.hpp"
#include "diagnostics/monitor/baseline.hpp"

namespace ambid::diag {

struct OfflineDiagnosis {
  std::vector<Alert> alerts;                        // every alert raised, in time order
  using Key = std::pair<std::string, std::string>;  // plant id, parameter
  std::map<Key, Baseline> baselines;
  std::map<Key, Level> final_levels;  // the level of each parameter after the last window
};

// `config.monitor.learning_windows` is replaced by baseline_windows. A store file already at
// `store` (and its -wal, -shm) is removed first: the run starts a new history. Throws Error
// when baseline_windows < kMinLearningWindows or not smaller than the number of windows of
// some parameter (nothing would be left to diagnose), and whatever the engine throws.
OfflineDiagnosis diagnose_offline(const std::vector<EstimateWindow>& windows, std::size_t baseline_windows,
                                  const std::filesystem::path& store, EngineConfig config = {});

}  // namespace ambid::diag
