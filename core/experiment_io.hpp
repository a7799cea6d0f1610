#pragma once
// Reader and writer of experiment files (experiment-format.md): `stem.csv` + `stem.json`.
// No printing: warnings (e.g. ignored extra CSV columns) are returned to the caller.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/experiment.hpp"

namespace ambid {

// The value of the sidecar's `format` key that this version reads and writes.
inline constexpr std::string_view kExperimentFormat = "ambid-experiment/1";

struct ReadOptions {
  // Accept non-uniform sampling by linear interpolation onto the sidecar's sample_time grid.
  bool resample = false;
};

struct ReadResult {
  Experiment experiment;              // passes Experiment::validate()
  std::vector<std::string> warnings;  // each names its file
  // Per sample: a clamp of the controller (controller.output_limits, state_limits) acted, so
  // the sample is not exogenous (core/controller_replay.hpp); all false without limits.
  std::vector<bool> clamped;
  Eigen::Index clamped_samples = 0;
};

// `path` may name the .json sidecar, the .csv, or the stem without extension.
// Throws Error whose message names the file, the row or key, and what was expected.
ReadResult read_experiment(const std::filesystem::path& path, const ReadOptions& options = {});

// The sidecar alone (`path` as above; no CSV is read): the plant description of
// experiment-format.md, as an experiment without samples that passes validate_metadata().
Experiment read_sidecar(const std::filesystem::path& path);

// Writes `stem.csv` and `stem.json` (creating the parent directory); `stem` may carry either
// extension or none. Validates first and writes nothing for an invalid experiment. Each file
// is replaced atomically (temporary file, fsync, rename): never left half written. Numbers
// are written in their shortest round-trip form, so reading back gives identical doubles.
void write_experiment(const Experiment& experiment, const std::filesystem::path& stem);

// The sidecar alone, as JSON (used by the writer and by tools that publish metadata), with
// the keys of Experiment::extra merged back in. Throws Error if validate_metadata() fails.
nlohmann::json sidecar_json(const Experiment& experiment);

}  // namespace ambid
