#pragma once
// The data CSV of an experiment file (experiment-format.md): `t` then one column per signal.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/experiment.hpp"
#include "core/experiment_io.hpp"

namespace ambid {

// Fills e.t, e.y, e.u, e.r from the CSV file, taking the columns named by e's signal names and
// checking the sampling against e.sample_time. Ignored extra columns and resampling are
// reported in `warnings`. Errors name the line (1-based, the header is line 1) and the
// column; only errors of the file system name the file.
// Memory: the file is read line by line (file_lines.hpp) twice, the first time to size the
// arrays, which are then filled in place: 8 bytes x (1 + signals) per row and a buffer of at
// most one line (kMaxLineBytes), never the text (a file of N bytes holds at most N / (2 x
// (1 + signals)) rows, so at most 4 N bytes of samples). Resampling adds one copy of the samples.
void read_samples_csv(const std::filesystem::path& file, const ReadOptions& options, Experiment& e,
                      std::vector<std::string>& warnings);

// The CSV text of e's samples: header `t,<y names>,<u names>,<r names>`, shortest round-trip
// numbers, '\n' line ends.
std::string samples_csv(const Experiment& e);

}  // namespace ambid
