#include "diagnostics/offline_diagnosis.hpp"

#include <string>

#include "core/error.hpp"
#include "diagnostics/trend_store.hpp"

namespace ambid::diag {

OfflineDiagnosis diagnose_offline(const std::vector<EstimateWindow>& windows, std::size_t baseline_windows,
                                  const std::filesystem::path& store, EngineConfig config) {
  if (baseline_windows < kMinLearningWindows)
    throw Error("offline diagnosis: the baseline has " + std::to_string(baseline_windows) + " windows, at least " +
                std::to_string(kMinLearningWindows) + " are needed to learn its mean and scatter");
  std::map<OfflineDiagnosis::Key, std::size_t> counts;
  for (const EstimateWindow& w : windows)
    for (const ParameterEstimate& e : w.estimates) ++counts[{w.plant_id, e.parameter}];
  if (counts.empty()) throw Error("offline diagnosis: no estimates to diagnose");
  for (const auto& [key, count] : counts)
    if (count <= baseline_windows)
      throw Error("offline diagnosis: " + key.second + " of plant '" + key.first + "' has " + std::to_string(count) +
                  " windows, not more than the " + std::to_string(baseline_windows) + " of the baseline");

  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(store.string() + suffix);
  config.monitor.learning_windows = baseline_windows;
  TrendStore trends(store);
  DiagnosticsEngine engine(trends, config);
  OfflineDiagnosis out;
  for (const EstimateWindow& w : windows)
    for (Alert& a : engine.process(w)) out.alerts.push_back(std::move(a));
  for (const auto& [key, count] : counts) {
    out.baselines.emplace(key, *trends.baseline(key.first, key.second));
    out.final_levels.emplace(key, engine.level(key.first, key.second));
  }
  return out;
}

}  // namespace ambid::diag
