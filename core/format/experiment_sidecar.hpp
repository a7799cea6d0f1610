#pragma once
// The JSON sidecar of an experiment file (experiment-format.md) <-> Experiment metadata.
#include <map>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/experiment.hpp"

namespace ambid {

// The keys the format defines, per object: "" for the top level, then "plant", "signals",
// "controller". Any other key is unknown and lives in Experiment::extra.
const std::map<std::string, std::set<std::string>>& defined_sidecar_keys();

// The JSON value of sidecar text. Throws Error for malformed JSON (naming the parse
// position), a number beyond the range of double, or a key repeated within one object (which
// JSON parsers silently resolve in different ways).
nlohmann::json parse_sidecar_text(const std::string& text);

// An Experiment without samples, from a parsed sidecar. Checks that every required key is
// present with the right JSON type, then Experiment::validate_metadata(). Unknown keys go to
// Experiment::extra; operating_point entries that name no signal are kept and reported in
// `warnings`. Errors name the key path (`signals.u`, `controller.A[1][2]`), not the file.
Experiment parse_sidecar(const nlohmann::json& sidecar, std::vector<std::string>& warnings);

}  // namespace ambid
