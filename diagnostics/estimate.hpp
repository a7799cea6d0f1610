#pragma once
// What diagnostics consumes: the physical parameters identified over one window of plant data,
// each with its one-sigma uncertainty, stamped with the window's time, plant and source.
#include <string>
#include <string_view>
#include <vector>

namespace ambid::diag {

// Where the data of a window came from (the plant source of architecture.md).
enum class Source { sim, replay, rig };

std::string_view to_string(Source source);
// Throws Error naming the text and the accepted names.
Source parse_source(std::string_view text);

struct ParameterEstimate {
  std::string parameter;  // physical parameter name: R1, R2, kw1, kw2, kr1, kr2, ks
  double value = 0.0;
  double sigma = 0.0;  // one standard deviation, same unit as value; 0: the identifier reports none
};

struct EstimateWindow {
  double time = 0.0;  // seconds, end of the window, on the clock the caller uses throughout
  std::string plant_id;
  Source source = Source::sim;
  std::vector<ParameterEstimate> estimates;

  // Throws Error when the time, a value or a sigma is not finite, a sigma is negative,
  // the plant id or a parameter name is empty, or a parameter appears twice.
  void validate() const;
};

}  // namespace ambid::diag
