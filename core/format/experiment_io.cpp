#include "core/experiment_io.hpp"

#include <string_view>
#include <system_error>

#include <nlohmann/json.hpp>

#include "core/controller_replay.hpp"
#include "core/error.hpp"
#include "core/experiment_file.hpp"
#include "core/format/experiment_csv.hpp"
#include "core/format/experiment_sidecar.hpp"
#include "core/json_text.hpp"

namespace ambid {
namespace {

struct ExperimentFiles {
  std::filesystem::path csv, json;
};

// `path` names the .json, the .csv, or the stem; any other extension is part of the stem
// (`run.v2` means `run.v2.csv` + `run.v2.json`).
ExperimentFiles files_of(const std::filesystem::path& path) {
  std::filesystem::path stem = path;
  if (stem.extension() == ".json" || stem.extension() == ".csv") stem.replace_extension();
  ExperimentFiles files{stem, stem};
  files.csv += ".csv";
  files.json += ".json";
  return files;
}

// Runs `parse`, prefixing every new warning and any Error that does not name the file yet (a
// file-system error does) with the file name.
template <typename Parse>
void in_file(const std::filesystem::path& file, std::vector<std::string>& warnings, Parse parse) {
  std::vector<std::string> local;
  try {
    parse(local);
  } catch (const Error& e) {
    if (std::string_view(e.what()).find(file.string()) != std::string_view::npos) throw;
    throw Error(file.string() + ": " + e.what());
  }
  for (auto& w : local) warnings.push_back(file.string() + ": " + w);
}

}  // namespace

ReadResult read_experiment(const std::filesystem::path& path, const ReadOptions& options) {
  const ExperimentFiles files = files_of(path);
  ReadResult result;
  const std::string sidecar_text = read_json_file(files.json);
  in_file(files.json, result.warnings, [&](std::vector<std::string>& warnings) {
    result.experiment = parse_sidecar(parse_sidecar_text(sidecar_text), warnings);
  });
  in_file(files.csv, result.warnings, [&](std::vector<std::string>& warnings) {
    read_samples_csv(files.csv, options, result.experiment, warnings);
    ControllerReplay replay = clamped_samples(result.experiment);
    result.clamped = std::move(replay.clamped);
    result.clamped_samples = replay.clamped_samples;
    if (result.clamped_samples > 0)
      warnings.push_back(std::to_string(result.clamped_samples) + " of " + std::to_string(result.experiment.samples()) +
                         " samples have a controller clamp acting (controller.output_limits/state_limits): "
                         "not exogenous");
  });
  return result;
}

Experiment read_sidecar(const std::filesystem::path& path) {
  const ExperimentFiles files = files_of(path);
  const std::string sidecar_text = read_json_file(files.json);
  Experiment e;
  std::vector<std::string> warnings;  // a sidecar alone has no CSV columns to warn about
  in_file(files.json, warnings, [&](std::vector<std::string>& w) {
    e = parse_sidecar(parse_sidecar_text(sidecar_text), w);
    e.validate_metadata();
  });
  return e;
}

void write_experiment(const Experiment& experiment, const std::filesystem::path& stem) {
  experiment.validate();
  const ExperimentFiles files = files_of(stem);
  std::string sidecar_text;
  try {
    sidecar_text = sidecar_json(experiment).dump(2) + "\n";
  } catch (const nlohmann::json::exception& e) {  // a string that is not valid UTF-8
    throw Error(std::string("cannot encode the sidecar of ") + files.json.string() + " as JSON: " + e.what());
  }
  const std::string csv_text = samples_csv(experiment);
  if (const auto dir = files.json.parent_path(); !dir.empty()) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error) throw Error("cannot create directory " + dir.string() + ": " + error.message());
  }
  write_files_atomically({{files.csv, csv_text}, {files.json, sidecar_text}});
}

}  // namespace ambid
