#pragma once
// Import of records written by other tools (rig loggers, MATLAB, scripts) as a contract
// experiment (experiment-format.md): MAT v5 files (read by libmatio; one 2-D variable whose
// columns are signals, or one vector per signal) and CSV files with their own column names,
// units, scales and column order, with or without a time column. A mapping names the source
// of t and of every y, u and r signal; the plant description comes from a template sidecar or
// from options.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/experiment.hpp"

namespace ambid {

// Where one signal comes from and how it becomes SI: value = raw * scale * (unit's factor).
struct SignalSource {
  std::string name;    // the signal in the experiment (x, i1, u1...), "t" for time
  std::string source;  // CSV column, MAT variable (a vector), or MAT "VAR(:,K)": column K (1-based)
  std::string unit;    // unit as recorded (one of import_units()); empty: already SI
  double scale = 1.0;  // a further factor, e.g. a sensor's m/V
};

struct ImportMapping {
  std::optional<SignalSource> t;  // absent: no time column; the sample time must be given
  std::vector<SignalSource> y, u, r;
  double sample_time = 0.0;  // s; 0: not given here
};

// The units a mapping may name, as "unit (factor to SI unit)" for messages and help.
std::string import_units();
// The factor from `unit` to its SI unit; 1 for an empty unit. Throws Error for an unknown unit.
double unit_factor(const std::string& unit);

// "SOURCE[:UNIT][*SCALE]" for the signal `name`, e.g. "pos:mm", "A(:,2)*0.001", "I:mA*2".
// Throws Error naming the text and what is wrong (unknown unit, a scale that is no finite
// number, a time unit for a signal or a signal unit for t).
SignalSource parse_signal_source(const std::string& name, std::string_view spec);
// "NAME=SOURCE[:UNIT][*SCALE]", the form of --y/--u/--r and of the mapping file.
SignalSource parse_signal_mapping(std::string_view text);

// A mapping file: {"t": "SPEC", "y": ["NAME=SPEC", ...], "u": [...], "r": [...],
// "sample_time": s}; every key optional. Errors name the file and the key.
ImportMapping read_import_mapping(const std::filesystem::path& path);

struct ImportOptions {
  // The plant description (plant, signals, operating point, controller, sample time) of a
  // contract sidecar. Its y and u signals must all be mapped (any order); its r signals too,
  // unless reconstruct_r.
  std::optional<Experiment> template_sidecar;
  std::string plant_model;     // without a template: plant.model (parameters stay empty)
  std::string name;            // empty: the template's name, else the file's stem
  double sample_time = 0.0;    // s; 0: the mapping's, the template's, else the median step of t
  bool resample = false;       // non-uniform t: interpolate linearly onto the uniform grid
  double max_gap = 0.0;        // resampling refuses a step of t longer than this (s); 0: 10 sample times
  bool reconstruct_r = false;  // r = u - controller output (needs the template's controller)
};

struct ImportResult {
  Experiment experiment;  // passes Experiment::validate()
  std::string file_kind;  // "MAT v5" or "CSV"
  Eigen::Index rows = 0;  // rows (samples) read from the file, before any resampling
  // What was done, one line each: the source and conversion of every signal, the sample time
  // and where it came from, resampling, the operating point, reconstruction of r.
  std::vector<std::string> steps;
  // Per sample of the experiment: a controller clamp acted (core/controller_replay.hpp).
  std::vector<bool> clamped;
  Eigen::Index clamped_samples = 0;
};

// Reads `file` (MAT v5 when it starts with the MAT header text, else CSV with a header line)
// and builds the experiment. Throws Error whose message starts with the file's name and says
// what is wrong: a missing variable or column, signals of different lengths, a value that is
// NaN, infinite or no number, a time column that is not strictly increasing, non-uniform
// sampling without `resample`, a gap longer than max_gap, a mapping that does not cover the
// template's signals.
ImportResult import_experiment(const std::filesystem::path& file, const ImportMapping& mapping,
                               const ImportOptions& options);

}  // namespace ambid
