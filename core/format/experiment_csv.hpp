#pragma once
// The data CSV of an experiment file (experiment-format.md): `t` then one column per signal.
#include <string>
#include <string_view>
#include <vector>

#include "core/experiment.hpp"
#include "core/experiment_io.hpp"

namespace ambid {

// Fills e.t, e.y, e.u, e.r from CSV text, taking the columns named by e's signal names and
// checking the sampling against e.sample_time. Ignored extra columns and resampling are
// reported in `warnings`. Errors name the line (1-based, the header is line 1) and the
// column, not the file.
void parse_samples_csv(std::string_view text, const ReadOptions& options, Experiment& e,
                       std::vector<std::string>& warnings);

// The CSV text of e's samples: header `t,<y names>,<u names>,<r names>`, shortest round-trip
// numbers, '\n' line ends.
std::string samples_csv(const Experiment& e);

}  // namespace ambid
