#pragma once
// Reader and writer of experiment files (experiment-format.md): `stem.csv` + `stem.json`.
// No printing: warnings (e.g. ignored extra CSV columns) are returned to the caller.
#include <filesystem>
#include <string>
#include <vector>

#include "core/experiment.hpp"

namespace ambid {

struct ReadOptions {
  // Accept non-uniform sampling by linear interpolation onto the sidecar's sample_time grid.
  bool resample = false;
};

struct ReadResult {
  Experiment experiment;
  std::vector<std::string> warnings;
};

// `path` may name the .json sidecar, the .csv, or the stem without extension.
// Throws Error whose message names the file, the row or key, and what was expected.
ReadResult read_experiment(const std::filesystem::path& path, const ReadOptions& options = {});

// Writes `stem.csv` and `stem.json` (creating the parent directory); `stem` may carry either
// extension or none. Validates first and writes nothing for an invalid experiment.
void write_experiment(const Experiment& experiment, const std::filesystem::path& stem);

// The sidecar alone, as JSON (used by the writer and by tools that publish metadata).
nlohmann::json sidecar_json(const Experiment& experiment);

}  // namespace ambid
