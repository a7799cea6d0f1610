#include "diagnostics/estimate.hpp"

#include <cmath>
#include <set>
#include <string>

#include "core/error.hpp"

namespace ambid::diag {

std::string_view to_string(Source source) {
  switch (source) {
    case Source::sim:
      return "sim";
    case Source::replay:
      return "replay";
    case Source::rig:
      return "rig";
  }
  throw Error("unknown plant source value " + std::to_string(static_cast<int>(source)));
}

Source parse_source(std::string_view text) {
  for (Source s : {Source::sim, Source::replay, Source::rig})
    if (text == to_string(s)) return s;
  throw Error("unknown plant source '" + std::string(text) + "' (expected sim, replay or rig)");
}

void EstimateWindow::validate() const {
  const std::string where = "estimate window of plant '" + plant_id + "' at t=" + std::to_string(time);
  if (plant_id.empty()) throw Error("estimate window at t=" + std::to_string(time) + " has an empty plant id");
  if (!std::isfinite(time)) throw Error(where + ": time is not finite");
  std::set<std::string_view> seen;
  for (const ParameterEstimate& e : estimates) {
    if (e.parameter.empty()) throw Error(where + ": a parameter name is empty");
    if (!seen.insert(e.parameter).second) throw Error(where + ": parameter " + e.parameter + " appears twice");
    if (!std::isfinite(e.value))
      throw Error(where + ": " + e.parameter + " value is not finite (" + std::to_string(e.value) + ")");
    if (!(e.sigma >= 0.0) || !std::isfinite(e.sigma))
      throw Error(where + ": " + e.parameter + " sigma must be non-negative (0: not reported) and finite, got " +
                  std::to_string(e.sigma));
  }
}

}  // namespace ambid::diag
